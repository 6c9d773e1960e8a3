"""Moreau-Jean time stepping of the planar block: an independent check of the planar engine.

A different formulation from the compiled event-driven engine
(:mod:`shaketable.models.planar.run`) and from the SciPy reference
(:mod:`shaketable.models.planar.reference`): no modes, no events, no impact law
written out. Both bottom corners are unilateral contacts with Coulomb friction at the
velocity level; impacts are the plastic Newton law (normal restitution 0), which is the
planar model with ``cor="housner"`` (docs/planar.md, "Impacts"). It converges at first
order in the step (the contact set and the impacts are resolved to one step).

Scheme (per unit mass, table frame, q = (x, y, theta) of the centre [m, m, rad], the
conventions of docs/planar.md; M = diag(1, 1, Ic)):

* theta-method with theta = 1/2 on the positions (Moreau's midpoint): q_m = q + h/2 v;
* the contacts active at the step are the corners whose gap y_m + r_y(theta_m) <= 0;
* the free velocity v_f = v + h f(t + h/2), f = (-ug, -(g + vg), 0);
* the local contact problem v+ = v_f + M^-1 W P (W: each active corner's normal
  (0, 1, r_x) and tangent (1, 0, -r_y) directions) is a small LCP: every status of each
  active corner (off; stick, |P_t| <= mu_s P_n; slip either way, P_t = -/+ mu_d P_n) is
  solved as a linear system and the first consistent one (P_n >= 0, normal velocity
  >= 0, slip along its sign) is taken: the problem is solved exactly, not iterated;
* q+ = q_m + h/2 v+.

Numpy only (no compiled code): a few tens of microseconds per step.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.core.validation import positive
from shaketable.models.sliding.result import Friction

#: Statuses of an active contact in the enumeration: off, stick, slip toward +x, toward -x.
_OFF, _STICK, _SLIP_PLUS, _SLIP_MINUS = range(4)


def contact_step(free, active, inverse_mass, mu_s, mu_d=None):
    """The velocity after one step's contact impulses, the contact problem solved exactly.

    Parameters
    ----------
    free : numpy.ndarray
        Free velocity (x', y', theta') at the end of the step [m/s, m/s, rad/s].
    active : sequence of (side, normal, tangent)
        The active corners: side (+1 or -1), their normal (0, 1, r_x) and tangent
        (1, 0, -r_y) directions [-, -, m].
    inverse_mass : numpy.ndarray
        diag(M)^-1 per unit mass [-, -, 1/m^2].
    mu_s, mu_d : float
        Static and dynamic friction [-] (``mu_d`` default ``mu_s``).

    Returns
    -------
    velocity : numpy.ndarray
        The velocity after the impulses [m/s, m/s, rad/s].
    pushing : tuple of float
        The sides of the corners that push (positive normal impulse status).

    Raises
    ------
    RuntimeError
        No status combination is consistent (not met for a rigid block with mu finite).
    """
    mu_d = mu_s if mu_d is None else mu_d
    tolerance = 1e-12 * (1.0 + np.abs(free).max())
    for statuses in itertools.product(range(4), repeat=len(active)):
        on = [(contact, status) for contact, status in zip(active, statuses) if status]
        if not on:
            if all(normal @ free >= -tolerance for _, normal, _ in active):
                return free, ()
            continue
        w = np.array([vector * inverse_mass for (_, normal, tangent), _ in on
                      for vector in (normal, tangent)]).T
        matrix = np.zeros((w.shape[1], w.shape[1]))
        rhs = np.zeros(w.shape[1])
        for index, ((_, normal, tangent), status) in enumerate(on):
            matrix[2 * index] = normal @ w
            rhs[2 * index] = -normal @ free
            if status == _STICK:
                matrix[2 * index + 1] = tangent @ w
                rhs[2 * index + 1] = -tangent @ free
            else:   # P_t = -mu_d P_n slipping toward +x, +mu_d P_n toward -x
                matrix[2 * index + 1, 2 * index] = mu_d if status == _SLIP_PLUS else -mu_d
                matrix[2 * index + 1, 2 * index + 1] = 1.0
        try:
            impulses = np.linalg.solve(matrix, rhs)
        except np.linalg.LinAlgError:
            continue
        velocity = free + w @ impulses
        consistent = all(normal @ velocity >= -tolerance for _, normal, _ in active)
        for index, ((_, _, tangent), status) in enumerate(on):
            normal_impulse, tangent_impulse = impulses[2 * index], impulses[2 * index + 1]
            slip = tangent @ velocity
            consistent &= normal_impulse >= -tolerance and (
                abs(tangent_impulse) <= mu_s * normal_impulse + tolerance
                if status == _STICK
                else (slip >= -tolerance if status == _SLIP_PLUS else slip <= tolerance))
        if consistent:
            return velocity, tuple(side for (side, _, _), _ in on)
    raise RuntimeError("Moreau-Jean step: no consistent contact status")


@dataclass(frozen=True)
class MoreauJeanResult:
    """A Moreau-Jean run: the states at every step and what the study compares.

    Attributes
    ----------
    t, x, y, theta : numpy.ndarray
        Time [s], centre relative to the table [m] and rotation [rad] at every step.
    pushing : tuple of tuple
        The sides of the corners that push at each step (one entry per step).
    step : float
        Time step h [s].
    max_abs_theta : float
        max |theta| up to the end or the overturn [rad].
    peak_slip : float
        max |x + h sin theta|, the same measure as the planar results' ``peak_slip`` [m].
    t_overturn : float
        First time |theta| reaches pi/2 (linear between steps) [s]; NaN if it does not.
    """

    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    theta: np.ndarray
    pushing: tuple
    step: float
    max_abs_theta: float
    peak_slip: float
    t_overturn: float
    statistics: dict = field(default_factory=dict)

    @property
    def overturned(self) -> bool:
        """Whether |theta| reached pi/2."""
        return bool(math.isfinite(self.t_overturn))

    @property
    def status(self) -> str:
        """``"overturned"`` or ``"completed"``."""
        return "overturned" if self.overturned else "completed"

    def to_frame(self):
        """The steps as a pandas DataFrame: t [s], x [m], y [m], theta [rad]."""
        import pandas as pd

        return pd.DataFrame({"t [s]": self.t, "x [m]": self.x, "y [m]": self.y,
                             "theta [rad]": self.theta})

    def plot(self, ax=None):
        """theta against t; returns the matplotlib Axes."""
        from shaketable.plots.base import pyplot

        if ax is None:
            _, ax = pyplot().subplots(figsize=(6, 3))
        ax.plot(self.t, self.theta, linewidth=1.0)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("θ [rad]")
        ax.set_title(f"Moreau-Jean, h = {self.step:g} s", fontsize=9)
        return ax


def _ground(motion: Motion | None, times: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Table accelerations [m/s^2] at ``times``, linear between samples (0 past the end)."""
    if motion is None:
        return np.zeros_like(times), np.zeros_like(times)
    t = np.asarray(motion.t, dtype=float)
    return (np.interp(times, t, motion.horizontal, right=0.0),
            np.interp(times, t, motion.vertical_or_zero, right=0.0))


def simulate_moreau_jean(block: Block, motion: Motion | None = None, *,
                         friction: Friction, step: float, duration: float | None = None,
                         state=None, t0: float | None = None) -> MoreauJeanResult:
    """Run the Moreau-Jean scheme (module docstring) on the planar block.

    Parameters
    ----------
    block : Block
        The block (B x H).
    motion : Motion, optional
        Horizontal (+x) and vertical (up) table accelerations [m/s^2], linear between
        samples; None: the table at rest.
    friction : Friction
        mu_s (sticking impulses) and mu_d (slipping impulses) [-].
    step : float
        Time step h [s].
    duration : float, optional
        Time to run [s]; default the motion's duration from ``t0``.
    state : sequence of 6 floats, optional
        (x, y, theta, x', y', theta') at ``t0`` [m, m, rad, m/s, m/s, rad/s]; default at
        rest on the table (0, h, 0, 0, 0, 0).
    t0 : float, optional
        Start time [s]; default the motion's first sample (0 without a motion).

    Returns
    -------
    MoreauJeanResult
        Stops at the step where |theta| passes pi/2 (overturned).
    """
    if not isinstance(block, Block):
        raise TypeError(f"block must be a Block, got {type(block).__name__}")
    if not isinstance(friction, Friction):
        raise TypeError(f"friction must be a Friction, got {type(friction).__name__}")
    step = positive("step", step, " [s]")
    start = (float(motion.t[0]) if motion is not None else 0.0) if t0 is None else float(t0)
    if duration is None:
        if motion is None:
            raise ValueError("duration [s] is needed without a motion")
        duration = float(motion.t[-1]) - start
    duration = positive("duration", duration, " [s]")
    b, h = block.b, block.h
    inverse_mass = np.array([1.0, 1.0, 3.0 / (b * b + h * h)])
    initial = (0.0, h, 0.0, 0.0, 0.0, 0.0) if state is None else state
    if len(initial) != 6:
        raise ValueError(f"state must have 6 entries (x, y, theta and rates), got "
                         f"{len(initial)}")
    q, v = np.array(initial[:3], float), np.array(initial[3:], float)
    count = int(round(duration / step))
    ug, vg = _ground(motion, start + (np.arange(count) + 0.5) * step)
    positions, pushing = [q.copy()], []
    t_overturn = math.nan
    for index in range(count):
        middle = q + 0.5 * step * v
        cosine, sine = math.cos(middle[2]), math.sin(middle[2])
        active = []
        for side in (1.0, -1.0):
            r_x, r_y = -side * b * cosine + h * sine, -side * b * sine - h * cosine
            if middle[1] + r_y <= 0.0:   # the corner's gap at the midpoint
                active.append((side, np.array([0.0, 1.0, r_x]), np.array([1.0, 0.0, -r_y])))
        free = v + step * np.array([-ug[index], -(G + vg[index]), 0.0])
        v, touching = (contact_step(free, active, inverse_mass, friction.static,
                                    friction.dynamic) if active else (free, ()))
        previous, q = q[2], middle + 0.5 * step * v
        positions.append(q.copy())
        pushing.append(touching)
        if abs(q[2]) >= 0.5 * math.pi:
            fraction = (0.5 * math.pi - abs(previous)) / (abs(q[2]) - abs(previous))
            t_overturn = start + (index + fraction) * step
            break
    states = np.array(positions)
    t = start + step * np.arange(len(states))
    inside = states if not math.isfinite(t_overturn) else states[:-1]
    slip = inside[:, 0] + h * np.sin(inside[:, 2])
    return MoreauJeanResult(
        t=t, x=states[:, 0], y=states[:, 1], theta=states[:, 2], pushing=tuple(pushing),
        step=step,
        max_abs_theta=(0.5 * math.pi if math.isfinite(t_overturn)
                       else float(np.max(np.abs(states[:, 2])))),
        peak_slip=float(np.max(np.abs(slip))), t_overturn=t_overturn,
        statistics={"steps": len(pushing)})
