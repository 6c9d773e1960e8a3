"""Equations of motion, contact forces and energies of a column of rigid blocks.

Coordinates and sign convention (the package's, ``docs/conventions.md``)
-------------------------------------------------------------------------
Block i (0 at the bottom) has the absolute rotation ``theta_i`` [rad], positive
counter-clockwise: a single block with ``theta > 0`` pivots on its corner at -x and its top
moves toward -x, as in the report's Fig. 2.7, so that a positive table acceleration drives
theta positive. Interface j lies below block j (interface 0 is the table). Its relative
rotation is ``phi_j = theta_j - theta_{j-1}`` (``theta_{-1} = 0``) and its state ``s_j``:
0 flat (both corners touch), +1 pivoting on the upper block's corner at -x
(``phi_j > 0``), -1 on its corner at +x (``phi_j < 0``). A *pattern* is the tuple ``s``.

The block positions follow from the rotations through the chain of pivots (one pivot per
interface; a flat interface may use either corner, the positions do not depend on it)::

    G_i = P_0 + sum_{k<i} R(theta_k) D_k + R(theta_i) C_i
    P_0 = (-s_0 b_0, 0),  D_k = (s_k b_k - s_{k+1} b_{k+1} + e_{k+1}, 2 h_k),  C_i = (s_i b_i, h_i)

(the flat interfaces' ``s`` taken as +1; ``e_{k+1}`` the offset of block k + 1's centre from
block k's, :attr:`~shaketable.models.stack.geometry.Stack.offsets`, zero for a centred
column; the origin is the bottom block's base centre at rest). Lagrange's equations with
the rotations as coordinates give ``M(theta) theta'' = Q(theta, theta', t)`` with

    M = sum_i m_i J_i^T J_i + diag(m_i (b_i^2 + h_i^2) / 3),   J_i = dG_i/dtheta
    Q = sum_i J_i^T m_i (f - c_i),   f = (-u'', -(g + v'')),
    c_i = -sum_{k<i} R(theta_k) D_k theta_k'^2 - R(theta_i) C_i theta_i'^2

(the table frame: the table's acceleration enters as the force -m u'' and the gravity
g + v''). A pattern keeps the flat interfaces' ``phi`` at zero: with ``theta = L phi`` (L the
lower-triangular matrix of ones) and ``T`` the columns of L of the open interfaces, the
reduced equations are ``(T^T M T) phi_open'' = T^T Q`` (``docs/stack.md``).
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from shaketable.core.constants import G

#: Rotation by +90 degrees: d R(theta) r / d theta = QUARTER R(theta) r.
QUARTER = np.array([[0.0, -1.0], [1.0, 0.0]])


class Chain:
    """The geometry of a stack as arrays (half sizes, masses, centroidal inertias, each
    block's offset from the centre of the one below, 0 for the bottom one)."""

    def __init__(self, b, h, m, e=None) -> None:
        self.b = np.asarray(b, dtype=float)
        self.h = np.asarray(h, dtype=float)
        self.m = np.asarray(m, dtype=float)
        self.n = self.b.size
        self.e = np.zeros(self.n) if e is None else np.asarray(e, dtype=float)
        # e_{k+1} at k (0 at the top), or None for a centred column (nothing added)
        self.offsets_above = None
        if np.any(self.e):
            self.offsets_above = np.zeros(self.n)
            self.offsets_above[:-1] = self.e[1:]
        self.inertia = self.m * (self.b ** 2 + self.h ** 2) / 3.0
        self.lower = np.tril(np.ones((self.n, self.n)))
        self.strictly_lower = np.tril(np.ones((self.n, self.n), dtype=bool), -1)
        self.m_twice = np.repeat(self.m, 2)   # the mass of each centroid coordinate
        self.inertia_matrix = np.diag(self.inertia)

    @classmethod
    def of(cls, stack) -> "Chain":
        return cls(stack.b, stack.h, stack.m, stack.e)


def pivots(pattern) -> np.ndarray:
    """The pivot side of each interface: ``s_j``, and +1 for a flat interface."""
    s = np.asarray(pattern, dtype=float)
    return np.where(s == 0.0, 1.0, s)


def rotation(theta: float) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s], [s, c]])


