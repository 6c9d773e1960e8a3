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

``--breakdown`` prints, for one cold first ``simulate``, where its CPU time goes: importing
numba, and for every function numba compiles (nested as numba compiles them) its own CPU
time (its typing, lowering and numba passes, excluding the functions it calls) and the
part of it spent in LLVM (optimisation and machine code, under numba's ``numba:llvm_lock``
event), from numba's compile events (``numba.core.event``) timed with the process's CPU
clock; ``outside compiles`` is the rest of the first call (numba's target context built on
first use, loading, the run itself), which a warm first call pays too.

    python3 benchmarks/cold_start.py [--repeats 2] [--breakdown]
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


BREAKDOWN = r"""
import json, time
cpu = time.process_time
start = cpu()
import shaketable as st
from shaketable.ground import records
block = st.Block.parse("16x4ft")
motion = records.load("pacoima-dam-s16e")
imported = cpu()
import numba
from numba.core import event
numba_imported = cpu()
from shaketable.solvers import api  # noqa: F401  (the solvers' modules)
solvers = cpu()


class Clock(event.Listener):
    def __init__(self):
        self.marks = []

    def on_start(self, ev):
        self.marks.append((cpu(), True, ev))

    def on_end(self, ev):
        self.marks.append((cpu(), False, ev))


compiles, llvm = Clock(), Clock()
event.register("numba:compile", compiles)
event.register("numba:llvm_lock", llvm)
before = cpu()
st.simulate(block, motion, cor=0.95)
after = cpu()
marks = sorted([(t, 0, s, e) for t, s, e in compiles.marks] + [(t, 1, s, e) for t, s, e in llvm.marks],
               key=lambda mark: mark[0])
stack, rows, llvm_started = [], [], 0.0
for t, kind, starting, ev in marks:
    if kind == 1:
        if starting:
            llvm_started = t
        elif stack:
            stack[-1][3] += t - llvm_started
        continue
    if starting:
        function = ev.data["dispatcher"].py_func
        stack.append([t, function.__qualname__.replace(".<locals>", ""), 0.0, 0.0, len(stack)])
    else:
        began, name, nested, in_llvm, depth = stack.pop()
        total = t - began
        if stack:
            stack[-1][2] += total
        rows.append({"function": "  " * depth + name, "self [s]": round(total - nested, 3),
                     "of which LLVM [s]": round(in_llvm, 3), "with callees [s]": round(total, 3)})
compiled = sum(row["self [s]"] for row in rows)
print(json.dumps({"import shaketable + a record [s]": imported - start,
                  "import numba [s]": numba_imported - imported,
                  "import the solvers [s]": solvers - numba_imported,
                  "first simulate [s]": after - before,
                  "  compiles [s]": compiled,
                  "  of which LLVM [s]": sum(row["of which LLVM [s]"] for row in rows),
                  "  outside compiles [s]": after - before - compiled,
                  "functions compiled": len(rows),
                  "per function, outermost first": rows[::-1]}))
"""


def once(cold: bool, cache: str | None = None, child: str = CHILD) -> dict:
    env = dict(os.environ)
    with tempfile.TemporaryDirectory() as folder:
        env["NUMBA_CACHE_DIR"] = folder if cold else (cache or env.get("NUMBA_CACHE_DIR", ""))
        output = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True,
                                env=env, check=True).stdout
    return json.loads(output.strip().splitlines()[-1])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--breakdown", action="store_true",
                        help="where one cold first simulate's CPU time goes, per function")
    args = parser.parse_args(argv)
    if args.breakdown:
        print(json.dumps({**once(cold=True, child=BREAKDOWN), "load average": os.getloadavg()},
                         indent=1))
        return 0
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
