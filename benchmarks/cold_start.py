"""Cold start: CPU seconds of the first ``simulate`` and of the first
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

``--planar`` measures the planar engine instead (``friction=``; block 30 x 6 in, COR 0.9,
mu 0.3, one second of Pacoima S16E): its first simulate and its first batch
(``simulate_many_planar``) after it, and with ``--breakdown`` both of them per function.

``--breakdown`` prints, for one cold first ``simulate``, where its CPU time goes: importing
numba, and for every function numba compiles (nested as numba compiles them) its own CPU
time (its typing, lowering and numba passes, excluding the functions it calls) and the
part of it spent in LLVM (optimisation and machine code, under numba's ``numba:llvm_lock``
event), from numba's compile events (``numba.core.event``) timed with the process's CPU
clock; ``outside compiles`` is the rest of the first call (numba's target context built on
first use, loading, the run itself), which a warm first call pays too.

``--constructs`` prints what numba's first compile costs per statement of each kind (a
float operation, a tuple item, a call of a helper, a branch, ...), from functions of 20 and
120 copies of it compiled as the engine's helpers are: the figures
:mod:`shaketable.models.rocking.engine` is shaped by.

    python3 benchmarks/cold_start.py [--repeats 2] [--breakdown] [--planar] [--constructs]
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
from shaketable.models.rocking.batch import simulate_many
simulate_many([block], [motion, records.load("pacoima-dam-s74w")], [0.9, 0.95], threads=2)
batch = cpu()
simulate_many([block], [motion], [0.9], threads=1)
serial = cpu()
from shaketable.models.rocking import engine
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
from shaketable.models import api  # noqa: F401  (the solvers' modules)
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
FIRST_CALL
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


#: The first call that --breakdown times: the rocking engine's, or with --planar the planar
#: engine's first simulate and then its first batch (both counted).
ROCKING_CALL = "st.simulate(block, motion, cor=0.95)"
PLANAR_CALL = ("st.simulate(block, motion, cor=0.9, friction=st.Friction(0.3), duration=1.0); "
               "from shaketable.models.planar.batch import simulate_many_planar; "
               "simulate_many_planar([block], motion, st.Friction(0.3), [0.9], duration=1.0)")

PLANAR = r"""
import json, resource
def cpu():
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime
start = cpu()
import shaketable as st
from shaketable.ground import records
block = st.Block.parse("30x6in")
motion = records.load("pacoima-dam-s16e")
imported = cpu()
st.simulate(block, motion, cor=0.9, friction=st.Friction(0.3), duration=1.0)
first = cpu()
from shaketable.models.planar.batch import simulate_many_planar
simulate_many_planar([block], motion, st.Friction(0.3), [0.9], duration=1.0)
batch = cpu()
from shaketable.models.planar import engine as planar
print(json.dumps({"import [s]": imported - start, "first planar simulate [s]": first - imported,
                  "first planar batch after it [s]": batch - first,
                  "planar engine signatures": len(planar.integrate.signatures)}))
"""


#: --constructs: the first-compile CPU time of one statement of each kind, from functions of
#: 20 and 120 copies of it compiled as the engine's helpers are (the difference / 100), in
#: a process whose numba target is already built.
CONSTRUCTS = r"""
import json, os, time
import shaketable  # noqa: F401  (numba's settings, as the engine's)
from numba import njit
helper = njit(no_cpython_wrapper=True, no_cfunc_wrapper=True, _nrt=False)
@helper
def pair(a, b):
    return a + b, a - b, a * b
pair.compile("UniTuple(float64, 3)(float64, float64)")
BODIES = {
    "float operation (x = x * b)": "    x = x * b",
    "tuple item (x = t[3])": "    x = t[3]",
    "abs (x = abs(x))": "    x = abs(x)",
    "min of two floats": "    x = min(x, b)",
    "call of a helper returning 3 floats": "    x, y, z = pair(x, b)",
    "branch (if x > b: y = b)": "    if x > b:\n        y = b",
    "branch on two comparisons with and": "    if x > b and x < a:\n        y = b",
    "branch on two comparisons with &": "    if (x > b) & (x < a):\n        y = b",
    "conditional expression": "    x = b if x > b else x",
}
def function(body, copies):
    lines = ["def f(a, b, t):", "    x = y = z = a"] + [body] * copies + ["    return x + y + z"]
    namespace = {"pair": pair}
    exec("\n".join(lines), namespace)
    return helper(namespace["f"])
njit(lambda a, b: a * b)(1.0, 2.0)  # numba's target context, built once
signature = "float64(float64, float64, UniTuple(float64, 10))"
costs = {}
for name, body in BODIES.items():
    seconds = []
    for copies in (20, 120):
        compiled = function(body, copies)
        start = time.process_time()
        compiled.compile(signature)
        seconds.append(time.process_time() - start)
    costs[name + " [ms]"] = round((seconds[1] - seconds[0]) / 100 * 1e3, 2)
print(json.dumps(costs))
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
    parser.add_argument("--constructs", action="store_true",
                        help="numba's first-compile CPU time per statement of each kind")
    parser.add_argument("--planar", action="store_true",
                        help="the planar engine's first simulate (friction=) and first batch "
                             "instead of the rocking engine's")
    args = parser.parse_args(argv)
    if args.constructs:
        runs = [once(cold=True, child=CONSTRUCTS) for _ in range(args.repeats)]
        best = {key: min(run[key] for run in runs) for key in runs[0].keys()}
        print(json.dumps({"per statement, best of repeats": best,
                          "load average": os.getloadavg()}, indent=1))
        return 0
    if args.breakdown:
        child = BREAKDOWN.replace("FIRST_CALL", PLANAR_CALL if args.planar else ROCKING_CALL)
        print(json.dumps({**once(cold=True, child=child), "load average": os.getloadavg()},
                         indent=1))
        return 0
    if args.planar:
        runs = [once(cold=True, child=PLANAR) for _ in range(args.repeats)]
        best = {key: min(run[key] for run in runs) for key in runs[0].keys()}
        with tempfile.TemporaryDirectory() as cache:
            once(cold=False, cache=cache, child=PLANAR)          # fills this cache
            warm = once(cold=False, cache=cache, child=PLANAR)   # and reads it
        print(json.dumps({"cold, best of repeats": best, "cold, every repeat": runs,
                          "warm cache": warm, "load average": os.getloadavg()}, indent=1))
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