def arms(chain: Chain, theta, pattern):
    """The rotated chain vectors ``R(theta_k) D_k`` and ``R(theta_i) C_i`` [m], shape (n, 2)
    each, and the pivot on the table ``P_0``."""
    sigma = pivots(pattern)
    above = np.zeros(chain.n)
    above[:-1] = sigma[1:] * chain.b[1:]
    dx, dy = sigma * chain.b - above, 2.0 * chain.h
    if chain.offsets_above is not None:
        dx = dx + chain.offsets_above
    cx, cy = sigma * chain.b, chain.h
    cosine, sine = np.cos(theta), np.sin(theta)
    rd = np.stack([cosine * dx - sine * dy, sine * dx + cosine * dy], axis=1)
    rc = np.stack([cosine * cx - sine * cy, sine * cx + cosine * cy], axis=1)
    return rd, rc, np.array([-sigma[0] * chain.b[0], 0.0])


def kinematics(chain: Chain, theta, theta_dot, pattern):
    """Centroids ``G`` (n, 2) [m], Jacobians ``J`` (n, 2, n) [m] and the velocity-product
    accelerations ``c`` (n, 2) [m/s^2] of the chain with the pivots of ``pattern``."""
    n = chain.n
    theta_dot = np.asarray(theta_dot, dtype=float)
    rd, rc, p0 = arms(chain, np.asarray(theta, dtype=float), pattern)
    # sums over the blocks below: base_i = P_0 + sum_{k<i} R D_k, likewise the spin terms
    below = np.zeros((n, 2))
    below[1:] = np.cumsum(rd[:-1], axis=0)
    spun = rd * (theta_dot ** 2)[:, None]
    spin_below = np.zeros((n, 2))
    spin_below[1:] = np.cumsum(spun[:-1], axis=0)
    centroid = p0[None, :] + below + rc
    centripetal = -(spin_below + rc * (theta_dot ** 2)[:, None])
    # J_i[:, k] = QUARTER R D_k for k < i, QUARTER R C_i for k = i: QUARTER (x, y) = (-y, x)
    turned_d = np.stack([-rd[:, 1], rd[:, 0]], axis=1)
    turned_c = np.stack([-rc[:, 1], rc[:, 0]], axis=1)
    jacobian = np.where(chain.strictly_lower[:, None, :], turned_d.T[None, :, :], 0.0)
    index = np.arange(n)
    jacobian[index, :, index] = turned_c
    return centroid, jacobian, centripetal


def mass_matrix(chain: Chain, jacobian) -> np.ndarray:
    """M = sum_i m_i J_i^T J_i + diag(I_i) [kg m^2]."""
    flat = jacobian.reshape(2 * chain.n, chain.n)
    return flat.T @ (chain.m_twice[:, None] * flat) + chain.inertia_matrix


def applied(chain: Chain, ug: float, vg: float) -> np.ndarray:
    """The force on each block in the table frame, m_i (-u'', -(g + v'')) [N], (n, 2)."""
    return chain.m[:, None] * np.array([-ug, -(G + vg)])[None, :]


def open_columns(chain: Chain, pattern) -> np.ndarray:
    """``T``: the columns of L for the open interfaces (theta = T phi_open)."""
    return chain.lower[:, [j for j, s in enumerate(pattern) if s != 0]]


def accelerations(chain: Chain, phi, phi_dot, pattern, ug: float, vg: float):
    """phi'' [rad/s^2] of every interface in ``pattern`` (zero at the flat ones), with the
    kinematics it used."""
    theta, theta_dot = np.cumsum(phi), np.cumsum(phi_dot)
    centroid, jacobian, centripetal = kinematics(chain, theta, theta_dot, pattern)
    phi_ddot = np.zeros(chain.n)
    columns = [j for j, s in enumerate(pattern) if s != 0]
    if columns:
        force = applied(chain, ug, vg) - chain.m[:, None] * centripetal
        q = jacobian.reshape(2 * chain.n, chain.n).T @ force.reshape(2 * chain.n)
        t = chain.lower[:, columns]
        matrix = t.T @ mass_matrix(chain, jacobian) @ t
        phi_ddot[columns] = np.linalg.solve(matrix, t.T @ q)
    return phi_ddot, (theta, theta_dot, centroid, jacobian, centripetal)


def cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def interface_loads(chain: Chain, pattern, theta, centroid, demand, spin):
    """What each interface carries for the blocks above it, from what they need.

    ``demand`` (n, 2) is each block's ``m_i G_i'' - f_i`` [N] (or its momentum change
    ``m_i dG_i'`` [N s] at an impact) and ``spin`` (n,) its ``I_i theta_i''`` [N m] (or
    ``I_i dtheta_i'`` [N m s]). Returns an array (n, 4): normal N and tangential F of the resultant
    (along the lower surface's normal and its +x direction) and the normal parts at the
    upper block's -x and +x corners: a pivot carries all of N; a flat interface's two
    corners follow from the moments about each corner (``N_+x = M_-x / 2b``,
    ``N_-x = -M_+x / 2b``).
    """
    n = chain.n
    result = np.zeros((n, 4))
    resultant = np.zeros(2)
    for j in range(n - 1, -1, -1):
        resultant = resultant + demand[j]
        below = theta[j - 1] if j > 0 else 0.0
        normal = np.array([-math.sin(below), math.cos(below)])
        tangent = np.array([math.cos(below), math.sin(below)])
        result[j, 0] = resultant @ normal
        result[j, 1] = resultant @ tangent
        s = pattern[j]
        if s != 0:
            result[j, 2 if s > 0 else 3] = result[j, 0]
            continue
        r = rotation(theta[j])
        bottom = centroid[j] - r @ np.array([0.0, chain.h[j]])
        left = bottom + r @ np.array([-chain.b[j], 0.0])
        right = bottom + r @ np.array([chain.b[j], 0.0])
        about_left = about_right = 0.0
        for k in range(j, n):
            about_left += cross(centroid[k] - left, demand[k]) + spin[k]
            about_right += cross(centroid[k] - right, demand[k]) + spin[k]
        result[j, 3] = about_left / (2.0 * chain.b[j])
        result[j, 2] = -about_right / (2.0 * chain.b[j])
    return result


def interface_forces(chain: Chain, pattern, ug, vg, theta, theta_ddot, centroid, jacobian,
                     centripetal):
    """Contact forces [N] of every interface on the blocks above it (the columns of
    :func:`interface_loads`)."""
    acceleration = np.einsum("iak,k->ia", jacobian, theta_ddot) + centripetal
    demand = chain.m[:, None] * acceleration - applied(chain, ug, vg)
    return interface_loads(chain, pattern, theta, centroid, demand, chain.inertia * theta_ddot)


def state_forces(chain: Chain, phi, phi_dot, pattern, ug, vg):
    """phi'' and the contact forces (see :func:`interface_forces`) of a state."""
    phi_ddot, (theta, _, centroid, jacobian, centripetal) = accelerations(
        chain, phi, phi_dot, pattern, ug, vg)
    forces = interface_forces(chain, pattern, ug, vg, theta, np.cumsum(phi_ddot), centroid,
                              jacobian, centripetal)
    return phi_ddot, forces


def energy(chain: Chain, phi, phi_dot, pattern) -> tuple[float, float]:
    """Kinetic energy in the table frame and potential energy m g y above the table [J]."""
    theta, theta_dot = np.cumsum(phi), np.cumsum(phi_dot)
    centroid, jacobian, _ = kinematics(chain, theta, theta_dot, pattern)
    kinetic = 0.5 * theta_dot @ mass_matrix(chain, jacobian) @ theta_dot
    return float(kinetic), float(G * chain.m @ centroid[:, 1])


def table_power(chain: Chain, phi, phi_dot, pattern, ug, vg) -> float:
    """Power of the table's inertial forces -m u'' and -m v'' on the blocks [W]."""
    theta, theta_dot = np.cumsum(phi), np.cumsum(phi_dot)
    _, jacobian, _ = kinematics(chain, theta, theta_dot, pattern)
    velocity = np.einsum("iak,k->ia", jacobian, theta_dot)
    return float(-(chain.m * (ug * velocity[:, 0] + vg * velocity[:, 1])).sum())


def candidates(pattern, free):
    """Every pattern that keeps the interfaces not in ``free`` and gives each free one any of
    flat, +1, -1 (flat first)."""
    for level in candidate_levels(pattern, free):
        yield from level


def candidate_levels(pattern, free):
    """The candidates of :func:`candidates` in groups, by how many free interfaces they open
    (0, 1, 2, ...)."""
    for count in range(len(free) + 1):
        level = []
        for opened in itertools.combinations(free, count):
            for sides in itertools.product((1, -1), repeat=count):
                candidate = [0 if j in free else s for j, s in enumerate(pattern)]
                for j, side in zip(opened, sides):
                    candidate[j] = side
                level.append(tuple(candidate))
        yield level
