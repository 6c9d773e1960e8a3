"""The plastic law's active set found by a complementarity pivot, compiled (numba).

The plastic, no-slip multi-contact law (:mod:`shaketable.models.stack.impact`) keeps the
active set whose corners all carry a normal impulse >= 0 and whose free corners at zero
gap separate. Written in the blocks' full coordinates (x, y, theta of each centroid, the
mass matrix ``M = diag(m, m, I)``), every candidate is a solution of one linear
complementarity problem (LCP) in the corners' impulses: the rows are

* at each interface at zero gap, the normal velocity of the upper block's two bottom
  corners relative to the block (or table) below, and the tangential one (no slip);
* at each interface open at a gap, the normal and tangential velocity at its pivot;

with ``w = J v- + W lambda`` (``W = J M^-1 J^T``, the Delassus matrix) the velocities after
the impact; the tangential rows, the pivots of open interfaces and the corners of the
interfaces held flat are equalities (``w = 0``), every other normal row a complementarity
pair (``lambda >= 0``, ``w >= 0``, ``lambda w = 0``). An admissible candidate of the law
is a solution of this LCP (an active corner: ``w = 0``, ``lambda >= 0``; a free corner:
``lambda = 0``, ``w >= 0``). The rows of ``J`` are independent (at most three per
interface, each fixing the upper block's motion relative to the lower one: two normal
velocities at distinct points and a tangential one), so that ``W`` is positive definite
and so is its Schur complement on the complementarity rows: a P-matrix, whose LCP has
exactly one solution for every ``J v-``. Hence the law's admissible post-impact velocities
are unique (two admissible candidates can differ only at a corner with ``lambda = w = 0``,
where both give the same velocities), and the one solution is found by Murty's
least-index principal pivoting method, finite on a P-matrix.

The solution's candidate (an interface flat where both its corners stay closed, pivoting
on the one that does where one lifts) is handed back to the law, which computes its rates
and impulses as it does any candidate's (:func:`~shaketable.models.stack.compiled_physics.
plastic_candidate`) and keeps it if admissible. A solution that lifts both corners of an
interface (a flight: outside the model) or a pivot that does not converge gives no
candidate: the law then enumerates as before.
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.models.stack.compiled_base import inlined, kernel, solve

#: Row kinds: an equality, a complementarity pair (int64 values, not literals: one compile).
EQUALITY, PAIR = np.int64(0), np.int64(1)
#: The corners of a row: the -x and +x bottom corners, the bottom's middle (tangential).
LEFT, RIGHT, MIDDLE = np.int64(-1), np.int64(1), np.int64(0)
#: Murty's pivots allowed per row before the law falls back to its enumeration.
PIVOTS_PER_ROW = 4


def lcp_workspace_size(n):
    """The float and int64 elements of :func:`lcp_workspace` for ``n`` blocks."""
    rows = 3 * n
    return rows * 6 + 2 * rows * rows + 4 * rows, 5 * rows


@inlined
def lcp_workspace(reals, f, integers, i, n):
    """The LCP's arrays as views of the zeroed pools: the rows' coefficients (3 n, 6) (the
    upper block's x, y, theta, then the lower block's), W and a matrix to factor (3 n, 3 n),
    vectors (4, 3 n) and the rows' integers (5, 3 n): interface, kind, corner, basis, the
    active rows."""
    rows = 3 * n
    coefficients, f = reals[f:f + 6 * rows].reshape((rows, 6)), f + 6 * rows
    delassus, f = reals[f:f + rows * rows].reshape((rows, rows)), f + rows * rows
    matrix, f = reals[f:f + rows * rows].reshape((rows, rows)), f + rows * rows
    vectors, f = reals[f:f + 4 * rows].reshape((4, rows)), f + 4 * rows
    codes, i = integers[i:i + 5 * rows].reshape((5, rows)), i + 5 * rows
    return (coefficients, delassus, matrix, vectors, codes), f, i


@inlined
def add_row(coefficients, codes, count, j, kind, corner, px, py, dx, dy, centroid, theta):
    """One row: the velocity along (dx, dy) at the point (px, py) of block ``j`` relative
    to the body below (the table for ``j`` = 0); returns the row count."""
    coefficients[count, 0] = dx
    coefficients[count, 1] = dy
    coefficients[count, 2] = (px - centroid[j, 0]) * dy - (py - centroid[j, 1]) * dx
    if j > 0:
        coefficients[count, 3] = -dx
        coefficients[count, 4] = -dy
        coefficients[count, 5] = -((px - centroid[j - 1, 0]) * dy
                                   - (py - centroid[j - 1, 1]) * dx)
    else:
        coefficients[count, 3] = 0.0
        coefficients[count, 4] = 0.0
        coefficients[count, 5] = 0.0
    codes[0, count] = j
    codes[1, count] = kind
    codes[2, count] = corner
    return count + 1



@inlined
def build_rows(chain, theta, centroid, phi, start, held, coefficients, codes):
    """The LCP's rows for the state at the impact (``theta`` absolute [rad], ``centroid``
    (n, 2) [m]); ``start`` the pattern before with the landing interface flat, ``held`` the
    bits of the interfaces held flat. Returns the number of rows."""
    b, h = chain[0], chain[1]
    n = b.size
    count = 0
    for j in range(n):
        below = theta[j - 1] if j > 0 else 0.0
        nx, ny = -math.sin(below), math.cos(below)
        tx, ty = ny, -nx
        cosine, sine = math.cos(theta[j]), math.sin(theta[j])
        bottom_x = centroid[j, 0] + sine * h[j]
        bottom_y = centroid[j, 1] - cosine * h[j]
        if phi[j] == 0.0:
            kind = EQUALITY if (held >> j) & 1 else PAIR
            px, py = bottom_x - cosine * b[j], bottom_y - sine * b[j]
            count = add_row(coefficients, codes, count, j, kind, LEFT, px, py, nx, ny,
                            centroid, theta)
            px, py = bottom_x + cosine * b[j], bottom_y + sine * b[j]
            count = add_row(coefficients, codes, count, j, kind, RIGHT, px, py, nx, ny,
                            centroid, theta)
            count = add_row(coefficients, codes, count, j, EQUALITY, MIDDLE, bottom_x,
                            bottom_y, tx, ty, centroid, theta)
        else:
            corner = -np.int64(start[j])   # the pivot: the -x corner for +1
            px, py = bottom_x + corner * cosine * b[j], bottom_y + corner * sine * b[j]
            count = add_row(coefficients, codes, count, j, EQUALITY, corner, px, py, nx, ny,
                            centroid, theta)
            count = add_row(coefficients, codes, count, j, EQUALITY, corner, px, py, tx, ty,
                            centroid, theta)
    return count


@inlined
def delassus_matrix(chain, coefficients, codes, rows, delassus):
    """W = J M^-1 J^T of the rows (two rows share a block when their interfaces are the
    same or next to each other)."""
    m, inertia = chain[2], chain[3]
    for r in range(rows):
        jr = codes[0, r]
        for s in range(r, rows):
            js = codes[0, s]
            total = 0.0
            for side_r in range(2):
                block_r = jr - side_r
                if block_r < 0:
                    continue
                for side_s in range(2):
                    if js - side_s != block_r:
                        continue
                    a, c = 3 * side_r, 3 * side_s
                    total += (coefficients[r, a] * coefficients[s, c]
                              + coefficients[r, a + 1] * coefficients[s, c + 1]) / m[block_r] \
                        + coefficients[r, a + 2] * coefficients[s, c + 2] / inertia[block_r]
            delassus[r, s] = total
            delassus[s, r] = total


@inlined
def murty(delassus, matrix, vectors, codes, rows):
    """Murty's least-index principal pivoting on the LCP ``w = q + W lambda`` (``q`` in
    ``vectors[0]``), the equalities always basic, the pairs' basis in ``codes[3]`` (1:
    lambda basic, w = 0); ``lambda`` into ``vectors[1]``, ``w`` into ``vectors[2]``.
    Returns whether it converged."""
    q, lam, w, rhs = vectors[0], vectors[1], vectors[2], vectors[3]
    basis, active = codes[3], codes[4]
    scale_w = 0.0
    for r in range(rows):
        scale_w = max(scale_w, abs(q[r]))
    scale_w = 1e-300 + scale_w
    for _ in range(PIVOTS_PER_ROW * rows + 8):
        size = 0
        for r in range(rows):
            if codes[1, r] == EQUALITY or basis[r] == 1:
                active[size] = r
                size += 1
        for a in range(size):
            rhs[a] = -q[active[a]]
            for c in range(size):
                matrix[a, c] = delassus[active[a], active[c]]
        solve(matrix, rhs, size)
        scale_lambda = 1e-300
        for r in range(rows):
            lam[r] = 0.0
        for a in range(size):
            lam[active[a]] = rhs[a]
            scale_lambda = max(scale_lambda, abs(rhs[a]))
        flip = -1
        for r in range(rows):
            total = q[r]
            for a in range(size):
                total += delassus[r, active[a]] * rhs[a]
            w[r] = total
            if flip < 0 and codes[1, r] == PAIR:
                if basis[r] == 1 and lam[r] < -1e-12 * scale_lambda:
                    flip = r
                elif basis[r] == 0 and total < -1e-12 * scale_w:
                    flip = r
        if flip < 0:
            return True
        basis[flip] = 1 - basis[flip]
    return False


@kernel
def lcp_solve(chain, theta, theta_dot, velocity, centroid, phi, start, held, lcp):
    """Solve the LCP of the impact (see the module docstring) into ``lcp``; returns its
    number of rows, or -1 when the pivot did not converge."""
    coefficients, delassus, matrix, vectors, codes = lcp
    rows = build_rows(chain, theta, centroid, phi, start, held, coefficients, codes)
    delassus_matrix(chain, coefficients, codes, rows, delassus)
    q = vectors[0]
    for r in range(rows):
        j = codes[0, r]
        total = coefficients[r, 0] * velocity[j, 0] + coefficients[r, 1] * velocity[j, 1] \
            + coefficients[r, 2] * theta_dot[j]
        if j > 0:
            total += coefficients[r, 3] * velocity[j - 1, 0] \
                + coefficients[r, 4] * velocity[j - 1, 1] \
                + coefficients[r, 5] * theta_dot[j - 1]
        q[r] = total
        codes[3, r] = 1   # every corner closed: the candidate with no interface opened
    return rows if murty(delassus, matrix, vectors, codes, rows) else -1


@kernel
def lcp_candidate(phi, lcp, rows, start, rate_tolerance, impulse_tolerance, candidate):
    """The candidate of the LCP's solution (:func:`lcp_solve`) into ``candidate``: a corner
    is closed where its impulse is basic, or where it separates so slowly that closing it
    would take an impulse within the law's tolerance: at most ``rate_tolerance`` [m/s], or
    ``impulse_tolerance`` [N s] times its diagonal of W (to open as few interfaces as the
    tolerance allows; negative tolerances: as solved). Returns
    False when there is none (both corners of an interface lift: a flight)."""
    delassus, vectors, codes = lcp[1], lcp[3], lcp[4]
    n = phi.size
    for j in range(n):
        candidate[j] = start[j] if phi[j] != 0.0 else 0   # held flat: stays 0
    for r in range(rows):
        j = codes[0, r]
        if phi[j] != 0.0 or codes[1, r] != PAIR or codes[2, r] != LEFT:
            continue
        left = codes[3, r] == 1 or vectors[2, r] <= max(
            rate_tolerance, impulse_tolerance * delassus[r, r])
        right = codes[3, r + 1] == 1 or vectors[2, r + 1] <= max(
            rate_tolerance, impulse_tolerance * delassus[r + 1, r + 1])
        if left and right:
            candidate[j] = 0
        elif left:
            candidate[j] = 1    # the pivot on the -x corner
        elif right:
            candidate[j] = -1
        else:
            return False        # both corners lift: a flight
    return True
