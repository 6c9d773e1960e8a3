"""The sweep's store: Parquet (or CSV) parts written atomically, found again on resume,
and read back as one table.
"""

from __future__ import annotations

import importlib.util
import json
import warnings
from pathlib import Path

import numpy as np

from shaketable.core.files import write_csv, write_parquet, write_text
from shaketable.sweeps.base import SweepError

#: Version of the result layout, written in the manifest (2: the intensity-measure
#: columns; 3: the ``block`` column in the user's units, ``2 x 0.5 m``, not always inches).
#: A folder of version 2 is migrated when resumed (:func:`migrate_parts`); one of version 1
#: is not resumed: its rows lack the measures.
FORMAT_VERSION = 3

#: The earlier versions a resume brings up to :data:`FORMAT_VERSION`.
MIGRATED_VERSIONS = (2,)


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


def migrate_parts(spec, out: Path, fmt: str, version: int, label) -> int:
    """Bring the parts of a sweep folder of layout ``version`` to :data:`FORMAT_VERSION`;
    the number of parts rewritten.

    Version 2 differs from 3 in the ``block`` column alone: it held every block in inches
    (``30 x 6 in``, ``Block.describe(unit="in")``), version 3 in the user's units
    (``Block.describe()``). Each part's ``block`` is written again from its ``block_index``
    (``label(spec.blocks[index])``), atomically; the other columns are kept as they are,
    so a resumed sweep's table equals the table of a sweep run whole by this version.
    A joined ``results.*`` of the old layout is removed (the parts are joined again at the
    end of the resume).
    """
    if version not in MIGRATED_VERSIONS:
        raise SweepError(f"{out}: a sweep folder of layout version {version!r} cannot be "
                         f"brought to version {FORMAT_VERSION}")
    suffix = "parquet" if fmt == "parquet" else "csv"
    rewritten = 0
    for chunk in range(spec.n_chunks):
        path = part_path(out, chunk, fmt)
        if not path.exists():
            continue
        try:
            frame = _read(path, fmt)
            labels = [label(spec.blocks[int(index)]) for index in frame["block_index"]]
        except Exception:  # unreadable or not this spec's: recomputed on resume
            path.unlink()
            continue
        if list(frame["block"]) != labels:
            frame["block"] = labels
            write_atomic(frame, path, fmt)
            rewritten += 1
    (out / f"results.{suffix}").unlink(missing_ok=True)
    return rewritten


def write_text_atomic(path: Path, text: str) -> None:
    """Write the manifest: temporary file, then rename."""
    write_text(path, text)


def read_results(out, *, fmt: str | None = None, parts_only: bool = False,
                 n_chunks: int | None = None):
    """The result table of a sweep folder: ``results.*`` or, if absent, the parts so far.

    Rows are in run order. A partial sweep gives the finished chunks only. Only the
    parts of the sweep's own chunks are joined (``part-000000`` to the manifest's
    ``n_chunks - 1``): any other file named like a part (a copy, a part of a larger
    sweep) is left out, with a warning naming it.

    Parameters
    ----------
    out : path
        The sweep folder.
    fmt : {"parquet", "csv"}, optional
        Default: the manifest's.
    parts_only : bool
        Join the parts even when ``results.*`` exists.
    n_chunks : int, optional
        The sweep's number of chunks; default the manifest's.
    """
    import pandas as pd

    out = Path(out)
    if fmt is None or n_chunks is None:
        manifest = read_manifest(out)
        fmt = manifest["format"] if fmt is None else fmt
        n_chunks = manifest["n_chunks"] if n_chunks is None else n_chunks
    suffix = "parquet" if fmt == "parquet" else "csv"
    final = out / f"results.{suffix}"
    if final.exists() and not parts_only:
        return _read(final, fmt)
    expected = {part_path(out, chunk, fmt).name for chunk in range(int(n_chunks))}
    found = sorted((out / "parts").glob(f"part-*.{suffix}"))
    if message := stray_parts_message(out, fmt, int(n_chunks)):
        warnings.warn(message, SweepStoreWarning, stacklevel=2)
    parts = [path for path in found if path.name in expected]
    if not parts:
        raise SweepError(f"{out}: no finished chunks yet")
    table = pd.concat([_read(path, fmt) for path in parts], ignore_index=True)
    return table.sort_values("run", kind="stable").reset_index(drop=True)


def stray_parts_message(out: Path, fmt: str, n_chunks: int) -> str | None:
    """What is left out of the table: files named like parts that are not the sweep's."""
    suffix = "parquet" if fmt == "parquet" else "csv"
    expected = {part_path(out, chunk, fmt).name for chunk in range(n_chunks)}
    stray = [path.name for path in sorted((out / "parts").glob(f"part-*.{suffix}"))
             if path.name not in expected]
    if not stray:
        return None
    return (f"{out / 'parts'}: left out {len(stray)} file(s) that are not parts of this "
            f"sweep's {n_chunks} chunk(s): {', '.join(stray[:5])}"
            f"{' ...' if len(stray) > 5 else ''}")


class SweepStoreWarning(UserWarning):
    """Something in a sweep folder that is not the sweep's was left out."""


def read_manifest(out) -> dict:
    """The manifest of the sweep folder ``out``, or a SweepError naming it."""
    path = Path(out) / "manifest.json"
    try:
        manifest = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as error:
        raise SweepError(f"{path}: unreadable manifest ({error})") from None
    if not isinstance(manifest, dict) or not {"format", "n_chunks"} <= manifest.keys():
        raise SweepError(f"{path}: not a sweep manifest (no 'format' and 'n_chunks')")
    return manifest
