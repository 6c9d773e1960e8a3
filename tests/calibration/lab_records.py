"""Free-rocking records made as a lab makes them, by a generator independent of the package.

Nothing of ``shaketable`` is used to make the record: the rocking equation of a rigid
block on a rigid base (Housner; the report's Eq. 2-3 for free rocking),

    theta'' = -p^2 sin(alpha - theta)   (theta > 0),   theta'' = p^2 sin(alpha + theta)   (theta < 0),

p^2 = 3 g / (4 R), is integrated by SciPy's ``solve_ivp`` (DOP853, rtol 1e-11) from
one impact (theta = 0, an event) to the next; at each impact theta' is multiplied by
the COR of that impact (Eq. 2-6), which may be constant, drawn per impact from
N(mean, sigma^2), or a function of the impact velocity. The top displacement of the
30 x 6 in block, x = -H sin(theta) - sign(theta) (B/2) (1 - cos(theta)), goes through a
4-pole 20 Hz *analog* Butterworth filter (``scipy.signal.lsim`` of the continuous
signal on a 2 kHz grid), is sampled at 50 samples/s at an unknown phase, and gets
white noise, an offset and a 12-bit ADC over +-15 in. The file is written as a DAQ
exports it: ``Time (sec),WP1 Top Disp (in)``.

Used by ``tests/calibration/test_scatter.py`` and ``benchmarks/calibration_scatter.py``.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import scipy.integrate
import scipy.signal

G = 9.80665
INCH = 0.0254
HEIGHT, WIDTH = 30 * INCH, 6 * INCH            # the report's 30 x 6 in block [m]
HEADER = "Time (sec),WP1 Top Disp (in)"


@dataclass(frozen=True)
class LabRecord:
    """A generated record: times [s], top displacement [in] as written, and the truth."""

    t: np.ndarray
    displacement_in: np.ndarray
    cors: np.ndarray = field(repr=False)      # the COR of each impact [-]
    impact_velocities: np.ndarray = field(repr=False)   # |theta'| before each impact [rad/s]
    theta0: float = 0.0
    t_release: float = 0.0

    def write(self, path: Path | str, header: str = HEADER, time_scale: float = 1.0) -> Path:
        """The record as a CSV file (``time_scale`` 1000 writes milliseconds)."""
        path = Path(path)
        lines = [header] + [f"{t * time_scale:.6f},{x:.5f}"
                            for t, x in zip(self.t, self.displacement_in)]
        path.write_text("\n".join(lines) + "\n")
        return path


def rocking(theta0: float, cor_of_impact: Callable[[int, float], float], duration: float,
            height: float = HEIGHT, width: float = WIDTH):
    """Free rocking from theta0 at rest: (piecewise dense solutions, impact CORs, velocities).

    ``cor_of_impact(n, omega)`` is the COR of the n-th impact (0-based) at the impact
    angular velocity |omega| [rad/s]. Integration stops when an amplitude falls below
    1e-6 rad (the block then rests at theta = 0) or at ``duration``.
    """
    b, h = width / 2, height / 2
    R, alpha = math.hypot(b, h), math.atan2(b, h)
    p2 = 3 * G / (4 * R)

    def rhs(_, y):
        theta, omega = y
        s = 1.0 if theta > 0 else -1.0
        return [omega, -s * p2 * math.sin(alpha - s * theta)]

    def crossing(_, y):
        return y[0]

    crossing.terminal = True
    pieces, cors, velocities = [], [], []
    t0, y0 = 0.0, [theta0, 0.0]
    n = 0
    while t0 < duration:
        # start a hair off theta = 0 so the event is not the starting point
        solution = scipy.integrate.solve_ivp(rhs, (t0, duration), y0, method="DOP853",
                                             rtol=1e-11, atol=1e-14, events=crossing,
                                             dense_output=True)
        pieces.append((t0, solution.t[-1], solution.sol))
        if solution.status != 1:
            break
        t_hit = float(solution.t_events[0][0])
        omega = float(solution.y_events[0][0][1])
        cor = float(cor_of_impact(n, abs(omega)))
        cors.append(cor)
        velocities.append(abs(omega))
        # cos(alpha - theta_next) - cos(alpha) = (cor omega)^2 / (2 p^2) ~ sin(alpha) theta_next:
        # below 1e-6 rad of amplitude (1e-3 of a 12-bit step) the block is at rest
        if (cor * omega) ** 2 / (2 * p2) < math.sin(alpha) * 1e-6:
            pieces.append((t_hit, duration, None))
            break
        # the next half cycle starts at theta = 0 on the other side, nudged by omega dt
        nudge = 1e-9
        t0 = t_hit + nudge
        y0 = [cor * omega * nudge, cor * omega]
        n += 1
    return pieces, np.array(cors), np.array(velocities)


def theta_on(times: np.ndarray, pieces, theta0: float) -> np.ndarray:
    """theta [rad] at ``times`` (measured from the release; theta0 before it)."""
    out = np.full(times.shape, theta0)
    for start, stop, solution in pieces:
        inside = (times >= start) & (times <= stop)
        if solution is None:
            out[times >= start] = 0.0
        elif np.any(inside):
            out[inside] = solution(times[inside])[0]
    return out


def lab_record(seed: int, *, cor: float = 0.9, sigma: float = 0.0,
               velocity_slope: float = 0.0, theta0_ratio: tuple[float, float] = (0.3, 0.7),
               duration: float = 10.0, rate: float = 50.0, cutoff: float = 20.0,
               noise_in: float = 0.005, offset_in: float | None = None) -> LabRecord:
    """One record: COR ``cor`` (+ N(0, sigma^2) per impact, + ``velocity_slope`` x (|omega| -
    0.4 rad/s)), released from a random angle in ``theta0_ratio`` alpha at a random time.

    A function of its arguments only (the seed fixes every draw): made once per process for
    each set of arguments (about 0.3 s of CPU; several tests read the same record), and
    each caller gets arrays of its own."""
    made = _lab_record(seed, cor, sigma, velocity_slope, tuple(theta0_ratio), duration, rate,
                       cutoff, noise_in, offset_in)
    return LabRecord(made.t.copy(), made.displacement_in.copy(), made.cors.copy(),
                     made.impact_velocities.copy(), made.theta0, made.t_release)


@functools.lru_cache(maxsize=16)
def _lab_record(seed, cor, sigma, velocity_slope, theta0_ratio, duration, rate, cutoff,
                noise_in, offset_in) -> LabRecord:
    rng = np.random.default_rng(seed)
    alpha = math.atan2(WIDTH / 2, HEIGHT / 2)
    theta0 = rng.uniform(*theta0_ratio) * alpha
    before = rng.uniform(0.3, 1.5)
    draws = rng.normal(0.0, 1.0, 400)
    offset = rng.uniform(-0.3, 0.3) if offset_in is None else offset_in

    def cor_of_impact(n: int, omega: float) -> float:
        value = cor + sigma * draws[n % draws.size] + velocity_slope * (omega - 0.4)
        return min(max(value, 0.05), 0.999)

    pieces, cors, velocities = rocking(theta0, cor_of_impact, duration - before)
    fine_rate = 2000.0
    phase = rng.uniform(0.0, 1.0 / rate)
    t_fine = np.arange(-before - 0.5, duration - before, 1.0 / fine_rate)
    theta = theta_on(t_fine, pieces, theta0)
    x = -HEIGHT * np.sin(theta) - np.sign(theta) * (WIDTH / 2) * (1 - np.cos(theta))
    b, a = scipy.signal.butter(4, 2 * math.pi * cutoff, analog=True)
    system = scipy.signal.StateSpace(*scipy.signal.tf2ss(b, a))
    steady = -np.linalg.solve(system.A, system.B[:, 0] * x[0])
    _, filtered, _ = scipy.signal.lsim(system, x, t_fine - t_fine[0], X0=steady)
    t = np.arange(-before + phase, duration - before, 1.0 / rate)
    sampled = np.interp(t, t_fine, filtered) / INCH
    sampled = sampled + offset + noise_in * rng.normal(size=t.size)
    lsb = 30.0 / 4096
    digitized = np.clip(np.round(sampled / lsb) * lsb, -15.0, 15.0 - lsb)
    clock = rng.uniform(0.0, 5.0)
    return LabRecord(t + before + clock, digitized, cors, velocities, theta0, before + clock)
