"""Impacts of a stack: the plastic, no-slip multi-contact law (default) and a constant COR.

Plastic law
-----------
At an impact every corner at zero gap may carry an impulse: both corners of the impacting
interface and of every flat interface, the pivot of every open one. A candidate *active
set* is a post-impact pattern: each interface at zero gap flat (both corners active), or
pivoting on one corner (that corner active, the other free); an open interface keeps its
pivot. The active corners stick (no slip) and stay closed (plastic), so the post-impact
velocities lie in the pattern's velocity space ``theta' = T q'`` and the impulses do no
work on it; projecting the momentum balance ``M_f (V+ - V-) = W Lambda`` on that space:

    (T^T M+ T) q'+ = T^T J+^T M_f V-,      V- = J- theta'-

(``M_f`` the blocks' masses and centroidal inertias, ``J-``/``J+`` the velocity maps of the
pre- and post-impact pivots; for one block, the conservation of angular momentum about the
new corner, which gives Housner's r = 1 - 1.5 sin^2(alpha)). The candidate is admissible
when every active corner's normal impulse is >= 0 and every free corner at zero gap
separates (``s_j phi_j'+ >= 0``); the complementarity is enumerated over the candidates.
The kinetic energy after is the M_f-norm of a projection of V-: it never rises.

Constant COR (``impact="cor"``)
--------------------------------
The report's law (Section 2.7 (5)) for every block: ``theta_i'+ = cor theta_i'-`` (each
absolute rate scaled, same sign); the impacting interface moves to its other corner, the
other interfaces keep their pattern. For one block it is the single-block engine's law.
It is a rule, not mechanics: the energy after may exceed the energy before when the
post-impact pivots carry more inertia (the result records it).
"""

from __future__ import annotations

import numpy as np

from shaketable.models.stack.physics import (
    Chain,
    candidate_levels,
    interface_loads,
    kinematics,
    mass_matrix,
)
from shaketable.models.stack.pivot import pivot_candidate, solve_impact_lcp

#: Relative rounding of the impulses computed from the whole motion's momenta.
ROUNDING = 1e-6
#: Up to this many blocks every active set is tried (and the admissible ones counted);
#: above it the search stops after the fewest open interfaces that give an admissible one.
FULL_ENUMERATION = 3
#: Relative tolerance of the admissibility tests (impulses, separating velocities).
IMPACT_TOLERANCE = 1e-9


