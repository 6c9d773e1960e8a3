"""Batch throughput: runs per second on 1 and 2 threads.

The grid: Table 4.2's nine block sizes x the two Pacoima Dam records (S16E and S74W,
with their verticals) x 8 COR in [0.7, 1.0] = 144 runs, fast method, as
:func:`shaketable.studies.work_precision.batch_throughput`. Printed: the best wall time
of a sweep over the repeats on each thread count, runs/s, the ratio 2 threads / 1 thread,
the CPU time per run, and the same runs' right-hand-side limit (their evaluations x the
cost of one evaluation in a tight compiled loop, ``benchmarks/engine_limit.py``).
Targets: >= 3,000 runs/s on 2 threads, >= 1.8 x one thread. Wall times on a shared
machine depend on whether the second core is free: the load average is printed too.

    python3 benchmarks/batch_rate.py [--repeats 15]
"""

from __future__ import annotations

import argparse
import json
import os
import threading
import time
from collections import defaultdict

import numpy as np

from shaketable import Block
from shaketable.ground import records
from shaketable.models.rocking import batch
from shaketable.models.rocking.batch import simulate_many
from shaketable.models.rocking.physics import block_parameters

try:  # run as a script from benchmarks/
    from engine_limit import cpu_per_call, rhs_loop
except ImportError:  # pragma: no cover - imported as benchmarks.batch_rate
    from benchmarks.engine_limit import cpu_per_call, rhs_loop

SIZES_FT = ((2, 1), (3, 1), (4, 1), (5, 1), (4, 2), (6, 2), (8, 2), (6, 3), (9, 3))


def measure(repeats: int = 15) -> dict:
    blocks = [Block.from_feet(h, w) for h, w in SIZES_FT]
    motions = [records.load("pacoima-dam-s16e"), records.load("pacoima-dam-s74w")]
    cors = list(np.linspace(0.7, 1.0, 8))
    out: dict = {"runs": len(blocks) * len(motions) * len(cors)}
    for threads in (1, 2):
        simulate_many(blocks[:1], motions[:1], cors[:1], threads=threads)  # compile / load
        best_wall = best_cpu = float("inf")
        for _ in range(repeats):
            wall, cpu = time.perf_counter(), time.process_time()
            table = simulate_many(blocks, motions, cors, threads=threads)
            best_wall = min(best_wall, time.perf_counter() - wall)
            best_cpu = min(best_cpu, time.process_time() - cpu)
        out[f"{threads} thread(s): best wall [s]"] = best_wall
        out[f"{threads} thread(s): runs/s"] = len(table) / best_wall
        out[f"{threads} thread(s): CPU per run [ms]"] = 1e3 * best_cpu / len(table)
    out["2 threads / 1 thread"] = out["2 thread(s): runs/s"] / out["1 thread(s): runs/s"]
    # Load-independent: each thread's own CPU time in the compiled loop. On two free cores
    # the sweep takes as long as its busier thread, so runs / max(thread CPU) is the
    # 2-thread rate the scheduling allows, whatever else the shared machine runs.
    compiled = batch._run_cases
    busy: dict = defaultdict(float)

    def timed(*arguments):
        start = time.thread_time()
        compiled(*arguments)
        busy[threading.get_ident()] += time.thread_time() - start

    best_split = float("inf")
    batch._run_cases = timed
    try:
        for _ in range(repeats):
            busy.clear()
            simulate_many(blocks, motions, cors, threads=2)
            best_split = min(best_split, max(busy.values()))
            threads_used = len(busy)
    finally:
        batch._run_cases = compiled
    out["2 threads, from per-thread CPU: runs/s"] = out["runs"] / best_split
    out["2 threads, from per-thread CPU / 1 thread CPU"] = (
        out["1 thread(s): CPU per run [ms]"] * 1e-3 * out["runs"] / best_split)
    out["threads that ran cases"] = threads_used
    evaluations = int(table["solver evaluations"].sum())
    parameters = block_parameters(blocks[0])
    ug, vg = motions[0].horizontal, motions[0].vertical_or_zero
    rhs_loop(10, ug, vg, parameters)
    per_evaluation = cpu_per_call(lambda: rhs_loop(100_000, ug, vg, parameters), 5, 5) / 1e5
    limit = evaluations * per_evaluation
    out["evaluations"] = evaluations
    out["limit, one thread [runs/s]"] = len(table) / limit
    out["one thread CPU / limit"] = out["1 thread(s): CPU per run [ms]"] * 1e-3 * len(table) / limit
    out["overturned [-]"] = float(table["overturned"].mean())
    out["targets"] = {"2 threads runs/s": 3000, "2 threads / 1 thread": 1.8}
    out["load average"] = os.getloadavg()
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=15)
    args = parser.parse_args(argv)
    print(json.dumps(measure(args.repeats), indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
