"""Bounds of a sweep's grid: what would exhaust memory is refused when the spec is read,
before any file or chunk, naming the key to change and the limit."""

from __future__ import annotations

from shaketable.sweeps.base import SweepError

#: Most chunks of one sweep (the resume bookkeeping holds one entry per chunk) and most
#: distinct motions (records x seeds x pitch phases, each held as a row of the grid).
MAX_CHUNKS = 1_000_000
MAX_VARIANTS = 1_000_000
MAX_CHUNK_SIZE = 100_000


def check_grid_size(spec, where: str) -> None:
    """Refuse a grid whose bookkeeping would exhaust memory, naming the limit and the key."""
    phases = 1 if spec.pitch is None else len(spec.pitch.phases)
    variants = sum(len(record.seeds) for record in spec.records) * phases
    if variants > MAX_VARIANTS:
        raise SweepError(f"{where}: the grid has {variants:,} distinct motions (records x "
                         f"seeds x pitch phases); at most {MAX_VARIANTS:,}: fewer "
                         "[[records]] seeds or pitch phases")
    if spec.n_chunks > MAX_CHUNKS:
        need = -(-spec.n_runs // MAX_CHUNKS)
        raise SweepError(f"{where}: {spec.n_runs:,} runs in chunks of {spec.chunk_size} make "
                         f"{spec.n_chunks:,} chunks; at most {MAX_CHUNKS:,}: set run.chunk_size "
                         f"to {need:,} or more (or make the grid smaller)")
