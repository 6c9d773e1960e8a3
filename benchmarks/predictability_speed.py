"""Timings of one overturning spectrum and the Table 4.2 ensembles.

Run: PYTHONPATH=. python benchmarks/predictability_speed.py  (best of ``REPEATS``; the
first call compiles and is not counted). Results in benchmarks/RESULTS.md.
"""

import time

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.studies.overturning_spectrum import overturning_spectrum
from shaketable.studies.predictability import ensemble, table_predictability
from shaketable.studies.report_tables import column_motion

REPEATS = 3


def best(label, function):
    function()
    times = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        value = function()
        times.append(time.perf_counter() - start)
    print(f"{label}: best {min(times):.2f} s of {REPEATS}")
    return value


if __name__ == "__main__":
    block = Block.from_slenderness(3 * G / 16, 0.25)       # alpha 0.25, p 2 rad/s
    for kind in ("half-sine", "one-sine"):
        best(f"spectrum {kind}, omega/p 1,2,3,4,6,8,10, edges to 1e-8",
             lambda: overturning_spectrum(block, pulses=(kind,), tolerance=1e-8))
    frame = best("Table 4.2, Pacoima columns (24 cells) x 200 members",
                 lambda: table_predictability("table_4_2",
                                              columns=["pacoima S16E", "pacoima S74W"]))
    best("Table 4.2, all 48 cells x 200 members",
         lambda: table_predictability("table_4_2"))
    result = best("one ensemble, 2 x 1 ft, Pacoima S74W, 200 members + horizon",
                  lambda: ensemble(Block.from_feet(2, 1), column_motion("pacoima S74W"),
                                   cor=1.0, members=200))
    print(result.describe())
