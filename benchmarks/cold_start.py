"""Cold start (issue 28, goal 3): CPU seconds of the first ``simulate`` and of the first
batch after it, in a fresh process with an empty numba cache.

Each measurement runs in a new Python process whose ``NUMBA_CACHE_DIR`` is an empty
temporary folder, so everything the engine needs is compiled there; the CPU time is
``resource.getrusage`` of that process (user + system), which counts compilation on
any thread and little of the other processes of a shared machine. Printed: import,
first ``simulate`` (Pacoima S16E, 16 x 4 ft, COR 0.95), first ``simulate_many`` on two
threads after it, a second ``simulate_many`` on one thread, the number of compiled
signatures of the engine (one: ``simulate`` and the batch share it) and, for comparison,
the same first call with the cache warm. Targets: first simulate <= 3 s CPU, first batch
<= 2 s more.

    python3 benchmarks/cold_start.py [--repeats 2]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile

CHILD = r"""
import json, resource
def cpu():
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime
start = cpu()
import shaketable as st
from shaketable.ground import records
block = st.Block.parse("16x4ft")
motion = records.load("pacoima-dam-s16e")
imported = cpu()
st.simulate(block, motion, cor=0.95)
first = cpu()
from shaketable.solvers.batch import simulate_many
simulate_many([block], [motion, records.load("pacoima-dam-s74w")], [0.9, 0.95], threads=2)
batch = cpu()
simulate_many([block], [motion], [0.9], threads=1)
serial = cpu()
from shaketable.solvers import engine
print(json.dumps({"import [s]": imported - start, "first simulate [s]": first - imported,
                  "first batch after it [s]": batch - first,
                  "batch on one thread after that [s]": serial - batch,
                  "engine signatures": len(engine.integrate_fast.signatures)}))
"""


def once(cold: bool, cache: str | None = None) -> dict:
    env = dict(os.environ)
    with tempfile.TemporaryDirectory() as folder:
        env["NUMBA_CACHE_DIR"] = folder if cold else (cache or env.get("NUMBA_CACHE_DIR", ""))
        output = subprocess.run([sys.executable, "-c", CHILD], capture_output=True, text=True,
                                env=env, check=True).stdout
    return json.loads(output.strip().splitlines()[-1])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=2)
    args = parser.parse_args(argv)
    runs = [once(cold=True) for _ in range(args.repeats)]
    keys = runs[0].keys()
    best = {key: min(run[key] for run in runs) for key in keys}
    with tempfile.TemporaryDirectory() as cache:
        once(cold=False, cache=cache)          # fills this cache
        warm = once(cold=False, cache=cache)   # and reads it
    print(json.dumps({"cold, best of repeats": best, "cold, every repeat": runs,
                      "warm cache": warm, "targets [s]": {"first simulate": 3.0,
                                                          "first batch after it": 2.0},
                      "load average": os.getloadavg()}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
