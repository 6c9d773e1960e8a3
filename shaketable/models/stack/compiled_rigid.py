"""The stack's one-DOF patterns and rest in closed form, compiled (numba).

While exactly one interface ``j`` of the column is open (pivot side ``s``), everything below
it is seated on the table and the blocks above it rock as one rigid body about the pivot
corner, which moves with the table: Eq. (2-13) of a single block with that body's numbers
(``docs/stack.md``, one-DOF patterns),

    I_O phi'' = M [ u'' (y_c cos(phi) + s b_j sin(phi)) - (g + v'') (s b_j cos(phi) - y_c sin(phi)) ],

M the mass above the interface, y_c the height of its centre of mass above the pivot, b_j the
lever arm of the centre of mass from the pivot at rest, on the pivot's side (the interface's
half width for a centred column; with offsets, b_j + s d, d the horizontal distance of the
centre of mass of the blocks from j up from block j's centre) and I_O = sum (I_i + m_i |r_i|^2)
its inertia about the pivot. That is the single-block engine's
:func:`~shaketable.models.rocking.physics.flight_acceleration` with b = b_j, h = y_c and
I0 / M = I_O / M (:func:`rigid_parameters`), so the one-DOF patterns are integrated with the
single block's stepper, its error control and its event location
(:func:`shaketable.models.stack.compiled_one.one_dof_segment`).

The contact forces of such a state (and of rest, phi = phi' = phi'' = 0) are linear in
(u'', g + v'', phi'', phi'^2) with coefficients that are constants or sin / cos of phi
(:func:`rigid_coefficients`, :func:`rigid_forces`): the moment about a corner of interface k
of everything above it, divided by the interface's width, as
:func:`~shaketable.models.stack.compiled_physics.interface_loads` computes it from the whole
chain. The normal force at a seated corner reaching zero (the next pattern's uplift) is
located on it.
"""

from __future__ import annotations

import math

from shaketable.core.constants import G
from shaketable.models.stack.compiled_physics import inlined, kernel

# columns of the coefficients of an interface (rigid_coefficients): the mass above it, the
# first moment of the rocking body about its pivot (x, y, in its own frame), whether the
# interface turns with the body, its width, then per corner (left, right) the moment's
# coefficients A (x, y: fixed), B (x, y: turning with the body), S0, C0, q1, q2
C_MASS, C_EX, C_EY, C_TURNS, C_WIDTH = 0, 1, 2, 3, 4
C_CORNER = 5
N_CORNER = 8
N_COEFFICIENTS = C_CORNER + 2 * N_CORNER
#: Columns of the coefficients' array: one more, for the blocks' heights.
N_COLUMNS = N_COEFFICIENTS + 1
# slots of a rigid body's numbers (rigid_coefficients' ``body``)
B_HALF_WIDTH, B_HEIGHT, B_INERTIA_PER_MASS, B_ALPHA, B_INERTIA, B_MASS, B_RX, B_RY = range(8)
N_BODY = 8


@inlined
def centre_of(h, n, i):
    """Block ``i``'s centre at rest from the bottom block's, horizontally [m]: the running
    sum of the offsets, which follow the ``n`` half heights in ``h`` (compiled_physics'
    chain; 0 for a centred column, whose ``h`` has n values)."""
    x = 0.0
    if h.size > n:
        for k in range(i + 1):
            x += h[n + k]
    return x


@kernel
def rigid_coefficients(chain, j, s, coefficients, body):
    """The coefficients of :func:`rigid_forces` for the pattern with interface ``j`` open on
    side ``s`` (+1 / -1) and every other interface flat, or rest (``j`` = -1), into
    ``coefficients`` (n, N_COLUMNS); the rocking body's numbers into ``body``
    (the lever arm b_j + s d [m], y_c [m], I_O / M [m^2], alpha_eq = atan(lever arm / y_c)
    [rad], I_O [kg m^2], M [kg], its first moment about the pivot at phi = 0,
    M (s b_j + d, y_c) [kg m]); d is the horizontal distance of the body's centre of mass
    from block j's centre (0 for a centred column)."""
    b, h, m, inertia = chain[0], chain[1], chain[2], chain[3]
    n = b.size
    # the height of each block's bottom at rest [m] in the last column (none allocated)
    last = N_COEFFICIENTS
    level = 0.0
    for i in range(n):
        coefficients[i, last] = level
        level += 2.0 * h[i]
    px, py, mass, rx, ry, inertia_o, shift = 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    if j >= 0:
        px, py = -s * b[j] + centre_of(h, n, j), coefficients[j, last]
        for i in range(j, n):
            dx = centre_of(h, n, i) - centre_of(h, n, j)
            x, y = s * b[j] + dx, coefficients[i, last] + h[i] - py
            mass += m[i]
            rx += m[i] * x
            ry += m[i] * y
            shift += m[i] * dx
            inertia_o += inertia[i] + m[i] * (x * x + y * y)
        arm = b[j] + s * (shift / mass)
        body[B_HALF_WIDTH] = arm
        body[B_HEIGHT] = ry / mass
        body[B_INERTIA_PER_MASS] = inertia_o / mass
        body[B_ALPHA] = math.atan(arm / (ry / mass))
        body[B_INERTIA] = inertia_o
        body[B_MASS] = mass
        body[B_RX] = rx
        body[B_RY] = ry
    for k in range(n):
        for q in range(N_COEFFICIENTS):
            coefficients[k, q] = 0.0
        above = 0.0
        for i in range(k, n):
            above += m[i]
        coefficients[k, C_MASS] = above
        coefficients[k, C_WIDTH] = 2.0 * b[k]
        turns = j >= 0 and k > j
        coefficients[k, C_TURNS] = 1.0 if turns else 0.0
        if j >= 0 and not turns:
            coefficients[k, C_EX], coefficients[k, C_EY] = rx, ry
        elif turns:
            for i in range(k, n):
                coefficients[k, C_EX] += m[i] * (s * b[j] + (centre_of(h, n, i)
                                                             - centre_of(h, n, j)))
                coefficients[k, C_EY] += m[i] * (coefficients[i, last] + h[i] - py)
        if j >= 0 and k == j:
            continue
        for corner in range(2):
            c = C_CORNER + corner * N_CORNER
            lx = (2.0 * corner - 1.0) * b[k] + centre_of(h, n, k)
            ly = coefficients[k, last]
            if turns:
                # every block above k is in the rocking body: moments in its frame
                lx, ly = lx - px, ly - py
                for i in range(k, n):
                    x = s * b[j] + (centre_of(h, n, i) - centre_of(h, n, j))
                    y = coefficients[i, last] + h[i] - py
                    dx, dy = x - lx, y - ly
                    coefficients[k, c + 2] += m[i] * dx
                    coefficients[k, c + 3] += m[i] * dy
                    coefficients[k, c + 4] += m[i] * (dx * x + dy * y) + inertia[i]
                    coefficients[k, c + 5] += m[i] * (dx * y - dy * x)
                continue
            # the seated blocks k .. j-1 (all above k at rest), then the rocking body
            top = n if j < 0 else j
            for i in range(k, top):
                coefficients[k, c] += m[i] * (centre_of(h, n, i) - lx)
                coefficients[k, c + 1] += m[i] * (coefficients[i, last] + h[i] - ly)
            if j >= 0:
                ax, ay = px - lx, py - ly
                coefficients[k, c] += mass * ax
                coefficients[k, c + 1] += mass * ay
                coefficients[k, c + 6] = ax * rx + ay * ry
                coefficients[k, c + 7] = ax * ry - ay * rx


