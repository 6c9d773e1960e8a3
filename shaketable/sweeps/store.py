"""The sweep's store: Parquet (or CSV) parts written atomically, found again on resume,
and read back as one table.
"""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import numpy as np

from shaketable.core.files import write_csv, write_parquet, write_text
from shaketable.sweeps.spec import SweepError

#: Version of the result layout, written in the manifest (2: the intensity-measure columns
#: of issue 29; a folder of version 1 is not resumed, its rows lack them).
FORMAT_VERSION = 2


# --------------------------------------------------------------------------- execution
def parquet_available() -> bool:
    """True when pyarrow (the ``parquet`` extra) is installed."""
    return importlib.util.find_spec("pyarrow") is not None


def write_atomic(frame, path: Path, fmt: str) -> None:
    """Write a part or the result table: temporary file, then rename (nothing truncated)."""
    if fmt == "parquet":
        write_parquet(path, frame)
    else:
        write_csv(path, frame)


def _read(path: Path, fmt: str):
    import pandas as pd

    if fmt == "parquet":
        return pd.read_parquet(path)
    frame = pd.read_csv(path)
    for column in ("seed",):
        if column in frame:
            frame[column] = frame[column].astype("Int64")
    return frame


def part_path(out: Path, chunk: int, fmt: str) -> Path:
    return out / "parts" / f"part-{chunk:06d}.{'parquet' if fmt == 'parquet' else 'csv'}"


def finished_chunks(spec, out: Path, fmt: str) -> set:
    """Chunks whose part file is on disk and holds exactly that chunk's runs."""
    done = set()
    for chunk in range(spec.n_chunks):
        path = part_path(out, chunk, fmt)
        if not path.exists():
            continue
        start = chunk * spec.chunk_size
        expected = np.arange(start, min(start + spec.chunk_size, spec.n_runs))
        try:
            runs = _read(path, fmt)["run"].to_numpy()
        except Exception:  # unreadable: recompute it (atomic writes make this unlikely)
            path.unlink()
            continue
        if np.array_equal(runs, expected):
            done.add(chunk)
        else:
            path.unlink()
    return done


def write_text_atomic(path: Path, text: str) -> None:
    """Write the manifest: temporary file, then rename."""
    write_text(path, text)


def read_results(out, *, fmt: str | None = None, parts_only: bool = False):
    """The result table of a sweep folder: ``results.*`` or, if absent, the parts so far.

    Rows are in run order. A partial sweep gives the finished chunks only.
    """
    import pandas as pd

    out = Path(out)
    if fmt is None:
        fmt = json.loads((out / "manifest.json").read_text())["format"]
    final = out / f"results.{'parquet' if fmt == 'parquet' else 'csv'}"
    if final.exists() and not parts_only:
        return _read(final, fmt)
    parts = sorted((out / "parts").glob(f"part-*.{'parquet' if fmt == 'parquet' else 'csv'}"))
    if not parts:
        raise SweepError(f"{out}: no finished chunks yet")
    table = pd.concat([_read(path, fmt) for path in parts], ignore_index=True)
    return table.sort_values("run", kind="stable").reset_index(drop=True)
