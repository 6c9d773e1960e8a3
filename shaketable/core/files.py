"""Output files: a folder checked before the work starts, every file written atomically.

A command checks its output folder with :func:`prepare_output_folder` before it
computes anything (an existing file in the way, a path under a file, a folder it
may not write into: a clear error, no work lost). Every file is then written
through :func:`atomic_write`: into a temporary file beside it, renamed over the
target when complete, so a failure (a full disk, Ctrl-C) leaves the previous
file or none, never a truncated one.
"""

from __future__ import annotations

import contextlib
import errno
import math
import os
import secrets
import socket
import stat
import tempfile
from collections.abc import Callable, Mapping
from pathlib import Path

import numpy as np


class OutputPathError(ValueError):
    """An output path that cannot be used; the message names the option and the path."""


#: The folders :func:`prepare_output_folder` created in this process, in order (the
#: command line removes those still empty when it refuses an input late; a folder another
#: process made at the same time is never among them).
CREATED_FOLDERS: list[Path] = []


def prepare_output_folder(path, option: str = "--out") -> Path:
    """Create the output folder ``path`` (and its parents) or say why it cannot be.

    Parameters
    ----------
    path : str or Path
        The folder the results go to.
    option : str
        What the user called it (a CLI option or a parameter name), for the message.

    Returns
    -------
    Path
        The folder, existing and writable.

    Raises
    ------
    OutputPathError
        The path is an existing file, lies under a file, or cannot be created or
        written into.
    """
    folder = Path(path)
    if str(path).strip() == "":
        raise OutputPathError(f"{option}: the output folder is empty; give a folder name")
    try:
        _check_name_lengths(folder, option, path)
        return _prepare_folder(folder, option, path)
    except OSError as error:  # e.g. a name too long, found by a stat: before any work
        raise OutputPathError(f"{option} {str(path)!r}: cannot use this folder "
                              f"({error.strerror or error})") from None


#: Characters :func:`atomic_write` adds to a file's name for its temporary file.
_TEMPORARY_EXTRA = len(".") + len(".tmp-") + 8


