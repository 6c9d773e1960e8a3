"""10 million samples through the command line against the Python API.

Writes a one-column text record of ``--samples`` accelerations (default 10 million,
dt 0.005 s: 14 h of a 0.08 g sine plus noise, below the 30x6 in block's rocking
threshold tan(alpha) = 0.2 g most of the time), then times, each once:

* API: ``shaketable.simulate`` on the motion already in memory (the engine alone);
* API + read: ``records.read`` of the text file, then ``simulate``;
* CLI: ``shaketable simulate --record big.txt --units g --dt 0.005`` in a fresh
  process (Python start, imports, reading, the run, summary, figure and the
  ``--history`` chosen; default ``auto``, which is ``peaks`` beyond 1e6 samples).

and prints the times and the ratio CLI / API (goal: within 3x).

    python benchmarks/cli_large_record.py [--samples N] [--history auto|full|peaks|none]
                                          [--folder DIR]

The engine is compiled (numba cache) before the timings. The machine is shared:
run it alone, once, and read the numbers as such.

Measured (the shared 2-core VM, nice 5, block at rest; five runs at load
averages 3 to 8): CLI (default --history auto = peaks) 7.7 to 19.9 s, against the
API's simulate alone 1.9 to 6.7 s (CLI / API 2.9 to 4.2) and the API's read +
simulate 4.8 to 17.3 s (CLI / that 1.1 to 1.9). Before: about 90 s (79 s reading the
text line by line, then a 350 MB history and a figure of 10 million points). What the
CLI adds to the engine: Python and the imports (~1 s), reading (~1.9 s), building the
Motion (0.8 s), the figure (1.4 s, drawn from the envelope). With --history full the
411 MB CSV alone takes about 2 minutes (pandas' to_csv): hence the peaks default.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np


def write_record(path: Path, samples: int) -> None:
    """A one-column record [g] (6 decimals), written in slices to bound memory."""
    rng = np.random.default_rng(1)
    with open(path, "w", encoding="utf-8") as stream:
        for start in range(0, samples, 1_000_000):
            t = np.arange(start, min(start + 1_000_000, samples)) * 0.005
            values = 0.08 * np.sin(2 * np.pi * 1.3 * t) + 0.02 * rng.standard_normal(t.size)
            stream.write("\n".join(f"{value:.6f}" for value in values) + "\n")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=10_000_000)
    parser.add_argument("--history", default="auto", choices=("auto", "full", "peaks", "none"))
    parser.add_argument("--folder", help="where to write the record (default a temporary one)")
    args = parser.parse_args()

    import shaketable as st
    from shaketable.ground import records

    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(args.folder or scratch)
        folder.mkdir(parents=True, exist_ok=True)
        record = folder / f"big-{args.samples}.txt"
        if not record.exists():
            write_record(record, args.samples)
        block = st.Block.parse("30x6in")
        st.simulate(block, st.Motion.at_rest(1.0), cor=0.9)          # compile / load cache

        began = time.perf_counter()
        motion = records.combine(records.read(record, units="g", dt=0.005), name="big")
        read = time.perf_counter() - began
        began = time.perf_counter()
        result = st.simulate(block, motion, cor=0.9)
        api = time.perf_counter() - began
        del motion

        command = [sys.executable, "-m", "shaketable", "simulate", "--block", "30x6in",
                   "--cor", "0.9", "--record", str(record), "--units", "g", "--dt", "0.005",
                   "--history", args.history, "--out", str(folder / "out"), "-q"]
        began = time.perf_counter()
        subprocess.run(command, check=True)
        cli = time.perf_counter() - began
        history = folder / "out" / "history.csv"
        print(json.dumps({
            "samples": args.samples, "verdict": result.verdict(), "history": args.history,
            "history.csv [MB]": round(history.stat().st_size / 1e6, 3) if history.exists()
            else None,
            "API simulate [s]": round(api, 2), "API read + simulate [s]": round(read + api, 2),
            "CLI [s]": round(cli, 2), "CLI / API simulate": round(cli / api, 2),
            "CLI / API read + simulate": round(cli / (read + api), 2)}, indent=1))


if __name__ == "__main__":
    main()
