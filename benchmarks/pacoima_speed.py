"""Pacoima Dam S16E + vertical, 16 x 4 ft block, COR 0.95: warm ms/run of fast and of
reference in the same process, the speed ratio, and the first call in a fresh process
(numba cache load, and compilation from an empty cache).

    python3 benchmarks/pacoima_speed.py
"""

import json

from shaketable.studies import work_precision as bench

if __name__ == "__main__":
    timing = bench.pacoima_timing(repeats=200, reference_repeats=3)
    cached = bench.first_call_seconds(cold=False)
    cold = bench.first_call_seconds(cold=True)
    print(json.dumps({"pacoima": timing, "first call (cache)": cached,
                      "first call (compile)": cold}, indent=1, default=float))
