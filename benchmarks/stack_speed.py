"""The stack model's compiled batch against the single-block batch on the same record grid.

Grid: the report's two Section 4 records (Pacoima Dam S16E and S74W) and El Centro 1940
(180 and 270; not a record of the report), each with its vertical, at full scale and at
half scale, on three block sizes (30 x 6 in, 4 x 1 ft, 16 x 4 ft: 24 runs). The
single-block batch (``shaketable.models.rocking.batch.simulate_many``, method "fast",
Housner's COR, which is the stack's plastic law for one block: one summary row per run)
runs each block; two of the same block stacked run three ways:

- **rows** (``shaketable.models.stack.batch.simulate_many``: the compiled stack engine, one
  summary row per run from its arrays, no result object): like for like with the
  single-block batch, rows against rows. **Its ratio is the one the target is about: a
  two-block run should cost at most 3 times a single-block run.**
- **results** (``StackModel.run_many``: a ``StackResult`` per run, with histories, forces
  and events as dicts): what ``shaketable.simulate`` hands a list of motions;
- **engine** (``compiled.integrate`` alone: no row, no result).

All on one thread, each called once first (compile or load the cache), then timed in turn
``--repeats`` times (default 5); the per-run cost is the CPU time of the process over a
repeat divided by the number of runs (CPU time: the machine is shared; one thread each, so
CPU time is the run's cost). Printed: the medians per run and, for each ratio two blocks /
one block, its median and range over the repeats. Why the ratio stays above 3 on this
grid: the two-block stack uplifts at half the block's acceleration and is in motion about
4.7 times as long as the block alone (487 s against 103 s over the 24 runs); per second of
motion the stack's engine costs about what the single-block batch does (``docs/stack.md``,
Speed).

    python3 benchmarks/stack_speed.py [--repeats N]
"""

import argparse
import json
import statistics
import time
import warnings

import numpy as np
import pandas as pd

from shaketable import Block
from shaketable.ground import records
from shaketable.models.rocking.batch import simulate_many
from shaketable.models.stack import Stack
from shaketable.models.stack.batch import simulate_many as stack_rows
from shaketable.models.stack.compiled import integrate
from shaketable.models.stack.model import STACK_MODEL

RECORDS = ("pacoima-dam-s16e", "pacoima-dam-s74w", "el-centro-1940-180",
           "el-centro-1940-270")
SCALES = (1.0, 0.5)
BLOCKS = {name: Block.parse(name) for name in ("30x6in", "4x1ft", "16x4ft")}


def grid():
    motions = [records.load(name).scaled(scale) for name in RECORDS for scale in SCALES]
    return motions


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    motions = grid()
    blocks = list(BLOCKS.values())
    runs = len(motions) * len(blocks)

    def single():
        for block in blocks:
            simulate_many(block, motions, 1.0 - 1.5 * np.sin(block.alpha) ** 2, threads=1)

    def rows():
        for block in blocks:
            stack_rows(Stack([block, block]), motions, threads=1)

    def results():
        for block in blocks:
            STACK_MODEL.run_many(Stack([block, block]), motions, threads=1)

    def engine():
        for block in blocks:
            stack = Stack([block, block])
            for motion in motions:
                integrate(stack, motion, law="plastic", cor=1.0, theta0=np.zeros(2),
                          theta_dot0=np.zeros(2), rtol=1e-12,
                          rest_tolerance=1e-6 / block.p, max_recorded_events=100_000)

    warnings.simplefilter("ignore")
    functions = {"single": single, "rows": rows, "results": results, "engine": engine}
    for function in functions.values():
        function()
    times: dict[str, list[float]] = {key: [] for key in functions}
    for _ in range(args.repeats):
        for key, function in functions.items():
            start = time.process_time()
            function()
            times[key].append((time.process_time() - start) / runs)

    def ratio(key):
        values = [s / b for s, b in zip(times[key], times["single"])]
        return [round(statistics.median(values), 2), round(min(values), 2),
                round(max(values), 2)]

    def per_run(key):
        return [round(1e3 * statistics.median(times[key]), 3),
                round(1e3 * min(times[key]), 3), round(1e3 * max(times[key]), 3)]

    table = pd.concat([stack_rows(Stack([block, block]), motions, threads=1)
                       for block in blocks])
    print(json.dumps({
        "runs per batch": runs, "repeats": args.repeats,
        "per run [ms] (median, range)": {
            "single block (rows)": per_run("single"),
            "two blocks (rows: stack batch)": per_run("rows"),
            "two blocks (results: run_many)": per_run("results"),
            "two blocks (engine only)": per_run("engine")},
        "ratio two blocks / one block, rows against rows (the target: at most 3)":
            ratio("rows"),
        "ratio two blocks with results (run_many) / one block (rows)": ratio("results"),
        "ratio two blocks, engine only / one block (rows)": ratio("engine"),
        "two-block runs that overturn (and stop)":
            f"{int(table['overturned'].sum())} of {runs}",
    }, indent=1))


if __name__ == "__main__":
    main()
