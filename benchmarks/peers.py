"""The engine beside a researcher's own script.

The peer is the script a researcher writes with SciPy alone: Eq. (2-13) with the
vertical acceleration, ground accelerations interpolated linearly between samples
(``np.interp``, the engine's model too), rest until Eq. (2-1) holds (the crossing
interpolated linearly inside the sample interval), then ``solve_ivp`` from impact to
impact with terminal events (theta = 0 on the active corner, |theta| = pi/2), restarted
after each impact with theta' -> COR theta' on the other corner (Section 2.7 (5)).
It is run with RK45 at rtol 1e-6 and with DOP853 at rtol 1e-10 on Pacoima Dam S16E +
vertical, 16 x 4 ft block, COR 0.95, beside ``shaketable.simulate`` (fast, rtol 1e-11)
on the same record, in the same process.

Printed for each peer: its CPU time per run (minimum over repeats), the ratio to the
engine's, and its errors against the engine: the overturn time, the largest difference
of the impact times, and the number of impacts. The engine agrees with the package's
``reference`` (DOP853 at rtol 2.5e-14) to 1e-10 on this case (README, "Error against
run time"), so its numbers stand for the truth here.

    python3 benchmarks/peers.py [--repeats 3]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time

import numpy as np
from scipy.integrate import solve_ivp

from shaketable import Block, simulate
from shaketable.core.constants import G
from shaketable.ground import records


def researcher_script(t_record, ug_record, vg_record, b, h, cor, method, rtol):
    """Overturn time [s] (NaN if none) and impact times [s] of a rigid block, by solve_ivp."""
    inertia = 4.0 / 3.0 * (b * b + h * h)      # I0 / M about a corner
    alpha = math.atan2(b, h)
    p = math.sqrt(3.0 * G / (4.0 * math.sqrt(b * b + h * h)))
    t_end = t_record[-1]

    def ground(t):
        return np.interp(t, t_record, ug_record), np.interp(t, t_record, vg_record)

    def rhs(t, y, side):
        ug, vg = ground(t)
        theta = y[0]
        moment = (ug * (h * math.cos(theta) + side * b * math.sin(theta))
                  - (G + vg) * (side * b * math.cos(theta) - h * math.sin(theta)))
        return [y[1], moment / inertia]

    # at rest until Eq. (2-1): |ug| h > (g + vg) b, the crossing interpolated linearly
    margin = np.abs(ug_record) * h - (G + vg_record) * b
    first = int(np.argmax(margin > 0.0))
    if margin[first] <= 0.0:
        return math.nan, []
    t, side = t_record[first], math.copysign(1.0, ug_record[first])
    if first > 0:
        m0 = side * ug_record[first - 1] * h - (G + vg_record[first - 1]) * b
        m1 = margin[first]
        t = t_record[first - 1] + (t_record[first] - t_record[first - 1]) * (-m0) / (m1 - m0)
    theta, omega = 0.0, 0.0
    impacts = []
    while t < t_end:
        def impact(t, y, side):  # solve_ivp hands events the args too
            return side * y[0]
        impact.terminal, impact.direction = True, -1

        def overturn(t, y, side):
            return abs(y[0]) - 0.5 * math.pi
        overturn.terminal, overturn.direction = True, 1

        solution = solve_ivp(rhs, (t, t_end), [theta, omega], method=method, rtol=rtol,
                             atol=rtol * alpha * np.array([1.0, p]), events=[impact, overturn],
                             args=(side,))
        if solution.t_events[1].size:
            return float(solution.t_events[1][0]), impacts
        if not solution.t_events[0].size:
            return math.nan, impacts
        t = float(solution.t_events[0][0])
        omega = cor * float(solution.y_events[0][0][1])
        theta, side = 0.0, -side
        impacts.append(t)
        if abs(omega) < 1e-9 * alpha * p:   # a cascade: the block is at rest
            return math.nan, impacts
    return math.nan, impacts


def cpu_seconds(function, repeats):
    best = float("inf")
    for _ in range(repeats):
        start = time.process_time()
        value = function()
        best = min(best, time.process_time() - start)
    return best, value


def measure(repeats: int = 3) -> dict:
    block = Block.parse("16x4ft")
    motion = records.load("pacoima-dam-s16e")
    cor = 0.95
    simulate(block, motion, cor=cor)  # compile / load
    engine_seconds = float("inf")
    for _ in range(20):
        start = time.process_time()
        for _ in range(20):
            result = simulate(block, motion, cor=cor)
        engine_seconds = min(engine_seconds, (time.process_time() - start) / 20)
    out: dict = {"case": "Pacoima Dam S16E + vertical, 16 x 4 ft, COR 0.95",
                 "engine [ms]": 1e3 * engine_seconds,
                 "engine t_overturn [s]": float(result.t_overturn),
                 "engine impacts": int(result.n_impacts)}
    t, ug, vg = motion.t, motion.horizontal, motion.vertical_or_zero
    for method, rtol in (("RK45", 1e-6), ("DOP853", 1e-10)):
        seconds, (t_overturn, impacts) = cpu_seconds(
            lambda method=method, rtol=rtol: researcher_script(t, ug, vg, block.b, block.h, cor,
                                                               method, rtol), repeats)
        same = len(impacts) == result.n_impacts
        out[f"{method} rtol {rtol:g}"] = {
            "CPU per run [ms]": 1e3 * seconds,
            "ratio to the engine [-]": seconds / engine_seconds,
            "overturn time error [s]": t_overturn - float(result.t_overturn),
            "impacts": len(impacts),
            "largest impact time error [s]": (
                float(np.max(np.abs(np.array(impacts) - result.impact_times))) if same
                else "different number of impacts"),
        }
    out["load average"] = os.getloadavg()
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    print(json.dumps(measure(args.repeats), indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
