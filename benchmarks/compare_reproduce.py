"""Compare two ``shaketable reproduce --all --out DIR`` folders file by file.

What a speed change of the reproduction must keep: every CSV and JSON identical except
run-time columns and keys (``run time [s]`` and the like), every other file (PNG,
Markdown) byte-identical, and the same set of files. Prints each difference and exits 1
if there is one.

    python3 benchmarks/compare_reproduce.py BEFORE_DIR AFTER_DIR [SCENE ...]
"""

from __future__ import annotations

import csv
import io
import json
import re
import sys
from pathlib import Path

#: Column names and JSON keys that hold run times (they differ from run to run).
RUN_TIME = re.compile(r"run[ _-]?time|elapsed|wall|\bcpu\b", re.IGNORECASE)


def _json(value):
    if isinstance(value, dict):
        return {key: _json(item) for key, item in value.items() if not RUN_TIME.search(key)}
    if isinstance(value, list):
        return [_json(item) for item in value]
    return value


def _csv(path: Path) -> tuple[list, list]:
    rows = list(csv.reader(io.StringIO(path.read_text(encoding="utf-8"))))
    if not rows:
        return rows, []
    keep = [i for i, name in enumerate(rows[0]) if not RUN_TIME.search(name)]
    dropped = [name for i, name in enumerate(rows[0]) if i not in keep]
    return [[row[i] for i in keep if i < len(row)] for row in rows], dropped


def compare(before: Path, after: Path, scenes=()) -> int:
    def files(root):
        found = {path.relative_to(root) for path in root.rglob("*") if path.is_file()}
        return {path for path in found if not scenes or path.parts[0] in scenes}

    left, right = files(before), files(after)
    differences, ignored = 0, set()
    for relative in sorted(left ^ right):
        print("only in", before if relative in left else after, relative)
        differences += 1
    for relative in sorted(left & right):
        a, b = before / relative, after / relative
        if relative.suffix == ".csv":
            (rows_a, dropped), (rows_b, _) = _csv(a), _csv(b)
            ignored.update(dropped)
            same = rows_a == rows_b
        elif relative.suffix == ".json":
            same = _json(json.loads(a.read_text())) == _json(json.loads(b.read_text()))
        else:
            same = a.read_bytes() == b.read_bytes()
        if not same:
            print("differs:", relative)
            differences += 1
    print(f"{len(left & right)} files compared, {differences} differences; "
          f"run-time columns ignored: {sorted(ignored)}")
    return differences


if __name__ == "__main__":
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    raise SystemExit(1 if compare(Path(sys.argv[1]), Path(sys.argv[2]), set(sys.argv[3:]))
                     else 0)
