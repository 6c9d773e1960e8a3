"""An independent time-stepping reference for a column of rigid blocks: Moreau-Jean.

Full coordinates ``q = (x_i, y_i, theta_i)`` of every block's centroid in the table's
frame (the table's accelerations enter as the body forces ``-m u''`` and ``-m (g + v'')``),
a constant mass matrix ``diag(m_i, m_i, m_i (b_i^2 + h_i^2) / 3)``. Each bottom corner of
block i is a unilateral contact against the top face of the body below (the table's plane
for block 0), with Coulomb friction ``mu`` and the plastic Newton law (e = 0) at the
velocity level. One step of length h (theta-method on the forces, theta = 1/2):

    v+ = v + h M^-1 f_theta + M^-1 H P,     q+ = q + h (v + v+) / 2,
    active contacts: gap(q) + h/2 gap'(q, v) <= 0 (up to 1e-12 of the tallest half height),
    0 <= U_N+ _|_ P_N >= 0,  and every contact that carries an impulse sticks (U_T+ = 0)
    with |P_T| <= mu P_N on each interface (checked; the step fails if no such set exists).

The one-step contact problem is solved exactly by enumerating the active sets (the last
step's set first): a set is solved as ``W_AA P_A = -U_free_A`` (W = H^T M^-1 H, the
Delassus matrix; least squares where two corners of a flat interface make it singular:
only the tangential split between them is then undetermined, and the cone is checked on
the interface's resultant, which is exact for that split), and accepted when its normal
impulses are >= 0, the other active contacts do not approach and the cone holds. This
is Coulomb's law with every closed contact sticking: such a set, when found, solves the
frictional LCP. Nothing here is taken from ``shaketable.models.stack``.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

G = 9.80665


def _perp(r):
    return np.array([-r[1], r[0]])


def _rot(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


class MoreauStack:
    """Moreau-Jean time stepping of a planar column (block 0 at the bottom).

    Parameters
    ----------
    b, h, m : sequence of float
        Half widths [m], half heights [m], masses [kg], bottom first.
    mu : float
        Coulomb coefficient of every contact [-] (large: the column does not slide).
    """

    def __init__(self, b, h, m, mu: float = 10.0) -> None:
        self.b, self.h, self.m = (np.asarray(x, dtype=float) for x in (b, h, m))
        self.n = self.b.size
        inertia = self.m * (self.b ** 2 + self.h ** 2) / 3.0
        self.mass = np.repeat(self.m, 3)
        self.mass[2::3] = inertia
        self.mu = mu
        # contact c = 2 i + k: block i's corner at x = (-1)^(k+1) b_i ... -x first
        self.contacts = [(i, side) for i in range(self.n) for side in (-1.0, 1.0)]
        self.previous: tuple[int, ...] = ()
        #: The largest |tangential| / normal impulse of an interface so far [-].
        self.friction_used = 0.0

    def initial(self, theta, pivots=None):
        """Positions [m, rad] of a column with absolute rotations ``theta`` [rad]: each
        interface with a relative rotation pivots on the upper block's corner at
        -sign(relative rotation) x (on its lower body's top face); a flat one is centred."""
        q = np.zeros(3 * self.n)
        below_centre, below_angle, below_h = np.zeros(2), 0.0, 0.0
        for i in range(self.n):
            phi = theta[i] - below_angle
            sigma = 0.0 if phi == 0.0 else -math.copysign(1.0, phi)
            rb = _rot(below_angle)
            pivot = below_centre + rb @ np.array([sigma * self.b[i], below_h])
            centre = pivot + _rot(theta[i]) @ np.array([-sigma * self.b[i], self.h[i]])
            q[3 * i:3 * i + 3] = centre[0], centre[1], theta[i]
            below_centre, below_angle, below_h = centre, theta[i], self.h[i]
        return q

    def geometry(self, q):
        """Gaps [m] and the contact matrix H (columns: normal, tangential per contact)."""
        nc = len(self.contacts)
        gaps = np.zeros(nc)
        H = np.zeros((3 * self.n, 2 * nc))
        for c, (i, side) in enumerate(self.contacts):
            centre_i = q[3 * i:3 * i + 2]
            r = _rot(q[3 * i + 2]) @ np.array([side * self.b[i], -self.h[i]])
            point = centre_i + r
            if i == 0:
                normal, tangent = np.array([0.0, 1.0]), np.array([1.0, 0.0])
                gaps[c] = point[1]
            else:
                k = i - 1
                rk = _rot(q[3 * k + 2])
                normal, tangent = rk[:, 1], rk[:, 0]
                arm = point - q[3 * k:3 * k + 2]
                gaps[c] = normal @ arm - self.h[k]
                for col, direction in ((2 * c, normal), (2 * c + 1, tangent)):
                    H[3 * k:3 * k + 2, col] = -direction
                    H[3 * k + 2, col] = -direction @ _perp(arm)
            for col, direction in ((2 * c, normal), (2 * c + 1, tangent)):
                H[3 * i:3 * i + 2, col] = direction
                H[3 * i + 2, col] = direction @ _perp(r)
        return gaps, H

    def _solve_set(self, subset, W, u_free):
        rows = [2 * c + j for c in subset for j in (0, 1)]
        impulses = np.zeros(u_free.size)
        if rows:
            A = W[np.ix_(rows, rows)]
            impulses[rows] = np.linalg.lstsq(A, -u_free[rows], rcond=1e-12)[0]
        return impulses

    def _admissible(self, subset, active, impulses, u_after, scale):
        tol = 1e-10 * scale[0]
        for c in subset:
            if impulses[2 * c] < -tol:
                return False
        for c in active:
            if c not in subset and u_after[2 * c] < -1e-10 * scale[1]:
                return False
        for i in range(self.n):
            normal = impulses[4 * i] + impulses[4 * i + 2]
            tangential = impulses[4 * i + 1] + impulses[4 * i + 3]
            if abs(tangential) > self.mu * normal + tol:
                return False
        return True

    def step(self, q, v, t, dt, accel):
        """One Moreau-Jean step from ``(q, v)`` at ``t``; ``accel(t) -> (u'', v'')``.
        Returns ``(q+, v+, impulses)`` (impulses: normal, tangential per contact [N s])."""
        gaps, H = self.geometry(q)
        u_now = H.T @ v
        predicted = gaps + 0.5 * dt * u_now[0::2]
        # a contact is active when its predicted gap is closed, up to the rounding of the
        # positions (a corner at rest must not leave the set by a 1e-20 m rebound)
        active = [c for c in range(len(self.contacts))
                  if predicted[c] <= 1e-12 * float(self.h.max())]
        u0, v0 = accel(t)
        u1, v1 = accel(t + dt)
        ux, vy = 0.5 * (u0 + u1), 0.5 * (v0 + v1)
        force = np.zeros(3 * self.n)
        force[0::3] = -self.m * ux
        force[1::3] = -self.m * (G + vy)
        v_free = v + dt * force / self.mass
        impulses = np.zeros(2 * len(self.contacts))
        if active:
            Hm = H / self.mass[:, None]
            W = H.T @ Hm
            u_free = H.T @ v_free
            speed = max(float(np.abs(u_free).max()), 1e-300)
            scale = (speed / float(np.abs(W).max()), speed)
            tried = []
            first = tuple(c for c in self.previous if c in active)
            candidates = itertools.chain(
                [first], (s for r in range(len(active), -1, -1)
                          for s in itertools.combinations(active, r)))
            found = None
            for subset in candidates:
                if subset in tried:
                    continue
                tried.append(subset)
                trial = self._solve_set(subset, W, u_free)
                u_after = u_free + W @ trial
                if self._admissible(subset, active, trial, u_after, scale):
                    found = subset
                    impulses = trial
                    break
            if found is None:
                raise RuntimeError(f"Moreau-Jean: no admissible contact set at t = {t!r} s")
            self.previous = found
            for i in range(self.n):
                normal = impulses[4 * i] + impulses[4 * i + 2]
                if normal > 0.0:
                    tangential = abs(impulses[4 * i + 1] + impulses[4 * i + 3])
                    self.friction_used = max(self.friction_used, tangential / normal)
            v_new = v_free + Hm @ impulses
        else:
            self.previous = ()
            v_new = v_free
        return q + 0.5 * dt * (v + v_new), v_new, impulses

    def run(self, q0, v0, t_end, dt, accel, every: int = 1):
        """Steps to ``t_end``; the states every ``every`` steps: times [s], rotations
        [rad] (n columns), and per step each interface's normal impulses (n, 2)."""
        steps = int(round(t_end / dt))
        q, v = np.array(q0, dtype=float), np.array(v0, dtype=float)
        self.previous = ()
        times, thetas, contact = [0.0], [q[2::3].copy()], []
        for k in range(steps):
            q, v, impulses = self.step(q, v, k * dt, dt, accel)
            contact.append(impulses[0::2].reshape(self.n, 2))
            if (k + 1) % every == 0:
                times.append((k + 1) * dt)
                thetas.append(q[2::3].copy())
        return np.array(times), np.array(thetas), np.array(contact)


def patterns_from_impulses(contact, floor):
    """Each step's pattern from the normal impulses (steps, n, 2): an interface whose two
    corners carry more than ``floor`` [N s] is flat (0); only the -x corner: +1; only the
    +x corner: -1; neither: 9 (no contact: flight)."""
    loaded = contact > floor
    pattern = np.where(loaded[..., 0] & loaded[..., 1], 0,
                       np.where(loaded[..., 0], 1, np.where(loaded[..., 1], -1, 9)))
    return pattern.astype(int)


def linear_accel(t_samples, horizontal, vertical=None):
    """``accel(t)`` of a motion linear between samples (the model's input convention)."""
    t_samples = np.asarray(t_samples, dtype=float)
    horizontal = np.asarray(horizontal, dtype=float)
    vertical = np.zeros_like(horizontal) if vertical is None else np.asarray(vertical, float)

    def accel(t):
        return (float(np.interp(t, t_samples, horizontal)),
                float(np.interp(t, t_samples, vertical)))
    return accel
