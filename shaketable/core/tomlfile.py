"""TOML input files, read once for every parser: the text, its data, and key lines.

The scene files, the sweep specs and the object files of ``shaketable assess`` are TOML.
:func:`read_toml` reads one (UTF-8, valid TOML, not nested past the parser's recursion)
into its data and its text, :func:`key_line` finds the line where a dotted key is written
(for error messages that name file, key and line); the check of a section's keys is
:func:`shaketable.core.validation.unknown_keys`. This is the one module outside
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

__all__ = ["key_line", "read_toml", "tomllib"]

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

