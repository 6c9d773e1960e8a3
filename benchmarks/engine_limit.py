"""The engine against its own limit: Pacoima Dam S16E + vertical,
16 x 4 ft block, COR 0.95.

The limit is the cost of the run's right-hand-side evaluations alone: the same number of
calls of :func:`shaketable.models.rocking.physics.flight_acceleration` (the run's own
``statistics["evaluations"]``) in a tight compiled loop, measured in the same process.
Printed: CPU time per run [ms] of ``simulate``, of ``engine.integrate_fast`` called directly
(no Python wrapper), of the limit loop, and the two ratios (target: simulate <= 2.0 x the
limit). Times are CPU time (``time.process_time``) of a block of runs, the minimum over
repeats, so that other processes on a shared machine count as little as possible.

    python3 benchmarks/engine_limit.py [--repeats 30] [--block-runs 20]
"""

from __future__ import annotations

import argparse
import json
import os
import time

import numpy as np
from numba import njit

from shaketable import Block, simulate
from shaketable.ground import records
from shaketable.models.rocking import engine
from shaketable.models.rocking.physics import block_parameters, flight_acceleration


@njit(cache=True)
def rhs_loop(n, ug, vg, parameters):
    """``n`` evaluations of Eq. (2-13)/(2-14) on the record's samples, one after another.

    Each evaluation's theta depends on the previous one's result, as a Runge-Kutta
    stage depends on the stages before it (without that chain the processor overlaps
    independent evaluations and the loop measures throughput, not a stepper's latency).
    """
    total = 0.0
    side = 1.0
    j = 0
    m = ug.shape[0]
    acceleration = 0.0
    for _ in range(n):
        theta = 0.01 + 1e-6 * acceleration
        acceleration = flight_acceleration(theta, side, ug[j], vg[j], 0.0, parameters)
        total += acceleration
        side = -side
        j += 1
        if j == m:
            j = 0
    return total


def cpu_per_call(function, block_runs: int, repeats: int) -> float:
    """Minimum over ``repeats`` of the CPU time of ``block_runs`` calls, per call [s]."""
    best = float("inf")
    for _ in range(repeats):
        start = time.process_time()
        for _ in range(block_runs):
            function()
        best = min(best, time.process_time() - start)
    return best / block_runs


def measure(repeats: int = 30, block_runs: int = 20) -> dict:
    block = Block.parse("16x4ft")
    motion = records.load("pacoima-dam-s16e")
    result = simulate(block, motion, cor=0.95)  # compile / load
    evaluations = result.statistics["evaluations"]
    parameters = block_parameters(block)
    t, ug = motion.t, motion.horizontal
    vg, rg = motion.vertical_or_zero, motion.rotation_or_zero
    n = t.size

    def engine_only():
        info = np.zeros(engine.N_INFO)
        empty = np.zeros(0)
        engine.integrate_fast(t, ug, vg, rg, 1.0, parameters, 0.95, 0.0, 0.0, 1e-11, 4, -1.0,
                              np.zeros(n), np.zeros(n), np.zeros(n), empty, empty, info)

    rhs_loop(10, ug, vg, parameters)
    engine_only()
    limit = cpu_per_call(lambda: rhs_loop(evaluations, ug, vg, parameters), block_runs,
                         repeats)
    whole = cpu_per_call(lambda: simulate(block, motion, cor=0.95), block_runs, repeats)
    alone = cpu_per_call(engine_only, block_runs, repeats)
    return {"evaluations": evaluations, "steps": result.statistics["steps"],
            "rejected": result.statistics["rejected"],
            "limit [ms]": 1e3 * limit, "ns per evaluation": 1e9 * limit / evaluations,
            "simulate [ms]": 1e3 * whole, "engine.integrate [ms]": 1e3 * alone,
            "simulate / limit": whole / limit, "engine / limit": alone / limit,
            "target simulate / limit": 2.0, "load average": os.getloadavg()}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=30)
    parser.add_argument("--block-runs", type=int, default=20)
    args = parser.parse_args(argv)
    print(json.dumps(measure(args.repeats, args.block_runs), indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
