"""Timing of a sweep with ``[ensemble]``: the Pacoima Dam cells of Tables 4.2
and 4.3 (12 blocks x S16E, S74W x COR 1.0, 0.90 = 48 cells) x 200 members each.

Run: PYTHONPATH=. python benchmarks/sweep_ensemble_speed.py [--threads 2]
(best of ``REPEATS`` after one warm-up sweep that loads the compiled code; each sweep
is written to a fresh folder exactly as ``shaketable sweep`` does). Results in
benchmarks/RESULTS.md.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from shaketable.sweeps import load_spec, run_sweep

REPEATS = 3

SPEC = """
name = "tables-4-2-4-3-pacoima-ensembles"
[blocks]
sizes = ["2x1ft", "3x1ft", "4x1ft", "5x1ft", "4x2ft", "6x2ft", "8x2ft", "10x2ft",
         "6x3ft", "9x3ft", "12x3ft", "15x3ft"]
[rocking]
cor = [1.0, 0.9]
[[records]]
name = "pacoima-dam-s16e"
[[records]]
name = "pacoima-dam-s74w"
[ensemble]
members = 200
[run]
chunk_size = 48
"""


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "spec.toml"
        path.write_text(SPEC)
        spec = load_spec(path)
        run_sweep(spec, Path(folder) / "warm", workers=args.threads, progress=False,
                  max_chunks=0)
        times = []
        for k in range(REPEATS + 1):
            start = time.perf_counter()
            outcome = run_sweep(spec, Path(folder) / f"run{k}", workers=args.threads,
                                progress=False)
            times.append(time.perf_counter() - start)
        table = outcome.table
    times = times[1:]          # the first full run compiles what max_chunks=0 did not load
    print(f"{spec.n_runs} cells x {spec.ensemble['members']} members on {args.threads} "
          f"thread(s): best {min(times):.2f} s of {REPEATS}")
    print(f"{int((table['mark'] == 'fragile').sum())} fragile cells of {len(table)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