def _check_name_lengths(path: Path, option: str, given, extra: int = 0) -> None:
    """Refuse a path whose name (or one of its folders' names) the file system cannot hold.

    ``extra`` characters are added to the last name (the atomic writer's temporary
    name); the limit is the file system's (``os.pathconf``), else 255.
    """
    def exists(candidate: Path) -> bool:
        try:
            return candidate.exists()
        except OSError:  # a name too long to even look up
            return False

    existing = next((parent for parent in [path, *path.parents] if exists(parent)), Path("."))
    try:
        name_max = os.pathconf(existing, "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):
        name_max = 255
    parts = path.parts
    for index, part in enumerate(parts):
        limit = name_max - (extra if index == len(parts) - 1 else 0)
        if len(os.fsencode(part)) > limit:
            raise OutputPathError(f"{option} {str(given)!r}: the name {part[:40]!r}... is "
                                  f"{len(os.fsencode(part))} bytes long; this file system "
                                  f"holds names of at most {limit} bytes here; give a "
                                  f"shorter name")


def _prepare_folder(folder: Path, option: str, path) -> Path:
    if folder.exists() and not folder.is_dir():
        raise OutputPathError(f"{option} {str(path)!r}: is an existing file, not a folder; "
                              f"give a folder name")
    for parent in folder.parents:
        if parent.exists():
            if not parent.is_dir():
                raise OutputPathError(f"{option} {str(path)!r}: {str(parent)!r} is a file, so "
                                      f"no folder can be made under it")
            break
    try:
        for level in [*reversed(folder.parents), folder]:
            try:   # one level at a time: the ones this process made are known
                level.mkdir()
            except FileExistsError:
                continue
            CREATED_FOLDERS.append(level.absolute())
    except OSError as error:
        raise OutputPathError(f"{option} {str(path)!r}: cannot create the folder "
                              f"({error.strerror or error})") from None
    try:  # the only reliable test of "may write here" (permissions, read-only mounts, ACLs)
        with tempfile.NamedTemporaryFile(dir=folder, prefix=".shaketable-write-test-"):
            pass
    except OSError as error:
        raise OutputPathError(f"{option} {str(path)!r}: cannot write into the folder "
                              f"({error.strerror or error})") from None
    return folder


def prepare_output_file(path, option: str = "--out", suffixes: tuple = ()) -> Path:
    """Check an output file's path before the work starts; create its folder.

    Parameters
    ----------
    path : str or Path
        The file to be written.
    option : str
        What the user called it, for the message.
    suffixes : tuple of str, optional
        Accepted suffixes (e.g. ``(".gif",)``); empty accepts any.

    Raises
    ------
    OutputPathError
        The path is an existing folder, has a suffix not accepted, or its folder
        cannot be created or written into.
    """
    file = Path(path)
    if str(path).strip() == "":
        raise OutputPathError(f"{option}: the output file name is empty")
    _check_name_lengths(file, option, path, extra=_TEMPORARY_EXTRA)
    if file.is_dir():
        raise OutputPathError(f"{option} {str(path)!r}: is an existing folder; give a file name")
    if suffixes and file.suffix.lower() not in suffixes:
        raise OutputPathError(f"{option} {str(path)!r}: the file must end in "
                              f"{' or '.join(suffixes)}")
    prepare_output_folder(file.parent if str(file.parent) else ".", option=f"{option} (its folder)")
    return file


def atomic_write(path, write: Callable[[Path], object]) -> Path:
    """Write a file through a temporary file in the same folder, then rename it.

    Parameters
    ----------
    path : str or Path
        The file to produce.
    write : callable
        ``write(temporary_path)`` writes the content; the temporary path keeps the
        target's suffix, so writers that choose a format from the suffix (matplotlib)
        work unchanged.

    Returns
    -------
    Path
        ``path``, complete. On any failure the temporary file is removed and the
        exception propagates: ``path`` keeps its previous content (or does not exist).
    """
    path = Path(path)
    try:
        temporary = _new_temporary(path)
    except OSError as error:
        raise OSError(error.errno, error.strerror or str(error), str(path)) from error
    try:
        write(temporary)
        os.replace(temporary, path)
    except OSError as error:  # a full disk, a quota: say which file (not its temporary)
        temporary.unlink(missing_ok=True)
        if error.filename is not None and str(error.filename) != str(temporary):
            raise
        raise OSError(error.errno, error.strerror or str(error), str(path)) from error
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise
    return path


#: The mark in the name of a temporary file of :func:`atomic_write`:
#: ``.<stem>.tmp-<random><suffix>`` beside its target (what a clean-up may remove).
TEMPORARY_MARK = ".tmp-"


def temporary_files(folder, stem: str = "*") -> list[Path]:
    """The temporary files :func:`atomic_write` left in ``folder`` (a kill, a failed unlink).

    Parameters
    ----------
    folder : Path
    stem : str
        The target's stem (a glob pattern), e.g. ``"part-*"``; default any.
    """
    return sorted(Path(folder).glob(f".{stem}{TEMPORARY_MARK}*"))


def _new_temporary(path: Path) -> Path:
    """A new empty file beside ``path``, with the mode the umask gives a normal file.

    Created with ``os.open(..., 0o666)`` so the kernel applies the process's umask
    (0644 under umask 022, 0640 under 027), as for a file written in place;
    ``tempfile.mkstemp`` would give 0600 whatever the umask, and the rename would
    keep that mode. Reading the umask (``os.umask``) would change it for a moment,
    which is not safe while other threads create files.
    """
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
    for _ in range(100):
        temporary = path.parent / f".{path.stem}{TEMPORARY_MARK}{secrets.token_hex(4)}{path.suffix}"
        try:
            os.close(os.open(temporary, flags, 0o666))
        except FileExistsError:
            continue
        return temporary
    raise FileExistsError(errno.EEXIST, "no free temporary file name", str(path.parent))


def read_utf8(path, what: str, error: type = ValueError) -> str:
    """The text of a UTF-8 input file, or ``error`` naming the file (and line, and byte).

    Parameters
    ----------
    path : Path
    what : str
        What the file is, for the message (``"scene"``, ``"sweep spec"``).
    error : type
        The exception class to raise (a ValueError subclass of the caller's layer).
    """
    path = Path(path)
    try:
        return path.read_text(encoding="utf-8")
    except OSError as problem:
        raise error(f"{path}: cannot read the {what} ({problem.strerror})") from None
    except UnicodeDecodeError as problem:
        line = path.read_bytes()[:problem.start].count(b"\n") + 1
        raise error(f"{path}, line {line}: not UTF-8 text (byte "
                    f"{problem.object[problem.start]:#04x}); save the {what} as UTF-8") from None


def folder_name_problem(name: str) -> str | None:
    """Why ``name`` cannot be used as one folder inside an output folder, or None.

    A scene's or sweep spec's ``name`` becomes the default output folder
    ``shaketable-out/<name>``: it must stay inside, so a name that is a path (a
    separator ``/`` or ``\\``, ``.`` or ``..``, an absolute path) or holds
    control characters is refused rather than sanitised -- the user sees which name
    to change instead of finding the results under another name.
    """
    if name in (".", ".."):
        return "is not a folder name"
    if "/" in name or "\\" in name:
        return "holds a path separator ('/' or '\\'); a name names one folder"
    if any(ord(character) < 32 or ord(character) == 127 for character in name):
        return "holds a control character"
    if len(name.encode("utf-8")) > 200:
        return "is longer than 200 bytes (too long for a folder name on most file systems)"
    return None


def json_ready(value):
    """A scalar as JSON can hold it: NaN and infinities as None, NumPy scalars as Python."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    return value


def json_ready_dict(data: Mapping) -> dict:
    """:func:`json_ready` applied to every value of a flat mapping (a run's summary)."""
    return {key: json_ready(value) for key, value in data.items()}


def write_text(path, text: str) -> Path:
    """Write a UTF-8 text file atomically (see :func:`atomic_write`)."""
    return atomic_write(path, lambda temporary: temporary.write_text(text, encoding="utf-8"))


def write_csv(path, frame, **options) -> Path:
    """Write a pandas DataFrame as CSV atomically (``index=False`` unless given)."""
    options.setdefault("index", False)
    return atomic_write(path, lambda temporary: frame.to_csv(temporary, **options))


def write_parquet(path, frame) -> Path:
    """Write a pandas DataFrame as Parquet atomically (needs pyarrow)."""
    return atomic_write(path, lambda temporary: frame.to_parquet(temporary, index=False))


#: The lock file of an output folder (see :func:`folder_lock`).
LOCK_NAME = ".shaketable.lock"


def open_in_place(path, what: str) -> int:
    """Open (or create) a file that must be written in place, never through a link.

    The one file the package opens for writing in place (an output folder's lock
    file, which must keep its identity for ``flock``) is opened with ``O_NOFOLLOW``,
    so a symbolic link planted under its name is refused rather than followed (which
    would create or truncate a file outside the folder), and is then checked to be a
    regular file with one name (a hard link planted there would be truncated
    through). Every other file is written by :func:`atomic_write`, whose rename
    replaces a link itself, never its target.

    Returns
    -------
    int
        An open file descriptor (read and write).

    Raises
    ------
    OutputPathError
        ``path`` is a symbolic link, not a regular file, or has another name.
    """
    flags = (os.O_RDWR | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0)
             | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_NONBLOCK", 0))
    try:
        handle = os.open(path, flags, 0o666)
    except OSError as error:
        if error.errno in (errno.ELOOP, errno.EMLINK) or Path(path).is_symlink():
            raise OutputPathError(f"{path}: {what} is a symbolic link; shaketable never writes "
                                  "through a link: remove it") from None
        raise
    status = os.fstat(handle)
    if not stat.S_ISREG(status.st_mode) or status.st_nlink != 1:
        os.close(handle)
        why = "not a regular file" if not stat.S_ISREG(status.st_mode) else \
            f"a file with {status.st_nlink} names (a hard link)"
        raise OutputPathError(f"{path}: {what} is {why}; shaketable never writes through a "
                              "link: remove it")
    return handle


def subfolder(parent, name: str, option: str = "--out") -> Path:
    """The folder ``parent/name``, created if missing, refused if it is a link.

    Every folder the package makes inside an output folder goes through here: a
    symbolic link planted under its name (pointing outside the output folder) is
    refused, so nothing is written outside the output folder.

    Raises
    ------
    OutputPathError
        ``parent/name`` is a symbolic link or a file, or cannot be created.
    """
    folder = Path(parent) / name
    if folder.is_symlink():
        raise OutputPathError(f"{option} {str(parent)!r}: {str(folder)!r} is a symbolic link; "
                              "shaketable never writes through a link: remove it")
    return prepare_output_folder(folder, option)


def copy_file(source, target) -> Path:
    """Copy ``source`` to ``target`` atomically (a link at ``target`` is replaced, not
    followed)."""
    import shutil

    return atomic_write(target, lambda temporary: shutil.copyfile(source, temporary))


class FolderBusyError(OutputPathError):
    """Another process holds the output folder's lock; the message names it and the folder."""


@contextlib.contextmanager
def folder_lock(folder, what: str = "output folder"):
    """Hold the lock of an output folder for the duration of a ``with`` block.

    The lock is an advisory ``flock`` on ``folder/.shaketable.lock``, which also
    holds the owner's pid and host for the message. The kernel releases it when its
    process ends, however it ends (``kill -9``, a crash): a lock left by a dead
    process is simply taken over, never stale. Two processes writing one sweep
    folder would otherwise rely on timing (both write part files, both clean up
    temporary files, both join the table); the second one now refuses.

    Parameters
    ----------
    folder : Path
        An existing folder.
    what : str
        What the folder is, for the message.

    Raises
    ------
    FolderBusyError
        Another process holds the lock (the message names the folder and its pid).

    Notes
    -----
    Where ``fcntl`` is missing (Windows) the block runs without a lock.
    """
    try:
        import fcntl
    except ImportError:  # pragma: no cover - Windows: no advisory locks here
        yield
        return
    path = Path(folder) / LOCK_NAME
    handle = open_in_place(path, "the lock file of the " + what)
    try:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as error:
            if error.errno not in (errno.EAGAIN, errno.EACCES, errno.EWOULDBLOCK):
                raise
            owner = os.pread(handle, 200, 0).decode("utf-8", "replace").split()
            who = (f"pid {owner[0]}" + (f" on {owner[1]}" if len(owner) > 1 else "")
                   if owner else "another process")
            raise FolderBusyError(f"{folder}: this {what} is in use by another shaketable "
                                  f"process ({who}, lock file {path}); wait for it to "
                                  f"finish, or choose another output folder") from None
        os.ftruncate(handle, 0)   # our own file: open_in_place refused a link
        os.pwrite(handle, f"{os.getpid()} {socket.gethostname()}\n".encode(), 0)
        try:
            yield
        finally:
            os.ftruncate(handle, 0)
            fcntl.flock(handle, fcntl.LOCK_UN)
    finally:
        os.close(handle)


def write_gallery(out: str | os.PathLike[str]) -> Path:
    """Write ``out/gallery.md``: every figure (PNG) under ``out``, one heading per scene.

    The page a reader scans to look at every figure of a reproduction at once
    (``shaketable reproduce --all --out FOLDER`` writes it beside report.md).
    """
    out = Path(out)
    lines = ["# Gallery: every figure of the reproduction", "",
             "Written by `shaketable reproduce --all --out FOLDER` beside `report.md`; "
             "each figure is discussed in the report's section of the same scene.", ""]
    for folder in sorted((path for path in out.iterdir() if path.is_dir()),
                         key=lambda path: [int(part) if part.isdigit() else part
                                           for part in path.name.replace("-", " ").split()]):
        figures = sorted(folder.glob("*.png"))
        if not figures:
            continue
        lines += [f"## `{folder.name}`", ""]
        lines += [f"![{folder.name}/{figure.name}]({folder.name}/{figure.name})"
                  for figure in figures]
        lines.append("")
    return write_text(out / "gallery.md", "\n".join(lines))
