"""An independent statement of the stack's dynamics: Newton-Euler with the contact forces as
unknowns, one linear solve per contact pattern.

Each block has its own coordinates (centroid x, y and rotation): 3 n accelerations. Each
interface adds the force on the block above (2 unknowns) at its pivot, and a flat interface
also a couple (1 unknown). The equations are each block's Newton-Euler balance and, per
interface, that the pivot point has the same acceleration on both bodies (the table's is
zero in the table frame) and, when flat, that the two rotations have the same acceleration.
Nothing here uses :mod:`shaketable.models.stack.physics`: the reduced Lagrange equations
(a mass matrix in the rotations) are checked against it (``tests/models/stack``).
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.core.constants import G


def _point_terms(r, omega):
    """Acceleration of a point at arm ``r`` from a centroid: a_G + alpha (-r_y, r_x) - omega^2 r;
    returns the coefficient of alpha and the velocity term."""
    return np.array([-r[1], r[0]]), -omega ** 2 * np.asarray(r)


def newton_euler(b, h, m, theta, theta_dot, pattern, ug, vg, e=None):
    """theta'' [rad/s^2] of each block and each interface's ``(N, F, N_-x, N_+x)`` [N].

    Geometry rebuilt from scratch: block i's bottom centre follows from the pivots, the
    upper block's corner at ``e_j - s_j b_j`` from the lower block's top centre (``e``:
    each block's offset from the centre of the one below [m], zeros by default) sitting on
    the lower block's top face.
    """
    b, h, m = (np.asarray(x, dtype=float) for x in (b, h, m))
    n = b.size
    inertia = m * (b ** 2 + h ** 2) / 3.0
    sides = [1.0 if s == 0 else float(s) for s in pattern]
    offsets = np.zeros(n) if e is None else np.asarray(e, dtype=float)

    def frame(angle):
        return np.array([math.cos(angle), math.sin(angle)]), np.array([-math.sin(angle),
                                                                        math.cos(angle)])

    bottoms, pivots, centroids = [], [], []
    for i in range(n):
        along, up = frame(theta[i])
        if i == 0:
            pivot = np.array([-sides[0] * b[0], 0.0])
        else:
            lower_along, lower_up = frame(theta[i - 1])
            pivot = bottoms[i - 1] + lower_along * (offsets[i] - sides[i] * b[i]) \
                + lower_up * (2 * h[i - 1])
        bottom = pivot - along * (-sides[i] * b[i])
        pivots.append(pivot)
        bottoms.append(bottom)
        centroids.append(bottom + up * h[i])
    # unknowns: [ax_i, ay_i, alpha_i]*n, then per interface [Fx, Fy] (+ couple if flat)
    index, column = [], 3 * n
    for j in range(n):
        index.append(column)
        column += 2 + (1 if pattern[j] == 0 else 0)
    size = column
    matrix = np.zeros((size, size))
    rhs = np.zeros(size)
    row = 0
    for i in range(n):
        # m a = f + F_i - F_{i+1}; I alpha = r_i x F_i + C_i - r'_{i+1} x F_{i+1} - C_{i+1}
        matrix[row, 3 * i], matrix[row + 1, 3 * i + 1] = m[i], m[i]
        rhs[row], rhs[row + 1] = -m[i] * ug, -m[i] * (G + vg)
        matrix[row + 2, 3 * i + 2] = inertia[i]
        for j, sign in ((i, 1.0), (i + 1, -1.0)):
            if j >= n:
                continue
            arm = pivots[j] - centroids[i]
            matrix[row, index[j]] -= sign
            matrix[row + 1, index[j] + 1] -= sign
            matrix[row + 2, index[j]] -= sign * (-arm[1])
            matrix[row + 2, index[j] + 1] -= sign * arm[0]
            if pattern[j] == 0:
                matrix[row + 2, index[j] + 2] -= sign
        row += 3
    for j in range(n):
        # the pivot's acceleration on the upper block equals that on the lower one
        coefficient, velocity = _point_terms(pivots[j] - centroids[j], theta_dot[j])
        for a in range(2):
            matrix[row + a, 3 * j + a] = 1.0
            matrix[row + a, 3 * j + 2] = coefficient[a]
            rhs[row + a] = -velocity[a]
        if j > 0:
            coefficient, velocity = _point_terms(pivots[j] - centroids[j - 1], theta_dot[j - 1])
            for a in range(2):
                matrix[row + a, 3 * (j - 1) + a] -= 1.0
                matrix[row + a, 3 * (j - 1) + 2] -= coefficient[a]
                rhs[row + a] += velocity[a]
        row += 2
        if pattern[j] == 0:
            matrix[row, 3 * j + 2] = 1.0
            if j > 0:
                matrix[row, 3 * (j - 1) + 2] = -1.0
            row += 1
    solution = np.linalg.solve(matrix, rhs)
    theta_ddot = solution[2:3 * n:3]
    forces = np.zeros((n, 4))
    for j in range(n):
        force = solution[index[j]:index[j] + 2]
        lower = theta[j - 1] if j > 0 else 0.0
        along, up = frame(lower)
        forces[j, 0], forces[j, 1] = force @ up, force @ along
        if pattern[j] != 0:
            forces[j, 2 if pattern[j] > 0 else 3] = forces[j, 0]
        else:
            # the couple about the pivot (the -x corner for a flat interface's s = +1):
            # the +x corner carries couple / 2b
            couple = solution[index[j] + 2]
            forces[j, 3] = couple / (2.0 * b[j])
            forces[j, 2] = forces[j, 0] - forces[j, 3]
    return theta_ddot, forces
