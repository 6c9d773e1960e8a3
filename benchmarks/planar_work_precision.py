"""Work-precision of the planar reference solver (issue 25) on one coupled case.

The 30 x 6 in block (mu_s 0.25, mu_d 0.22, COR 0.9) under a 3 Hz, 0.6 g harmonic table
motion for 3 s (half-cycle ramp) sampled every 0.05 s (with 5 ms samples one DOP853
step per sample is exact to rounding at any rtol, which says nothing): it rocks,
slide-rocks and impacts 16 times. The
reference (SciPy DOP853 with event location, ``solvers.planar_reference``) runs at
several rtol; the error of each is against the same solver at rtol 1e-13 (the tightest
it accepts with rtol/100 absolute tolerances): the largest difference in event times,
in theta at the samples and in the slip at the samples.

Run: ``python benchmarks/planar_work_precision.py`` (prints a Markdown table; about
ten seconds on one core). Measured on this machine (best of 3):

| rtol | run time [s] | event time error [s] | theta error [rad] | slip error [m] |
|---|---|---|---|---|
| 1e-06 | 0.16 | 3.9e-10 | 2.3e-10 | 2.1e-11 |
| 1e-08 | 0.16 | 5.4e-10 | 3.2e-10 | 2.9e-11 |
| 1e-10 | 0.17 | 5.5e-10 | 3.3e-10 | 3.0e-11 |
| 1e-11 | 0.20 | 8.2e-11 | 4.8e-11 | 4.7e-12 |
| 1e-12 | 0.19 | 2.5e-12 | 1.5e-12 | 2.4e-13 |

Down to rtol 1e-10 DOP853 takes one step per 0.05 s sample (the input's kink at each
sample bounds the step), so the error does not change; below it the steps split.
"""

from __future__ import annotations

import time

import numpy as np

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.core.sliding_result import Friction
from shaketable.ground.generators import harmonic
from shaketable.solvers.planar_reference import simulate_reference

RTOLS = (1e-6, 1e-8, 1e-10, 1e-11, 1e-12)


def run(rtol):
    block = Block.from_inches(30, 6)
    motion = harmonic(3.0, horizontal=0.6 * G, duration=3.0, dt=0.05, ramp=0.25)
    times = []
    for _ in range(3):  # best of three (a shared machine)
        start = time.perf_counter()
        result = simulate_reference(block, motion, cor=0.9, friction=Friction(0.25, 0.22),
                                    rtol=rtol)
        times.append(time.perf_counter() - start)
    return result, min(times)


def main():
    best, best_time = run(1e-13)
    print(f"Reference at rtol 1e-13: {len(best.event_times)} events, "
          f"{len(best.impact_times)} impacts, {best_time:.2f} s\n")
    print("| rtol | run time [s] | event time error [s] | theta error [rad] | "
          "slip error [m] | same events |")
    print("|---|---|---|---|---|---|")
    for rtol in RTOLS:
        result, elapsed = run(rtol)
        same = result.event_kinds == best.event_kinds
        if same:
            event_error = np.abs(result.event_times - best.event_times).max()
        else:
            event_error = float("nan")
        theta_error = np.abs(result.theta - best.theta).max()
        slip_error = np.abs(result.slip - best.slip).max()
        print(f"| {rtol:.0e} | {elapsed:.2f} | {event_error:.1e} | {theta_error:.1e} | "
              f"{slip_error:.1e} | {'yes' if same else 'no'} |")


if __name__ == "__main__":
    main()