def plastic_impact(chain: Chain, phi, phi_dot, pattern, interface: int, closed=()):
    """Post-impact ``phi'`` and pattern of the plastic, no-slip multi-contact law.

    ``phi[interface]`` is zero (the landing); ``pattern`` the pattern before. Returns
    ``(phi_dot_after, pattern_after, admissible, impulses)``: ``admissible`` is the number
    of admissible active sets (1: unique), ``impulses`` the (n, 4) impulses [N s] of the
    chosen one (see :func:`~shaketable.models.stack.physics.interface_loads`). Up to
    FULL_ENUMERATION blocks every active set is tried: with more than one admissible the
    one with the fewest open interfaces is kept; with none, the one whose worst violation is
    least. Above, the complementarity pivot's solution (:mod:`~shaketable.models.stack.
    pivot`) is kept: the one admissible set, or, with none (a pivot pulls: the impact throws
    a block into flight, outside the model), the solution with the pivots held; only where
    the pivot finds none (a flight) are the sets enumerated, by increasing number of open
    interfaces. ``closed``: interfaces held flat (the end of a cascade summed in closed
    form).
    """
    theta, theta_dot = np.cumsum(phi), np.cumsum(phi_dot)
    centroid, before_map, _ = kinematics(chain, theta, theta_dot, pattern)
    velocity = np.einsum("iak,k->ia", before_map, theta_dot)
    # the impulses and the rebounds scale with the landing's approach rate (the rest of the
    # motion needs none): the tolerances are relative to it, above the rounding of the
    # momenta of the whole motion
    landing = abs(phi_dot[interface]) + ROUNDING * np.abs(theta_dot).max() + 1e-300
    impulse_tolerance = (IMPACT_TOLERANCE * chain.m.sum() * landing
                         * float(np.hypot(chain.b, chain.h).max()))
    rate_tolerance = IMPACT_TOLERANCE * landing
    free = [j for j in range(chain.n) if phi[j] == 0.0]
    start = list(pattern)
    start[interface] = 0

    def evaluate(candidate):
        """(worst violation, open interfaces, candidate, phi' after, impulses)."""
        _, after_map, _ = kinematics(chain, theta, theta_dot, candidate)
        columns = [j for j, s in enumerate(candidate) if s != 0]
        theta_after = np.zeros(chain.n)
        if columns:
            t = chain.lower[:, columns]
            momentum = np.einsum("iak,i,ia->k", after_map, chain.m, velocity) \
                + chain.inertia * theta_dot
            matrix = t.T @ mass_matrix(chain, after_map) @ t
            theta_after = t @ np.linalg.solve(matrix, t.T @ momentum)
        change = np.einsum("iak,k->ia", after_map, theta_after) - velocity
        impulses = interface_loads(chain, candidate, theta, centroid,
                                   chain.m[:, None] * change,
                                   chain.inertia * (theta_after - theta_dot))
        phi_after = np.diff(theta_after, prepend=0.0)
        violation = max(0.0, -impulses[:, 2:].min() / impulse_tolerance)
        for j in free:
            if candidate[j] != 0:
                violation = max(violation, -candidate[j] * phi_after[j] / rate_tolerance)
        return violation, sum(s != 0 for s in candidate), candidate, phi_after, impulses

    if chain.n > FULL_ENUMERATION:
        chosen = _pivot_choice(chain, theta, theta_dot, velocity, centroid, phi, start, closed,
                               (rate_tolerance * 2.0 * float(chain.b.max()), impulse_tolerance),
                               evaluate)
        if chosen is not None:
            return chosen
    found: list[tuple] = []
    for candidate in (c for level in candidate_levels(tuple(start), free) for c in level):
        if any(candidate[j] != 0 for j in closed):
            continue
        if chain.n > FULL_ENUMERATION and any(item[0] <= 1.0 and item[1] < sum(
                s != 0 for s in candidate) for item in found):
            break   # an admissible set with fewer open interfaces is already found
        found.append(evaluate(candidate))
    admissible = [item for item in found if item[0] <= 1.0]
    pool = admissible if admissible else found
    best = min(pool, key=lambda item: (item[1], item[0]) if admissible else item[0])
    return _result(best, len(admissible))


def _result(item, admissible: int):
    """What :func:`plastic_impact` returns for the chosen ``item`` of its evaluation."""
    phi_after = item[3].copy()
    pattern_after = list(item[2])
    phi_after[[j for j, s in enumerate(pattern_after) if s == 0]] = 0.0
    return phi_after, tuple(pattern_after), admissible, item[4]


def _pivot_choice(chain, theta, theta_dot, velocity, centroid, phi, start, closed,
                  tolerances, evaluate):
    """The complementarity pivot's choice (:func:`plastic_impact`), or None (a flight, or
    no convergence): first with the corners that separate within the tolerances closed (as few
    interfaces open as the tolerances allow), then as solved."""
    solution = solve_impact_lcp(chain, theta, theta_dot, velocity, centroid, phi, start,
                                closed)
    if solution is None:
        return None
    tried = []
    for rate_tolerance, impulse_tolerance in (tolerances, (-1.0, -1.0)):
        candidate = pivot_candidate(solution, phi, start, rate_tolerance, impulse_tolerance)
        if candidate is None:
            continue
        item = evaluate(candidate)
        if item[0] <= 1.0:
            return _result(item, 1)
        tried.append(item)
    return _result(min(tried, key=lambda item: item[0]), 0) if tried else None


def cor_impact(chain: Chain, phi, phi_dot, pattern, interface: int, cor: float):
    """Post-impact ``phi'`` and pattern of the constant-COR law (every absolute rate times
    ``cor``; the impacting interface onto its other corner)."""
    theta_after = cor * np.cumsum(phi_dot)
    phi_after = np.diff(theta_after, prepend=0.0)
    pattern_after = list(pattern)
    pattern_after[interface] = -pattern[interface]
    if phi_after[interface] == 0.0:
        pattern_after[interface] = 0
    return phi_after, tuple(pattern_after)
