"""TOML input files, read once for every parser: the text, its data, and key lines.

The scene files, the sweep specs and the object files of ``shaketable assess`` are TOML.
:func:`read_toml` reads one (UTF-8, valid TOML, not nested past the parser's recursion)
into its data and its text, :func:`key_line` finds the line where a dotted key is written
(for error messages that name file, key and line) and :func:`with_line` adds that line
to a message; the check of a section's keys is
:func:`shaketable.core.validation.check_keys`. This is the one module outside
``scenes/`` and ``sweeps/`` that imports the TOML parser.
"""

from __future__ import annotations

import re
from pathlib import Path

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # Python 3.10: the same parser, packaged as tomli
    import tomli as tomllib  # type: ignore[no-redef]

from shaketable.core.files import read_utf8

__all__ = ["key_line", "read_toml", "tomllib", "with_line"]

_HEADER = re.compile(r"^\s*\[\[?\s*([\w.\"' -]+?)\s*\]\]?\s*(?:#.*)?$")
_ASSIGNMENT = re.compile(r"^\s*([\w.\"' -]+?)\s*=")


def read_toml(path: str | Path, what: str, error: type = ValueError) -> tuple[dict, str]:
    """The data and the text of the TOML file ``path``.

    Parameters
    ----------
    path : str or Path
    what : str
        What the file is, for the messages (``"scene"``, ``"sweep spec"``).
    error : type
        The exception class to raise (a ValueError subclass of the caller's layer).

    Raises
    ------
    error
        Naming the file: unreadable, not UTF-8 (with its line), not valid TOML (with the
        parser's line and column), or nested too deeply for the parser.
    """
    path = Path(path)
    text = read_utf8(path, what, error)
    try:
        return tomllib.loads(text), text
    except tomllib.TOMLDecodeError as problem:
        raise error(f"{path}: not valid TOML: {problem}") from None
    except RecursionError:  # an array nested thousands deep: the parser's recursion
        article = "an" if what[:1] in "aeiou" else "a"
        raise error(f"{path}: arrays or tables nested too deeply to read ({article} {what} "
                    f"needs a few levels)") from None


def key_line(text: str, path: list) -> int | None:
    """Line number (from 1) of the dotted key ``path`` in TOML ``text``, or of its longest
    written prefix (a section header, an inline table); ``None`` when nothing of it is written."""
    best, best_depth = None, 0
    section: list = []
    for number, line in enumerate(text.splitlines(), start=1):
        header = _HEADER.match(line)
        if header:
            section = [part.strip().strip("\"'") for part in header.group(1).split(".")]
            keys = section
        else:
            assignment = _ASSIGNMENT.match(line)
            if not assignment:
                continue
            keys = section + [part.strip().strip("\"'")
                              for part in assignment.group(1).split(".")]
        depth = 0
        while depth < min(len(keys), len(path)) and keys[depth] == path[depth]:
            depth += 1
        if depth == len(keys) and depth > best_depth:  # this line writes a prefix of path
            best, best_depth = number, depth
    return best



def with_line(message: str, where: str, text: str, sections, *, at_start: bool = False) -> str:
    """``message`` (``"WHERE: rocking.cor ..."``) with the line of the key it names in ``text``.

    ``"scene.toml: rocking.cor must be ..., got 1.5"`` becomes ``"scene.toml: rocking.cor
    must be ..., got 1.5 (line 9)"``: the line where the key (or, failing that, its
    section) is written. The key is found as ``unknown key 'k' in [section``, ``[section]``
    or ``section.key``, for the ``sections`` given (the top-level tables of the file). The
    line goes at the end so that the message still begins with the file and the key. A
    message naming no such key, or a key not written in ``text``, is returned as it is.

    Parameters
    ----------
    message, where, text : str
        The message, the file it begins with, the file's TOML text.
    sections : iterable of str
        The sections whose keys are looked for.
    at_start : bool
        Only a key right after ``"WHERE: "`` (else the first anywhere in the message).
    """
    prefix = f"{where}: "
    if not message.startswith(prefix):
        return message
    names = "|".join(re.escape(name) for name in sorted(sections, key=len, reverse=True))
    pattern = re.compile(rf"unknown key '([\w-]+)' in \[((?:{names})(?:\.[\w-]+)*)|"
                         rf"\[((?:{names})(?:\.[\w-]+)*)\]|\b((?:{names})(?:\.[\w-]+)+)")
    rest = message[len(prefix):]
    top = re.compile(r"unknown key '([\w-]+)' in \[top level")   # a misspelt section
    match = top.match(rest) if at_start else top.search(rest)
    if match is not None:
        line = key_line(text, [match.group(1)])
        return message if line is None else f"{message} (line {line})"
    match = pattern.match(rest) if at_start else pattern.search(rest)
    if match is None:
        return message
    unknown, section, header, dotted = match.groups()
    path = f"{section}.{unknown}" if unknown else (header or dotted)
    line = key_line(text, path.split("."))
    return message if line is None else f"{message} (line {line})"
