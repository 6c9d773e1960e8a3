"""The coupled planar model's batch against the rocking batch on the same grid: runs/s.

Grid: Pacoima Dam S16E + vertical; blocks H = 2 .. 16 ft with B/H = 1/4 and 1/6
(16 blocks); COR 0.9; the planar batch once with ample friction (mu = 10: it rocks as
the rocking model, the same work) and once with mu_s = 0.5, mu_d = 0.4 (it slides,
rocks and slide-rocks). Each batch is called once first (compile or load the cache),
then the three batches are timed in turn, ``--repeats`` times (default 5), so that a
change of the machine's load touches all three alike. Both the wall time and the CPU
time of the process (all threads: the batches run in parallel) are measured; the
ratios planar / rocking of runs/s are printed as the median over the repeats and
their range. The target is at least one third of the rocking batch's runs/s. Both
batches share their cases among Python threads (no numba threading layer, whose OpenMP
threads stayed busy after a parallel loop and slowed the batch timed next).

    python3 benchmarks/planar_speed.py [--repeats N]
"""

import argparse
import json
import statistics
import time

import numpy as np

from shaketable import Block
from shaketable.core.constants import INCH
from shaketable.ground import records
from shaketable.models.planar.batch import simulate_many_planar
from shaketable.models.rocking.batch import simulate_many
from shaketable.models.sliding.result import Friction

FOOT = 12 * INCH


def timed(function):
    """(wall, CPU) seconds of one call."""
    wall, cpu = time.perf_counter(), time.process_time()
    function()
    return time.perf_counter() - wall, time.process_time() - cpu


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    repeats = parser.parse_args().repeats
    motion = records.load("pacoima-dam-s16e")
    blocks = [Block(height=h * FOOT, width=h * FOOT * ratio)
              for h in np.linspace(2.0, 16.0, 8) for ratio in (0.25, 1 / 6)]
    runs = len(blocks)
    batches = {
        "rocking": lambda: simulate_many(blocks, motion, [0.9]),
        "planar, mu = 10": lambda: simulate_many_planar(blocks, motion, Friction(10.0), [0.9]),
        "planar, mu_s 0.5, mu_d 0.4": lambda: simulate_many_planar(
            blocks, motion, Friction(0.5, 0.4), [0.9]),
    }
    for batch in batches.values():
        batch()  # compile or load the cache
    times = {name: [] for name in batches}
    for _ in range(repeats):
        for name, batch in batches.items():
            times[name].append(timed(batch))
    report = {"runs": runs, "repeats": repeats}
    for name, pairs in times.items():
        report[f"{name} [runs/s, wall]"] = runs / statistics.median(p[0] for p in pairs)
        report[f"{name} [runs/s, CPU]"] = runs / statistics.median(p[1] for p in pairs)
    for name in list(batches)[1:]:
        for clock, which in (("wall", 0), ("CPU", 1)):
            ratios = [rocking[which] / planar[which]
                      for rocking, planar in zip(times["rocking"], times[name])]
            report[f"{name} / rocking ({clock}): median, min, max"] = [
                round(statistics.median(ratios), 3), round(min(ratios), 3),
                round(max(ratios), 3)]
    print(json.dumps(report, indent=1))
