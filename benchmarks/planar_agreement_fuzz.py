"""Random runs of the compiled planar model against the SciPy reference.

Draws blocks, friction, cor and ramped harmonic table motions (horizontal and vertical)
from a seeded generator, runs ``models.planar.run.simulate_planar`` and
``models.planar.reference.simulate_reference`` on each and prints one line per run:
the modes visited (r s r s f: rest, slide, rock, slide-rock, flight), the status and
either OK or the first difference beyond 1e-8 (events merged at one instant, as in
``tests/models/planar/test_planar_agreement.py``; peak slip, residual slip, max |theta|/alpha).
The cases of DISAGREEMENTS.md were found this way.

Run: ``python benchmarks/planar_agreement_fuzz.py --seed 1 --runs 25``
(about a second per run, after numba's first compilation).
"""

from __future__ import annotations

import argparse

import numpy as np

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.models.planar.reference import simulate_reference
from shaketable.models.planar.run import simulate_planar
from shaketable.models.sliding.result import Friction

TOLERANCE = 1e-8
UNSTABLE_KIND = 4   # the compiled result's |theta| = alpha event


def merged(rows):
    """(time, before, after) rows with those at one instant merged."""
    out: list[list[float]] = []
    for time, before, after in rows:
        if out and abs(time - out[-1][0]) <= 1e-12:
            out[-1][2] = after
        else:
            out.append([time, before, after])
    return np.array(out, dtype=float).reshape(-1, 3)


def draw(rng, low_friction=False):
    """One random case: block, motion, cor, friction."""
    height = rng.uniform(0.3, 2.0)
    ratio = rng.choice([rng.uniform(0.1, 0.4), rng.uniform(0.4, 1.5)])
    mu_s = rng.uniform(0.02, 0.45) if low_friction else rng.uniform(0.0, 1.0)
    mu_d = mu_s * rng.choice([1.0, rng.uniform(0.5, 1.0)])
    cor = rng.choice([rng.uniform(0.85 if low_friction else 0.5, 1.0), "housner"])
    cor = "housner" if cor == "housner" else float(cor)
    f_h, f_v = rng.uniform(0.5, 5), rng.uniform(0.5, 6)
    a_h = rng.uniform(0.05, 1.0) * G
    a_v = float(rng.choice([0.0, rng.uniform(0, 1.6) * G]))
    phase = rng.uniform(0, 2 * np.pi)
    t = np.arange(0.0, 3.0 + 1e-9, 0.005)
    ramp = np.minimum(t / 0.5, 1.0)
    motion = Motion(t, ramp * a_h * np.sin(2 * np.pi * f_h * t),
                    ramp * a_v * np.sin(2 * np.pi * f_v * t + phase))
    description = (f"Block({height!r}, {float(height * ratio)!r}) cor={cor!r} "
                   f"Friction({mu_s!r}, {float(mu_d)!r}) h=({a_h!r}, {f_h!r}) "
                   f"v=({a_v!r}, {f_v!r}, phase {phase!r})")
    return Block(height, height * ratio), motion, cor, Friction(mu_s, mu_d), description


def differences(reference, planar, block):
    events = np.asarray(planar.events).reshape(-1, 6)
    events = events[events[:, 1] != UNSTABLE_KIND]
    theirs = merged(events[:, [0, 2, 3]])
    mine = merged(zip(reference.event_times, reference.event_mode_before,
                      reference.event_mode_after))
    found = []
    if planar.status != reference.status:
        found.append(f"status {reference.status} vs {planar.status}")
    if len(theirs) != len(mine):
        found.append(f"{len(mine)} vs {len(theirs)} events")
    n = min(len(theirs), len(mine))
    bad = np.flatnonzero((np.abs(theirs[:n, 0] - mine[:n, 0]) > TOLERANCE)
                         | np.any(theirs[:n, 1:] != mine[:n, 1:], axis=1))
    if bad.size:
        i = bad[0]
        found.append(f"event {i}: {mine[i, 0]:.12f} {int(mine[i, 1])}->{int(mine[i, 2])} vs "
                     f"{theirs[i, 0]:.12f} {int(theirs[i, 1])}->{int(theirs[i, 2])}")
    for name, ours, other in (
            ("peak slip", reference.peak_slip, planar.peak_slip),
            ("residual slip", reference.residual_slip, planar.residual_slip),
            ("max|theta|/alpha", reference.max_abs_theta / block.alpha,
             planar.max_abs_theta / block.alpha)):
        if not abs(ours - other) <= TOLERANCE:
            found.append(f"{name} {ours!r} vs {other!r}")
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--runs", type=int, default=25)
    parser.add_argument("--low-friction", action="store_true",
                        help="mu_s in [0.02, 0.45] and cor in [0.85, 1] (capped impacts)")
    arguments = parser.parse_args()
    rng = np.random.default_rng(arguments.seed)
    for index in range(arguments.runs):
        block, motion, cor, friction, description = draw(rng, arguments.low_friction)
        try:
            reference = simulate_reference(block, motion, cor=cor, friction=friction)
            planar = simulate_planar(block, motion, cor=cor, friction=friction)
        except Exception as error:  # report and go on: this is a search for failures
            print(f"#{index} {description}: {type(error).__name__}: {error}", flush=True)
            continue
        modes = "".join(name[0] if seconds > 0 else "-"
                        for name, seconds in reference.time_in_mode.items())
        found = differences(reference, planar, block)
        print(f"#{index} [{modes}] {reference.status} {description}: "
              + ("OK" if not found else "DIFF " + " | ".join(found)), flush=True)


if __name__ == "__main__":
    main()
