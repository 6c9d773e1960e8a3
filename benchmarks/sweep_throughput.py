"""Throughput of ``shaketable sweep``: 10,000 runs of 30 s records on 2 cores.

The target: at most 60 s. The sweep (a spec built below) is 100 blocks
(width 0.5-5 ft x H/B 1.5-8) x 5 motions of 30 s at 100 Hz (Pacoima Dam S16E and
S74W with their vertical, cut to 30 s; three olive-view SUBSTITUTE realisations)
x 4 scale factors (0.25-1.0) x 5 COR (0.8-1.0) = 10,000 runs, run by
:func:`shaketable.sweeps.execute.run_sweep` exactly as ``shaketable sweep`` does
(chunks of 500, each written to its own Parquet part, then joined), after one
small warm-up sweep that loads the compiled code.

Run:  python benchmarks/sweep_throughput.py [--threads 2] [--out DIR]
It prints the wall time, runs per second, and the same for the bare batch
(:func:`shaketable.models.rocking.batch.simulate_cases` on the same runs, no I/O).
"""

from __future__ import annotations

import argparse
import os
import platform
import tempfile
import time
from pathlib import Path

SPEC = """
name = "throughput"
seed = 1
[blocks]
width = ["0.5 ft", "1 ft", "1.5 ft", "2 ft", "2.5 ft", "3 ft", "3.5 ft", "4 ft", "4.5 ft", "5 ft"]
aspect = [1.5, 2, 2.5, 3, 3.5, 4, 5, 6, 7, 8]
[rocking]
cor = [0.8, 0.85, 0.9, 0.95, 1.0]
duration = "30 s"
[[records]]
name = "pacoima-dam-s16e"
[[records]]
name = "pacoima-dam-s74w"
[[records]]
preset = "olive-view"
seeds = 3
[intensity]
scale = [0.25, 0.5, 0.75, 1.0]
[run]
chunk_size = 500
"""


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--out", default=None, help="keep the sweep folder here")
    args = parser.parse_args(argv)

    from shaketable.models.rocking.batch import simulate_cases
    from shaketable.sweeps import execute, spec

    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(args.out) if args.out else Path(scratch)
        spec_path = folder / "throughput.toml"
        folder.mkdir(parents=True, exist_ok=True)
        spec_path.write_text(SPEC)
        spec = spec.load_spec(spec_path)
        assert spec.n_runs == 10_000, spec.n_runs

        # warm-up: compiled code from the cache, records read, motions generated
        began = time.perf_counter()
        execute.run_sweep(spec.spec_from_dict({**spec.raw, "name": "warm-up",
                                              "blocks": {"sizes": ["30x6in"]},
                                              "rocking": {"cor": 0.9, "duration": "2 s"}},
                                             where="warm-up"),
                        folder / "warm-up", workers=args.threads, progress=False)
        warm_up = time.perf_counter() - began

        began = time.perf_counter()
        outcome = execute.run_sweep(spec, folder / "sweep", workers=args.threads, progress=False)
        seconds = time.perf_counter() - began
        table = outcome.table
        assert outcome.complete and len(table) == 10_000

        # the same runs through the bare batch (no chunking, no I/O)
        from shaketable.models.rocking.batch import Case
        cases = []
        for k in range(spec.n_chunks):
            inputs = execute.runs_table(spec, k * spec.chunk_size, (k + 1) * spec.chunk_size)
            for row in inputs.itertuples(index=False):
                seed = None if row.seed is None or str(row.seed) == "<NA>" else int(row.seed)
                motion, factor = execute.build_motion(spec, row.record_index, seed,
                                                    row.level_index)
                cases.append(Case(spec.blocks[row.block_index], motion, row[-1], scale=factor))
        began = time.perf_counter()
        bare = simulate_cases(cases, threads=args.threads, duration=spec.duration)
        batch_seconds = time.perf_counter() - began
        same = (bare["max_abs_theta [rad]"].to_numpy() == table["max_abs_theta [rad]"].to_numpy())

    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs "
          f"visible, threads used: {args.threads}")
    print(f"warm-up sweep (loads the compiled code): {warm_up:.1f} s")
    print(f"shaketable sweep, 10,000 runs of 30 s: {seconds:.1f} s "
          f"({10_000 / seconds:.0f} runs/s, {1e3 * seconds * args.threads / 10_000:.2f} "
          f"core-ms per run); target <= 60 s")
    print(f"bare batch, same runs: {batch_seconds:.1f} s ({10_000 / batch_seconds:.0f} runs/s); "
          f"identical max |theta| in {int(same.sum())} of 10000 rows")
    print(f"outcomes: {int(table['overturned'].sum())} overturned, "
          f"{int(table['airborne'].sum())} airborne, "
          f"{int((table['max_theta_ratio [-]'] == 0).sum())} never rocked; "
          f"{int(table['solver steps'].sum())} steps in total")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
