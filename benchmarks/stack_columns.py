"""Columns of ten blocks through long chatters: the compiled stack engine's CPU per run.

Four columns of ten blocks (each with its record's vertical, rtol 1e-12, the compiled
engine alone: ``shaketable.models.stack.compiled.integrate``, no result object):

- ``taper``: blocks 2 m high, 2 m wide at the bottom narrowing by 0.15 m per block, under
  Pacoima Dam S74W (41.7 s);
- ``8x2ft``: ten 8 x 2 ft blocks under El Centro 1940 180 (the first 30 s, or ``--whole``);
- ``1x0.4m``: ten 1 x 0.4 m blocks under El Centro 1940 180 (they overturn at about 7.5 s);
- ``30x6in``: ten 30 x 6 in blocks under El Centro 1940 270 at half scale (overturn at 7 s).

Printed for each: the status, where the run ended, the events and the process's CPU time
(one thread; the first call compiles or loads numba's cache, before the timing). These runs
are chaotic chatters of many contacts: their event counts change with any change of
rounding; the measure is the CPU they take. ``docs/stack.md`` (Contacts chattering below the
resolution) has the numbers before and after the plastic law's pivot.

    python3 benchmarks/stack_columns.py [--only NAME] [--whole]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import shaketable as st
from shaketable.ground import records
from shaketable.models.stack import Stack
from shaketable.models.stack.compiled import integrate

COLUMNS = {
    "taper": (lambda: Stack([st.Block(2.0, 2.0 - 0.15 * i) for i in range(10)]),
              "pacoima-dam-s74w", 1.0, None),
    "8x2ft": (lambda: Stack([st.Block.parse("8x2ft")] * 10), "el-centro-1940-180", 1.0, 30.0),
    "1x0.4m": (lambda: Stack([st.Block(1.0, 0.4)] * 10), "el-centro-1940-180", 1.0, None),
    "30x6in": (lambda: Stack([st.Block.parse("30x6in")] * 10), "el-centro-1940-270", 0.5,
               None),
}


def run(stack, motion) -> dict:
    """One compiled run from rest (the plastic law, rtol 1e-12)."""
    zeros = np.zeros(stack.n)
    return integrate(stack, motion, law="plastic", cor=0.0, theta0=zeros, theta_dot0=zeros,
                     rtol=1e-12, rest_tolerance=1e-6 / stack.blocks[0].p,
                     max_recorded_events=1)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", choices=sorted(COLUMNS), help="one column")
    parser.add_argument("--whole", action="store_true", help="whole records throughout")
    args = parser.parse_args()
    warm = Stack([st.Block(1.0, 0.4)] * 4)
    run(warm, st.Motion(np.array([0.0, 0.02]), np.zeros(2)))   # compile or load the cache
    for name, (make, record_name, scale, seconds) in COLUMNS.items():
        if args.only and name != args.only:
            continue
        record = records.load(record_name)
        keep = record.t <= (seconds if seconds and not args.whole else np.inf)
        motion = st.Motion(record.t[keep], scale * record.horizontal[keep],
                           scale * record.vertical[keep])
        stack = make()
        start = time.process_time()
        out = run(stack, motion)
        cpu = time.process_time() - start
        ended = float(motion.t[out["filled"] - 1])
        print(f"{name:7s} {record_name} x {scale:g}, {motion.t[-1]:.1f} s: "
              f"{out['run'].status} at {ended:.2f} s, {out['run'].n_events:,} events, "
              f"{cpu:.1f} s of CPU", flush=True)


if __name__ == "__main__":
    main()
