"""The fate of a block left rocking on a table at rest, decided by energy.

When the ground motion ends the table is at rest and the block rocks freely.
Whether it will overturn is then settled by its state alone, in closed form:
no free tail has to be run, nor its length guessed.

Exact model (Eq. 2-3, the report's Eq. 2-13 with the table at rest)
-------------------------------------------------------------------
Between impacts the energy per unit I0,

    E = theta'^2 / 2 + p^2 (cos(alpha - |theta|) - cos(alpha)),

is conserved (p^2 = M g R / I0). Its potential part rises from 0 at theta = 0
to the barrier E* = p^2 (1 - cos alpha) at |theta| = alpha and falls beyond
it (to theta = pi/2, where the block lies on its side). An impact (theta
crossing 0, Section 2.7 (5): theta' -> cor theta') happens at zero potential,
so it multiplies E by cor^2. With w = theta' sign(theta) (> 0: moving
outward, away from theta = 0; at theta = 0 a moving block moves outward):

* |theta| > alpha and w >= 0: nothing brings it back; it overturns
  (``"past alpha moving outward"``);
* |theta| > alpha, w < 0 and E < E*: it turns before alpha and falls out
  (``"falls back out before alpha"``); with E > E* it crosses alpha inward,
  reaches theta = 0 with kinetic energy E and impacts (next rule);
* |theta| <= alpha and w > 0: it passes alpha outward, and overturns, iff
  E > E* (``"passes alpha outward"``); otherwise it turns, falls back to
  theta = 0 and impacts with kinetic energy E (w < 0 likewise, at once);
* after an impact the energy is cor^2 E, the block moves outward on the other
  corner and overturns iff cor^2 E > E* (``"passes alpha after one impact"``),
  otherwise every later excursion has less energy still: it is safe
  (``"rocks down"``; ``"at rest"`` for theta = theta' = 0).

So at most one more impact precedes overturning. E = E* exactly (the block
creeping up to the unstable equilibrium theta = alpha forever) counts as safe.

Linearised model (Eq. 2-4, Housner's slender block)
---------------------------------------------------
theta'' = p^2 (theta - alpha sign(theta)) with the table at rest conserves

    E = theta'^2 / 2 + p^2 (alpha |theta| - theta^2 / 2),

whose potential rises from 0 at theta = 0 to E* = p^2 alpha^2 / 2 at
|theta| = alpha and falls without bound past it: passing alpha outward the
linearised block runs away (theta -> infinity), which is what the
linearised literature calls overturning (Housner 1963; Zhang & Makris 2001;
Dimitrakopoulos & DeJong 2012). Impacts are the same map theta' -> cor
theta' at theta = 0, so the rules above hold word for word with this E and E*.
(u = theta/alpha: u' > 1 - u for an outward block with u < 1.)

The package's runs stop at |theta| = pi/2 (``status == "overturned"``): a
result that did so has overturned already. For the ``linear`` method that
stop is the linearised block's runaway exactly when pi/2 exceeds alpha + the
largest |table acceleration| / g (past alpha + |ug|/g the linearised
theta'' is positive whatever the table does); an extremely strong motion on
a stocky block can break that condition, and the run then reports an
overturn the linearised model might have reversed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["FATE_REASONS", "Fate", "free_rocking_fate", "rocking_energy"]

#: Reason codes of :func:`free_rocking_fate`, in the order of the rules above.
FATE_REASONS = ("at rest", "past alpha moving outward", "falls back out before alpha",
                "passes alpha outward", "passes alpha after one impact", "rocks down")


@dataclass(frozen=True)
class Fate:
    """Whether a block left rocking on a table at rest will overturn.

    Attributes
    ----------
    will_overturn : bool
    impacts : int
        Impacts still to come before it overturns (0 or 1); 0 when it does not.
    reason : str
        One of :data:`FATE_REASONS`, or ``"overturned"`` (the run already
        stopped at |theta| = pi/2) or ``"undecided: ..."`` (outside the rules:
        rods, the block airborne).
    energy_ratio : float
        E / E* at the end of the motion [-] (the barrier at |theta| = alpha is 1).
    """

    will_overturn: bool
    impacts: int
    reason: str
    energy_ratio: float

    def __str__(self) -> str:
        verb = "will overturn" if self.will_overturn else "will not overturn"
        return f"{verb} ({self.reason}; E/E* = {self.energy_ratio:.6g})"


def rocking_energy(theta, theta_dot, alpha: float, p: float, model: str = "exact"):
    """Energy per unit I0 of free rocking and its barrier [rad^2/s^2].

    Parameters
    ----------
    theta, theta_dot : array_like
        Rotation [rad] and angular velocity [rad/s].
    alpha, p : float
        Block angle [rad] and frequency parameter [rad/s].
    model : {"exact", "linear"}
        Eq. (2-3) or the slender-block Eq. (2-4).

    Returns
    -------
    energy, barrier : ndarray, float
        E and E* as in the module docstring.
    """
    theta = np.abs(np.asarray(theta, dtype=float))
    kinetic = 0.5 * np.asarray(theta_dot, dtype=float) ** 2
    if model == "exact":
        return (kinetic + p * p * (np.cos(alpha - np.minimum(theta, math.pi / 2))
                                   - math.cos(alpha)), p * p * (1.0 - math.cos(alpha)))
    if model == "linear":
        return kinetic + p * p * (alpha * theta - 0.5 * theta * theta), 0.5 * (p * alpha) ** 2
    raise ValueError(f"model must be 'exact' or 'linear', got {model!r}")


def free_rocking_fate(theta, theta_dot, alpha: float, p: float, cor: float,
                      model: str = "exact"):
    """Fate of blocks rocking freely from (theta, theta_dot) on a table at rest.

    Parameters
    ----------
    theta, theta_dot : array_like
        State when the motion ends [rad], [rad/s] (signed theta, Section 2.7).
    alpha, p : float
        Block angle [rad] and frequency parameter [rad/s].
    cor : float
        Coefficient of restitution [-], theta' -> cor theta' at each impact.
    model : {"exact", "linear"}
        The exact Eq. (2-3) or the linearised Eq. (2-4) (the ``linear`` method).

    Returns
    -------
    overturns : ndarray of bool
    impacts : ndarray of int
        Impacts before it overturns (0 or 1); 0 for a block that does not.
    reasons : ndarray of int
        Index into :data:`FATE_REASONS`.
    energy_ratio : ndarray of float
        E / E* [-].
    """
    signed = np.asarray(theta, dtype=float)
    rate = np.asarray(theta_dot, dtype=float)
    # > 0: moving outward; at theta = 0 a moving block moves outward on the side it heads to
    omega = np.where(signed == 0.0, np.abs(rate), rate * np.sign(signed))
    energy, barrier = rocking_energy(signed, rate, alpha, p, model)
    magnitude = np.abs(signed)
    outward = omega >= 0.0
    past = magnitude > alpha
    at_rest = (signed == 0.0) & (rate == 0.0)
    now_past = past & outward
    falls_out = past & ~outward & (energy < barrier)
    passes = ~past & (omega > 0.0) & (energy > barrier)
    now = now_past | falls_out | passes
    later = ~now & ~at_rest & (cor * cor * energy > barrier)
    reasons = np.select([at_rest, now_past, falls_out, passes, later], [0, 1, 2, 3, 4], 5)
    return now | later, np.where(later, 1, 0), reasons, energy / barrier


def fate_of(theta: float, theta_dot: float, alpha: float, p: float, cor: float,
            model: str = "exact") -> Fate:
    """:func:`free_rocking_fate` of one state, as a :class:`Fate`."""
    overturns, impacts, reasons, ratio = free_rocking_fate(theta, theta_dot, alpha, p, cor,
                                                           model)
    return Fate(bool(overturns), int(impacts), FATE_REASONS[int(reasons)], float(ratio))
