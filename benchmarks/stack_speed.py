"""The stack model's compiled batch against the single-block batch on the same record grid.

Grid: the report's Section 4 records (Pacoima Dam S16E and S74W, El Centro 1940 180 and
270, each with its vertical), at full scale and at half scale, on three block sizes
(30 x 6 in, 4 x 1 ft, 16 x 4 ft: 24 runs). The single-block batch
(``shaketable.models.rocking.batch.simulate_many``, method "fast", Housner's COR, which is the
stack's plastic law for one block) runs each block; the stack batch
(``StackModel.run_many``: the compiled stack engine, plastic law, a result with histories,
forces and events per run) runs two of the same block stacked. Both on one thread, each
called once first (compile or load the cache), then timed in turn ``--repeats`` times
(default 3); the per-run cost is the median CPU time of the process over the repeats divided
by the number of runs (CPU time: the machine is shared; one thread each, so CPU time is the
run's cost), and the ratio two blocks / one block is printed with its range (target: at most 3).
The stack engine's own share (``compiled.integrate``, no result object) is printed too.

    python3 benchmarks/stack_speed.py [--repeats N]
"""

import argparse
import json
import statistics
import time
import warnings

import numpy as np

from shaketable import Block
from shaketable.ground import records
from shaketable.models.rocking.batch import simulate_many
from shaketable.models.stack import Stack, simulate_stack
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
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    motions = grid()
    blocks = list(BLOCKS.values())
    runs = len(motions) * len(blocks)

    def single():
        for block in blocks:
            simulate_many(block, motions, 1.0 - 1.5 * np.sin(block.alpha) ** 2, threads=1)

    def stacks():
        for block in blocks:
            STACK_MODEL.run_many(Stack([block, block]), motions, threads=1)

    def engine_only():
        for block in blocks:
            stack = Stack([block, block])
            for motion in motions:
                integrate(stack, motion, law="plastic", cor=1.0, theta0=np.zeros(2),
                          theta_dot0=np.zeros(2), rtol=1e-12,
                          rest_tolerance=1e-6 / block.p, max_recorded_events=100_000)

    warnings.simplefilter("ignore")
    for function in (single, stacks, engine_only):
        function()
    times: dict[str, list[float]] = {"single": [], "stack": [], "engine": []}
    for _ in range(args.repeats):
        for key, function in (("single", single), ("stack", stacks), ("engine", engine_only)):
            start = time.process_time()
            function()
            times[key].append((time.process_time() - start) / runs)
    ratios = [s / b for s, b in zip(times["stack"], times["single"])]
    engine_ratios = [s / b for s, b in zip(times["engine"], times["single"])]
    overturned = sum(simulate_stack(Stack([block, block]), motion).status == "overturned"
                     for block in blocks for motion in motions)
    print(json.dumps({
        "runs per batch": runs,
        "single block, per run [ms]": round(1e3 * statistics.median(times["single"]), 3),
        "two blocks (run_many, results), per run [ms]":
            round(1e3 * statistics.median(times["stack"]), 3),
        "two blocks (engine only), per run [ms]":
            round(1e3 * statistics.median(times["engine"]), 3),
        "ratio two blocks / one block (median, range)":
            [round(statistics.median(ratios), 2), round(min(ratios), 2), round(max(ratios), 2)],
        "ratio, engine only (median, range)":
            [round(statistics.median(engine_ratios), 2), round(min(engine_ratios), 2),
             round(max(engine_ratios), 2)],
        "two-block runs that overturn (and stop)": f"{overturned} of {runs}",
    }, indent=1))


if __name__ == "__main__":
    main()
