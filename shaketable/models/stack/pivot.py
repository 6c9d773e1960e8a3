"""The plastic law's impact as a linear complementarity problem, solved by a pivot.

Written in the blocks' full coordinates (x, y, theta of each centroid; the mass matrix
``M = diag(m, m, I)``), the rows are, at each interface at zero gap, the normal velocities
of the upper block's two bottom corners relative to the body below and the tangential one
(no slip), and at each interface open at a gap the normal and tangential velocities at its
pivot; ``w = J v- + W lambda`` with ``W = J M^-1 J^T`` are the velocities after the impact.
The tangential rows, the pivots and the corners of the interfaces held flat are
equalities (``w = 0``), every other normal row a complementarity pair (``lambda >= 0``,
``w >= 0``, ``lambda w = 0``). Every admissible active set of the plastic law
(:mod:`shaketable.models.stack.impact`) is a solution of it. The rows are independent (at
most three per interface, each fixing the upper block's motion relative to the lower one),
so that ``W`` and its Schur complement on the pairs are positive definite: a P-matrix,
whose LCP has exactly one solution. The admissible post-impact velocities are therefore
unique (two admissible sets differ only at corners where both ``lambda`` and ``w`` vanish,
with the same velocities), and Murty's least-index principal pivoting method, finite on a
P-matrix, finds them. The compiled engine's version is
:mod:`shaketable.models.stack.compiled_lcp` (the same rows, order and pivots).
"""

from __future__ import annotations

import numpy as np

#: Murty's pivots allowed per row before giving up (the law then enumerates).
PIVOTS_PER_ROW = 4
#: Relative rounding below which an impulse or a velocity of the pivot counts as zero.
PIVOT_ROUNDING = 1e-12


def impact_rows(chain, theta, centroid, phi, start, held=()):
    """The LCP's rows: coefficients (rows, 6) (the upper block's x, y, theta, then the lower
    block's), the interface of each row, whether it is a complementarity pair, its corner
    (-1, +1 the bottom corners, 0 the tangential row)."""
    coefficients, interfaces, pairs, corners = [], [], [], []

    def add(j, pair, corner, px, py, dx, dy):
        upper = [dx, dy, (px - centroid[j, 0]) * dy - (py - centroid[j, 1]) * dx]
        lower = [0.0, 0.0, 0.0] if j == 0 else [
            -dx, -dy, -((px - centroid[j - 1, 0]) * dy - (py - centroid[j - 1, 1]) * dx)]
        coefficients.append(upper + lower)
        interfaces.append(j)
        pairs.append(pair)
        corners.append(corner)

    for j in range(chain.n):
        below = theta[j - 1] if j > 0 else 0.0
        nx, ny = -np.sin(below), np.cos(below)
        tx, ty = ny, -nx
        cosine, sine = np.cos(theta[j]), np.sin(theta[j])
        bottom_x = centroid[j, 0] + sine * chain.h[j]
        bottom_y = centroid[j, 1] - cosine * chain.h[j]
        if phi[j] == 0.0:
            pair = j not in held
            for corner in (-1, 1):
                add(j, pair, corner, bottom_x + corner * cosine * chain.b[j],
                    bottom_y + corner * sine * chain.b[j], nx, ny)
            add(j, False, 0, bottom_x, bottom_y, tx, ty)
        else:
            corner = -int(start[j])   # the pivot: the -x corner for +1
            px = bottom_x + corner * cosine * chain.b[j]
            py = bottom_y + corner * sine * chain.b[j]
            add(j, False, corner, px, py, nx, ny)
            add(j, False, corner, px, py, tx, ty)
    return (np.array(coefficients), np.array(interfaces), np.array(pairs, dtype=bool),
            np.array(corners))


def solve_impact_lcp(chain, theta, theta_dot, velocity, centroid, phi, start, held=()):
    """The LCP's solution: ``(lambda, w, basis, rows, diagonal)`` (``basis``: the pairs
    whose impulse is basic; ``rows`` as :func:`impact_rows`' last three; ``diagonal``: W's),
    or None when Murty's pivot does not converge."""
    coefficients, interfaces, pairs, corners = impact_rows(chain, theta, centroid, phi, start,
                                                           held)
    count = interfaces.size
    inverse = np.stack([1.0 / chain.m, 1.0 / chain.m, 1.0 / chain.inertia], axis=1)
    jacobian = np.zeros((count, 3 * chain.n))
    for r, j in enumerate(interfaces):
        jacobian[r, 3 * j:3 * j + 3] = coefficients[r, :3]
        if j > 0:
            jacobian[r, 3 * j - 3:3 * j] = coefficients[r, 3:]
    delassus = (jacobian * inverse.ravel()) @ jacobian.T
    v_before = np.column_stack([velocity, theta_dot]).ravel()
    q = jacobian @ v_before
    basis = pairs.copy()   # every corner closed: no interface opened
    scale_w = np.abs(q).max() + 1e-300
    for _ in range(PIVOTS_PER_ROW * count + 8):
        active = ~pairs | basis
        lam = np.zeros(count)
        lam[active] = np.linalg.solve(delassus[np.ix_(active, active)], -q[active])
        w = q + delassus @ lam
        scale_lambda = np.abs(lam).max() + 1e-300
        wrong = pairs & ((basis & (lam < -PIVOT_ROUNDING * scale_lambda))
                         | (~basis & (w < -PIVOT_ROUNDING * scale_w)))
        if not wrong.any():
            return lam, w, basis, (interfaces, pairs, corners), np.diag(delassus).copy()
        first = int(np.argmax(wrong))
        basis[first] = not basis[first]
    return None


def pivot_candidate(solution, phi, start, rate_tolerance, impulse_tolerance):
    """The active set of the LCP's solution: a corner closed where its impulse is basic, or
    where it separates so slowly that closing it would take an impulse within the law's
    tolerance (at most ``rate_tolerance`` [m/s], or ``impulse_tolerance`` [N s] times its
    diagonal of W; negative tolerances: as solved); None when both corners of an interface
    lift (a flight: outside the model)."""
    _, w, basis, (interfaces, pairs, corners), diagonal = solution
    candidate = [int(s) if phi[j] != 0.0 else 0 for j, s in enumerate(start)]
    for r in np.flatnonzero(pairs & (corners == -1)):
        j = int(interfaces[r])
        left = bool(basis[r]) or w[r] <= max(rate_tolerance, impulse_tolerance * diagonal[r])
        right = bool(basis[r + 1]) or w[r + 1] <= max(rate_tolerance,
                                                      impulse_tolerance * diagonal[r + 1])
        if left and right:
            candidate[j] = 0
        elif left:
            candidate[j] = 1   # the pivot on the -x corner
        elif right:
            candidate[j] = -1
        else:
            return None
    return tuple(candidate)
