"""Record suites of a sweep spec: ``[[records]] folder = ...``, every file of a
folder (``pattern``, default NGA-West2 ``*.AT2``) as one record, labelled by its stem.
Parsed for :mod:`shaketable.sweeps.spec`.
"""

from __future__ import annotations

import os
from pathlib import Path

from shaketable.sweeps.base import RecordSpec, SweepError


def suite_records(entry: dict, where: str, key: str, directory: Path) -> list:
    """``folder = ...`` of a ``[[records]]`` entry: one file record per matching file, in
    name order (:class:`~shaketable.sweeps.spec.RecordSpec`, ``kind="file"``, its
    ``suite`` the entry's ``suite`` or the folder's name); SweepError naming ``key``."""
    folder = entry["folder"]
    pattern = entry.get("pattern", "*.AT2")
    for name in ("folder", "pattern"):
        if not isinstance(entry.get(name, pattern), str) or not entry.get(name, pattern):
            raise SweepError(f"{where}: {key}.{name} must be a non-empty string")
    path = Path(folder)
    path = path if path.is_absolute() else (directory / path)
    if not path.is_dir():
        raise SweepError(f"{where}: {key}.folder: no such folder {str(path)!r}")
    matched = sorted(path.glob(pattern))
    for candidate in matched:   # a link loop, a dangling link, a folder: never dropped silently
        try:
            regular = candidate.is_file()
        except OSError:
            regular = False
        if not regular and not candidate.is_dir():
            raise SweepError(f"{where}: {key}.folder: {str(candidate)!r} matches {pattern!r} "
                             "but is not a readable file (a broken or looping link?); remove "
                             "it or narrow the pattern")
        if regular and not os.access(candidate, os.R_OK):
            raise SweepError(f"{where}: {key}.folder: {str(candidate)!r} cannot be read "
                             "(permission denied)")
    files = [candidate for candidate in matched if candidate.is_file()]
    if not files:
        raise SweepError(f"{where}: {key}.folder: no file matching {pattern!r} in "
                         f"{str(path)!r}")
    suite = entry.get("suite", path.name)
    if not isinstance(suite, str) or not suite:
        raise SweepError(f"{where}: {key}.suite must be a non-empty string")
    options = (("units", str(entry["units"])),) if "units" in entry else ()
    return [RecordSpec("file", file.stem, file=str(file.resolve()), options=options,
                       suite=suite) for file in files]