@kernel
def rigid_forces(coefficients, j, s, cosine, sine, phi_dot, phi_ddot, ug, vg, out):
    """The contact forces [N] of a one-DOF state (interface ``j`` open on side ``s`` at
    cos(phi), sin(phi), phi' [rad/s], phi'' [rad/s^2]) or of rest (``j`` = -1, zeros) under
    the table's u'', v'' [m/s^2] into ``out`` (n, 4): the columns N, F, N at the -x corner,
    N at the +x corner of :func:`~shaketable.models.stack.compiled_physics.interface_loads`."""
    n = coefficients.shape[0]
    gx, gy = ug, G + vg
    w2 = phi_dot * phi_dot
    for k in range(n):
        ex = cosine * coefficients[k, C_EX] - sine * coefficients[k, C_EY]
        ey = sine * coefficients[k, C_EX] + cosine * coefficients[k, C_EY]
        fx = coefficients[k, C_MASS] * gx - phi_ddot * ey - w2 * ex
        fy = coefficients[k, C_MASS] * gy + phi_ddot * ex - w2 * ey
        if coefficients[k, C_TURNS] != 0.0:
            out[k, 0] = -fx * sine + fy * cosine
            out[k, 1] = fx * cosine + fy * sine
        else:
            out[k, 0] = fy
            out[k, 1] = fx
        out[k, 2] = 0.0
        out[k, 3] = 0.0
        if k == j:
            out[k, 2 if s > 0 else 3] = out[k, 0]
            continue
        for corner in range(2):
            c = C_CORNER + corner * N_CORNER
            mx = coefficients[k, c] + cosine * coefficients[k, c + 2] - sine * coefficients[k, c + 3]
            my = coefficients[k, c + 1] + sine * coefficients[k, c + 2] + cosine * coefficients[k, c + 3]
            q1, q2 = coefficients[k, c + 6], coefficients[k, c + 7]
            moment = (mx * gy - my * gx + phi_ddot * (coefficients[k, c + 4] + cosine * q1 - sine * q2)
                      - w2 * (coefficients[k, c + 5] + cosine * q2 + sine * q1))
            # about the left corner: the +x corner's force; about the right: the -x one's
            if corner == 0:
                out[k, 3] = moment / coefficients[k, C_WIDTH]
            else:
                out[k, 2] = -moment / coefficients[k, C_WIDTH]


@inlined
def rigid_acceleration(body, side, cosine, sine, ug, vg):
    """phi'' [rad/s^2] of the rocking body on the pivot ``side`` (+1.0 / -1.0) at cos(phi),
    sin(phi) under the table's u'', v'' [m/s^2]: Eq. (2-13) in the operations of
    :func:`~shaketable.models.rocking.physics.flight_acceleration` (no rods, no top force,
    no table rotation), so that both give the same number."""
    b, h = body[B_HALF_WIDTH], body[B_HEIGHT]
    moment = ug * (h * cosine + side * b * sine) - (G + vg) * (side * b * cosine - h * sine)
    return moment / body[B_INERTIA_PER_MASS]


@inlined
def rigid_energy(body, cosine, sine, phi_dot):
    """Kinetic plus potential energy of the rocking body less its value at rest [J], at
    cos(phi), sin(phi) and phi' [rad/s]."""
    return (0.5 * body[B_INERTIA] * phi_dot * phi_dot
            + G * (sine * body[B_RX] + (cosine - 1.0) * body[B_RY]))
