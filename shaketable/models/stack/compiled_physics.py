"""The stack's equations, contact forces, energies and impact laws, compiled (numba).

The same formulas as :mod:`shaketable.models.stack.physics` and
:mod:`shaketable.models.stack.impact` (their docstrings and ``docs/stack.md`` state them),
written as loops over preallocated arrays for the compiled engine
(:mod:`shaketable.models.stack.compiled`). A *chain* is the tuple ``(b, h, m, inertia)`` of
the blocks' half widths [m], half heights [m], masses [kg] and centroidal inertias
m (b^2 + h^2) / 3 [kg m^2]; for a column with offsets, ``h`` holds 2 n values: the half
heights, then each block's offset from the centre of the block below [m] (0 for the bottom
block). A centred column's ``h`` has n values and its kinematics add no offset: the same
types, operations and bits as a chain that knows no offsets (a fifth array in the tuple,
passed by value to every function compiled apart, made the centred two-block runs of
``benchmarks/stack_speed.py`` about 3 % slower, medians of 7 repeats on a shared machine).
A *workspace* (:func:`workspace`) holds the arrays the functions fill, so that a right-hand
side allocates nothing. Patterns are int64 arrays (0 flat, +1 / -1 the pivot side of each
interface).

Candidate patterns are enumerated in the order of :func:`~shaketable.models.stack.physics.
candidate_levels` (by the number of interfaces opened; the opened ones in lexicographic
order, their sides +1 before -1 with the first one varying slowest), so that the compiled
engine and the Python one choose alike.
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.core.constants import G
from shaketable.models.stack.compiled_base import (  # noqa: F401  (re-exported)
    COMPILED,
    KERNEL,
    inlined,
    kernel,
    solve,
)
from shaketable.models.stack.compiled_lcp import (
    lcp_candidate,
    lcp_solve,
    lcp_workspace,
    lcp_workspace_size,
)

#: Up to this many blocks every candidate is tried (as the Python engine and impact law).
FULL_ENUMERATION = 3
#: The plastic law's tolerances (as :mod:`shaketable.models.stack.impact`).
ROUNDING = 1e-6
IMPACT_TOLERANCE = 1e-9
#: No interface (an int64, not a literal).
NONE_INTERFACE = np.int64(-1)


def workspace_size(n):
    """The float and int64 elements of a workspace of ``n`` blocks (:func:`workspace`)."""
    return 23 * n + 6 * n * n, n


@inlined
def workspace(reals, f, integers, i, n):
    """The arrays the compiled functions fill, for a chain of ``n`` blocks (a tuple), as
    views of the zeroed pools ``reals`` from ``f`` and ``integers`` from ``i`` (the run's
    arrays are allocated once by its caller, so that the compiled run needs no reference
    counting); returns them and the offsets past them."""
    nn = n * n
    a0, a1, a2, f = reals[f:f + n], reals[f + n:f + 2 * n], \
        reals[f + 2 * n:f + 4 * n].reshape((n, 2)), f + 4 * n
    a3, a4, f = reals[f:f + 2 * nn].reshape((n, 2, n)), \
        reals[f + 2 * nn:f + 2 * nn + 2 * n].reshape((n, 2)), f + 2 * nn + 2 * n
    a5, a6, a7, f = reals[f:f + nn].reshape((n, n)), reals[f + nn:f + 2 * nn].reshape((n, n)), \
        reals[f + 2 * nn:f + 2 * nn + n], f + 2 * nn + n
    a8, a9, a10, f = reals[f:f + 4 * n].reshape((n, 4)), \
        reals[f + 4 * n:f + 6 * n].reshape((n, 2)), reals[f + 6 * n:f + 7 * n], f + 7 * n
    a11, a12, f = reals[f:f + 2 * nn].reshape((n, 2, n)), reals[f + 2 * nn:f + 2 * nn + n], \
        f + 2 * nn + n
    a13, a15, a16, f = reals[f:f + 2 * n].reshape((n, 2)), reals[f + 2 * n:f + 3 * n], \
        reals[f + 3 * n:f + 4 * n], f + 4 * n
    a17, f = reals[f:f + 4 * n].reshape((n, 4)), f + 4 * n
    a14, i = integers[i:i + n], i + n
    return (a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15, a16,
            a17), f, i


@inlined
def side_of(pattern, j):
    """The pivot side of interface ``j`` (+1 for a flat one) [-]."""
    return 1.0 if pattern[j] == 0 else float(pattern[j])


@kernel
def kinematics(chain, theta, theta_dot, pattern, centroid, jacobian, centripetal):
    """Centroids G (n, 2) [m], Jacobians J (n, 2, n) [m] and velocity-product accelerations
    c (n, 2) [m/s^2] of the chain with the pivots of ``pattern`` (into the arrays given)."""
    b, h = chain[0], chain[1]
    n = b.size
    shifted = h.size > n   # the offsets e_i follow the half heights (module docstring)
    base_x, base_y = -(1.0 if pattern[0] == 0 else float(pattern[0])) * b[0], 0.0
    spin_x, spin_y = 0.0, 0.0
    jacobian[:] = 0.0
    for i in range(n):
        sigma = side_of(pattern, i)
        cosine, sine = math.cos(theta[i]), math.sin(theta[i])
        cx, cy = sigma * b[i], h[i]
        rcx, rcy = cosine * cx - sine * cy, sine * cx + cosine * cy
        w2 = theta_dot[i] * theta_dot[i]
        centroid[i, 0] = base_x + rcx
        centroid[i, 1] = base_y + rcy
        centripetal[i, 0] = -(spin_x + rcx * w2)
        centripetal[i, 1] = -(spin_y + rcy * w2)
        jacobian[i, 0, i] = -rcy
        jacobian[i, 1, i] = rcx
        above = side_of(pattern, i + 1) * b[i + 1] if i < n - 1 else 0.0
        dx, dy = sigma * b[i] - above, 2.0 * h[i]
        if shifted and i < n - 1:
            dx = dx + h[n + i + 1]
        rdx, rdy = cosine * dx - sine * dy, sine * dx + cosine * dy
        for k in range(i + 1, n):
            jacobian[k, 0, i] = -rdy
            jacobian[k, 1, i] = rdx
        base_x += rdx
        base_y += rdy
        spin_x += rdx * w2
        spin_y += rdy * w2


@kernel
def mass_matrix(chain, jacobian, out):
    """M = sum_i m_i J_i^T J_i + diag(I_i) [kg m^2] into ``out``."""
    m, inertia = chain[2], chain[3]
    n = m.size
    for k in range(n):
        for q in range(k, n):
            total = 0.0
            for i in range(max(k, q), n):
                total += m[i] * (jacobian[i, 0, k] * jacobian[i, 0, q]
                                 + jacobian[i, 1, k] * jacobian[i, 1, q])
            if k == q:
                total += inertia[k]
            out[k, q] = total
            out[q, k] = total


@kernel
def reduced_solve(mass, generalized, pattern, columns, reduced, vector, out):
    """theta = T q of the pattern's open interfaces from (T^T M T) q = T^T Q: ``out``
    receives the absolute theta [per ``generalized``'s unit]; returns the number of open
    interfaces (``columns`` their indices)."""
    n = pattern.size
    size = np.int64(0)
    for j in range(n):
        if pattern[j] != 0:
            columns[size] = j
            size += 1
    out[:] = 0.0
    if size == 0:
        return 0
    # T[i, a] = 1 for i >= columns[a]: sums of M over the rows and columns below them
    for a in range(size):
        total = 0.0
        for i in range(columns[a], n):
            total += generalized[i]
        vector[a] = total
        for c in range(size):
            total = 0.0
            for i in range(columns[a], n):
                for k in range(columns[c], n):
                    total += mass[i, k]
            reduced[a, c] = total
    solve(reduced, vector, size)
    for a in range(size):
        for i in range(columns[a], n):
            out[i] += vector[a]
    return size


@kernel
def cumulate(values, out):
    total = 0.0
    for i in range(values.size):
        total += values[i]
        out[i] = total


@kernel
def accelerations(chain, phi, phi_dot, pattern, ug, vg, phi_ddot, ws):
    """phi'' [rad/s^2] of every interface of ``pattern`` into ``phi_ddot`` (zero at the flat
    ones); the workspace keeps theta, theta', G, J, c and theta'' (``ws[12]``; its first 15
    arrays are enough)."""
    theta, theta_dot, centroid, jacobian, centripetal = ws[0], ws[1], ws[2], ws[3], ws[4]
    mass, reduced, generalized, theta_ddot, columns = ws[5], ws[6], ws[7], ws[12], ws[14]
    m = chain[2]
    n = m.size
    cumulate(phi, theta)
    cumulate(phi_dot, theta_dot)
    kinematics(chain, theta, theta_dot, pattern, centroid, jacobian, centripetal)
    opened = False
    for j in range(n):
        opened = opened or pattern[j] != 0
    if not opened:
        phi_ddot[:] = 0.0
        theta_ddot[:] = 0.0
        return
    for k in range(n):
        total = 0.0
        for i in range(k, n):
            fx = m[i] * (-ug - centripetal[i, 0])
            fy = m[i] * (-(G + vg) - centripetal[i, 1])
            total += jacobian[i, 0, k] * fx + jacobian[i, 1, k] * fy
        generalized[k] = total
    mass_matrix(chain, jacobian, mass)
    size = reduced_solve(mass, generalized, pattern, columns, reduced, ws[10], theta_ddot)
    phi_ddot[:] = 0.0
    for a in range(size):
        phi_ddot[columns[a]] = ws[10][a]


@kernel
def interface_loads(chain, pattern, theta, centroid, demand, spin, out):
    """What each interface carries for the blocks above it (the columns N, F, N at the -x
    corner, N at the +x corner of :func:`~shaketable.models.stack.physics.interface_loads`)
    into ``out`` (n, 4), from each block's ``demand`` (n, 2) and ``spin`` (n,)."""
    b, h = chain[0], chain[1]
    n = b.size
    rx, ry = 0.0, 0.0
    for j in range(n - 1, -1, -1):
        rx += demand[j, 0]
        ry += demand[j, 1]
        below = theta[j - 1] if j > 0 else 0.0
        cb, sb = math.cos(below), math.sin(below)
        out[j, 0] = -rx * sb + ry * cb
        out[j, 1] = rx * cb + ry * sb
        out[j, 2] = 0.0
        out[j, 3] = 0.0
        s = pattern[j]
        if s != 0:
            out[j, 2 if s > 0 else 3] = out[j, 0]
            continue
        cosine, sine = math.cos(theta[j]), math.sin(theta[j])
        bottom_x = centroid[j, 0] + sine * h[j]
        bottom_y = centroid[j, 1] - cosine * h[j]
        left_x, left_y = bottom_x - cosine * b[j], bottom_y - sine * b[j]
        right_x, right_y = bottom_x + cosine * b[j], bottom_y + sine * b[j]
        about_left, about_right = 0.0, 0.0
        for k in range(j, n):
            about_left += ((centroid[k, 0] - left_x) * demand[k, 1]
                           - (centroid[k, 1] - left_y) * demand[k, 0]) + spin[k]
            about_right += ((centroid[k, 0] - right_x) * demand[k, 1]
                            - (centroid[k, 1] - right_y) * demand[k, 0]) + spin[k]
        out[j, 3] = about_left / (2.0 * b[j])
        out[j, 2] = -about_right / (2.0 * b[j])


@kernel
def interface_forces(chain, pattern, ug, vg, ws, out):
    """Contact forces [N] into ``out`` (n, 4) from the state :func:`accelerations` left in
    the workspace (its first 13 arrays are enough)."""
    m, inertia = chain[2], chain[3]
    theta, centroid, jacobian, centripetal = ws[0], ws[2], ws[3], ws[4]
    demand, spin, theta_ddot = ws[9], ws[10], ws[12]
    n = m.size
    for i in range(n):
        ax, ay = centripetal[i, 0], centripetal[i, 1]
        for k in range(i + 1):
            ax += jacobian[i, 0, k] * theta_ddot[k]
            ay += jacobian[i, 1, k] * theta_ddot[k]
        demand[i, 0] = m[i] * ax + m[i] * ug
        demand[i, 1] = m[i] * ay + m[i] * (G + vg)
        spin[i] = inertia[i] * theta_ddot[i]
    interface_loads(chain, pattern, theta, centroid, demand, spin, out)


@inlined
def state_forces(chain, phi, phi_dot, pattern, ug, vg, phi_ddot, forces, ws):
    """phi'' and the contact forces of a state (into ``phi_ddot`` and ``forces``)."""
    accelerations(chain, phi, phi_dot, pattern, ug, vg, phi_ddot, ws[:15])
    interface_forces(chain, pattern, ug, vg, ws[:13], forces)


@kernel
def power(chain, ug, vg, ws):
    """Power of the table's inertial forces -m u'', -m v'' [W] in the state of the
    workspace (after :func:`kinematics`; its first four arrays are enough: each call of a
    compiled function passes every array it is given)."""
    m = chain[2]
    theta_dot, jacobian = ws[1], ws[3]
    total = 0.0
    for i in range(m.size):
        vx, vy = 0.0, 0.0
        for k in range(i + 1):
            vx += jacobian[i, 0, k] * theta_dot[k]
            vy += jacobian[i, 1, k] * theta_dot[k]
        total += m[i] * (ug * vx + vg * vy)
    return -total


@inlined
def table_power(chain, phi, phi_dot, pattern, ug, vg, ws):
    """Power of the table's inertial forces on a state [W]."""
    cumulate(phi, ws[0])
    cumulate(phi_dot, ws[1])
    kinematics(chain, ws[0], ws[1], pattern, ws[2], ws[3], ws[4])
    return power(chain, ug, vg, ws[:4])


@kernel
def energy(chain, phi, phi_dot, pattern, ws):
    """Kinetic energy in the table frame plus potential energy m g y above the table [J]
    (``ws``: the workspace's first six arrays are enough)."""
    m = chain[2]
    theta, theta_dot, centroid, jacobian, mass = ws[0], ws[1], ws[2], ws[3], ws[5]
    cumulate(phi, theta)
    cumulate(phi_dot, theta_dot)
    kinematics(chain, theta, theta_dot, pattern, centroid, jacobian, ws[4])
    mass_matrix(chain, jacobian, mass)
    kinetic = 0.0
    for k in range(m.size):
        for q in range(m.size):
            kinetic += theta_dot[k] * mass[k, q] * theta_dot[q]
    potential = 0.0
    for i in range(m.size):
        potential += m[i] * centroid[i, 1]
    return 0.5 * kinetic + G * potential


@inlined
def first_combination(chosen, count):
    for p in range(count):
        chosen[p] = p


@inlined
def next_combination(chosen, count, total):
    """Advance ``chosen[:count]`` to the next combination of range(total) in lexicographic
    order (itertools.combinations'); False after the last."""
    p = count - 1
    while p >= 0 and chosen[p] == total - count + p:
        p -= 1
    if p < 0:
        return False
    chosen[p] += 1
    for q in range(p + 1, count):
        chosen[q] = chosen[q - 1] + 1
    return True


@inlined
def fill_candidate(base, free, n_free, chosen, count, sides, candidate):
    """``base`` with the free interfaces flat, the chosen ones opened to the sides coded in
    the bits of ``sides`` (+1 for a 0 bit; the first chosen one in the highest bit)."""
    for j in range(base.size):
        candidate[j] = base[j]
    for p in range(n_free):
        candidate[free[p]] = 0
    for p in range(count):
        bit = (sides >> (count - 1 - p)) & 1
        candidate[free[chosen[p]]] = 1 if bit == 0 else -1


@kernel
def open_count(pattern):
    total = 0
    for j in range(pattern.size):
        if pattern[j] != 0:
            total += 1
    return total


@inlined
def plastic_candidate(chain, theta, theta_dot, velocity, centroid, candidate, ws, impulses,
                      phi_after):
    """Post-impact phi' (into ``phi_after``) and impulses of one active set of the plastic
    law (see :mod:`shaketable.models.stack.impact`)."""
    m, inertia = chain[2], chain[3]
    n = m.size
    after_map, mass, reduced, vector, solution = ws[11], ws[5], ws[6], ws[7], ws[12]
    demand, spin, columns, spare = ws[9], ws[10], ws[14], ws[13]
    kinematics(chain, theta, theta_dot, candidate, spare, after_map, ws[4])
    for k in range(n):
        total = 0.0
        for i in range(k, n):
            total += m[i] * (after_map[i, 0, k] * velocity[i, 0]
                             + after_map[i, 1, k] * velocity[i, 1])
        vector[k] = total + inertia[k] * theta_dot[k]
    mass_matrix(chain, after_map, mass)
    reduced_solve(mass, vector, candidate, columns, reduced, ws[10], solution)
    for i in range(n):
        vx, vy = 0.0, 0.0
        for k in range(i + 1):
            vx += after_map[i, 0, k] * solution[k]
            vy += after_map[i, 1, k] * solution[k]
        demand[i, 0] = m[i] * (vx - velocity[i, 0])
        demand[i, 1] = m[i] * (vy - velocity[i, 1])
    for i in range(n):
        spin[i] = inertia[i] * (solution[i] - theta_dot[i])
    interface_loads(chain, candidate, theta, centroid, demand, spin, impulses)
    previous = 0.0
    for i in range(n):
        phi_after[i] = solution[i] - previous
        previous = solution[i]


# rows of an event workspace (:func:`event_workspace`): its float rows (n,), int rows (n,),
# (n, 4) and (n, 2) arrays
R_THETA, R_THETA_DOT, R_TRIAL, R_BEST, R_BEST_ANY, R_UNIT = range(6)
R_FREE, R_START, R_CANDIDATE, R_CHOSEN, R_PATTERN, R_PATTERN_ANY = range(6)
W_IMPULSES = 0
P_CENTROID, P_VELOCITY = range(2)
#: Rows of an event workspace's arrays that the plastic law leaves to its callers (the
#: pattern check and the impact of :mod:`shaketable.models.stack.compiled`).
FREE_ROWS, FREE_INT_ROWS = 6, 6
N_ROWS, N_INT_ROWS, N_WIDE = 16, 16, 1


def event_workspace_size(n):
    """The float and int64 elements of an event workspace of ``n`` blocks
    (:func:`event_workspace`)."""
    count = 3 ** n if n <= FULL_ENUMERATION else 1
    lcp_reals, lcp_integers = lcp_workspace_size(n)
    return (N_ROWS * n + N_WIDE * n * 4 + 4 * n + 2 * n * n + 5 + 2 * n * count * n * 5
            + lcp_reals, N_INT_ROWS * n + 2 * n + lcp_integers)


@inlined
def event_workspace(reals, f, integers, i, n):
    """The arrays the events fill (the plastic law, the pattern check, the impact) for a
    chain of ``n`` blocks, so that an event allocates nothing: float rows (16, n), int rows
    (16, n), the impulses (1, n, 4), centroids and velocities (2, n, 2), a velocity map
    (n, 2, n), the choice's bookkeeping (5,), the per-unit-rate landings of one-DOF
    patterns (whether computed, and each candidate's post-impact phi' and impulses per
    rad/s, for each interface and side: :func:`plastic_impact`) and the complementarity
    pivot's arrays (:func:`~shaketable.models.stack.compiled_lcp.lcp_workspace`); views of
    the zeroed pools as :func:`workspace`'s."""
    count = 3 ** n if n <= FULL_ENUMERATION else 1
    size = 2 * n * count * n
    e0, f = reals[f:f + N_ROWS * n].reshape((N_ROWS, n)), f + N_ROWS * n
    e1, i = integers[i:i + N_INT_ROWS * n].reshape((N_INT_ROWS, n)), i + N_INT_ROWS * n
    e2, f = reals[f:f + N_WIDE * n * 4].reshape((N_WIDE, n, 4)), f + N_WIDE * n * 4
    e3, e4, f = reals[f:f + 4 * n].reshape((2, n, 2)), \
        reals[f + 4 * n:f + 4 * n + 2 * n * n].reshape((n, 2, n)), f + 4 * n + 2 * n * n
    e5, e6, i = reals[f:f + 5], integers[i:i + 2 * n], i + 2 * n
    f += 5
    e7, e8 = reals[f:f + size].reshape((2 * n, count, n)), \
        reals[f + size:f + 5 * size].reshape((2 * n, count, n, 4))
    e9, f, i = lcp_workspace(reals, f + 5 * size, integers, i, n)
    return (e0, e1, e2, e3, e4, e5, e6, e7, e8, e9), f, i


@inlined
def plastic_prepare(chain, phi, phi_dot, pattern, ws, scratch):
    """theta, theta', the centroids and the blocks' velocities [m/s] before the impact into
    the event workspace."""
    n = phi.size
    floats, pairs, before_map = scratch[0], scratch[3], scratch[4]
    theta, theta_dot = floats[R_THETA], floats[R_THETA_DOT]
    centroid, velocity = pairs[P_CENTROID], pairs[P_VELOCITY]
    cumulate(phi, theta)
    cumulate(phi_dot, theta_dot)
    kinematics(chain, theta, theta_dot, pattern, centroid, before_map, ws[4])
    for i in range(n):
        vx, vy = 0.0, 0.0
        for k in range(i + 1):
            vx += before_map[i, 0, k] * theta_dot[k]
            vy += before_map[i, 1, k] * theta_dot[k]
        velocity[i, 0] = vx
        velocity[i, 1] = vy


@inlined
def plastic_tolerances(chain, phi_dot, interface, theta_dot):
    """The plastic law's tolerances of the impulses [N s] and the separating rates
    [rad/s], relative to the landing's approach rate (above the rounding of the momenta of
    the whole motion)."""
    b, h, m = chain[0], chain[1], chain[2]
    fastest, reach, total_mass = 0.0, 0.0, 0.0
    for i in range(m.size):
        total_mass += m[i]
        fastest = max(fastest, abs(theta_dot[i]))
        reach = max(reach, math.hypot(b[i], h[i]))
    landing = abs(phi_dot[interface]) + ROUNDING * fastest + 1e-300
    return IMPACT_TOLERANCE * total_mass * landing * reach, IMPACT_TOLERANCE * landing


@inlined
def violation(candidate, trial, impulses, free, n_free, impulse_tolerance, rate_tolerance):
    """The worst violation of a candidate's admissibility, relative to the tolerances
    (admissible: at most 1)."""
    worst = 0.0
    for j in range(candidate.size):
        worst = max(worst, -impulses[j, 2] / impulse_tolerance,
                    -impulses[j, 3] / impulse_tolerance)
    for p in range(n_free):
        j = free[p]
        if candidate[j] != 0:
            worst = max(worst, -candidate[j] * trial[j] / rate_tolerance)
    return worst


@inlined
def consider(scratch, candidate, trial, worst):
    """Keep a candidate of the plastic law if it is the best so far: among the admissible
    ones the fewest open interfaces, then the least violation; else the least violation.
    The bookkeeping (admissible sets, the kept one's open count and violation, the least
    violation, the fewest open interfaces admissible) is ``scratch[5]``."""
    floats, ints, book = scratch[0], scratch[1], scratch[5]
    opened = open_count(candidate)
    if worst <= 1.0:
        book[0] += 1.0
        book[4] = min(book[4], opened)
        if book[0] == 1.0 or opened < book[1] or (opened == book[1] and worst < book[2]):
            book[1], book[2] = opened, worst
            for j in range(trial.size):
                floats[R_BEST, j] = trial[j]
                ints[R_PATTERN, j] = candidate[j]
    if worst < book[3]:
        book[3] = worst
        for j in range(trial.size):
            floats[R_BEST_ANY, j] = trial[j]
            ints[R_PATTERN_ANY, j] = candidate[j]


@inlined
def plastic_choice(scratch, phi_dot_after, pattern_after):
    """The kept candidate into the arrays given (flat interfaces at rate zero); returns the
    number of admissible active sets."""
    floats, ints, book = scratch[0], scratch[1], scratch[5]
    admissible = np.int64(book[0])
    row = R_BEST if admissible else R_BEST_ANY
    for j in range(phi_dot_after.size):
        phi_dot_after[j] = floats[row, j]
        pattern_after[j] = ints[R_PATTERN if admissible else R_PATTERN_ANY, j]
        if pattern_after[j] == 0:
            phi_dot_after[j] = 0.0
    return admissible


@inlined
def one_dof_landing(phi, phi_dot, pattern, interface):
    """Whether a landing is that of a one-DOF pattern: ``interface`` the only open one, every
    interface at zero gap, the other rates zero (the group above it one rigid body)."""
    if pattern[interface] == 0:
        return False
    for j in range(phi.size):
        if phi[j] != 0.0 or (j != interface and (pattern[j] != 0 or phi_dot[j] != 0.0)):
            return False
    return True


@kernel
def plastic_impact(chain, phi, phi_dot, pattern, interface, held, ws, scratch,
                   phi_dot_after, pattern_after):
    """The plastic, no-slip multi-contact law, compiled
    (:func:`~shaketable.models.stack.impact.plastic_impact`): post-impact phi' and pattern
    into the arrays given; returns the number of admissible active sets. ``held``: the
    interfaces held flat, as the bits of an int64 (bit j: interface j; 0: none).

    Above FULL_ENUMERATION blocks the complementarity pivot's solution is taken
    (:func:`~shaketable.models.stack.compiled_lcp.lcp_candidate`): admissible, it is the
    one admissible set; not admissible (a pivot pulls), it is kept all the same (the
    pivots held, as the model holds them between impacts). Up to FULL_ENUMERATION blocks,
    and where the pivot finds none (a flight, or no convergence), every active set is tried
    in the candidates' order, each considered (:func:`consider`).
    At a landing of a one-DOF pattern (:func:`one_dof_landing`) of up to FULL_ENUMERATION
    blocks, the candidates' post-impact rates and impulses are linear in the landing's
    rate (the momentum balance and the admissibility are linear in the velocities before;
    the geometry at zero gap is fixed): they are computed once per interface and side at
    1 rad/s (kept in the event workspace) and scaled, agreeing with the general law's to
    rounding. It allocates nothing: compiled without reference counting."""
    n = phi.size
    floats, ints, wide, pairs, book = scratch[0], scratch[1], scratch[2], scratch[3], scratch[5]
    theta_dot = floats[R_THETA_DOT]
    cumulate(phi_dot, theta_dot)
    impulse_tolerance, rate_tolerance = plastic_tolerances(chain, phi_dot, interface,
                                                           theta_dot)
    store = NONE_INTERFACE
    if held == 0 and n <= FULL_ENUMERATION and \
            one_dof_landing(phi, phi_dot, pattern, interface):
        store = 2 * interface + (0 if pattern[interface] > 0 else 1)
    cached = store >= 0 and scratch[6][store] != 0
    rate = phi_dot[interface]
    if store >= 0 and not cached:
        unit = floats[R_UNIT]   # the first such landing: its candidates at 1 rad/s
        for j in range(n):
            unit[j] = 0.0
        unit[interface] = 1.0
        plastic_prepare(chain, phi, unit, pattern, ws, scratch)
    elif not cached:
        plastic_prepare(chain, phi, phi_dot, pattern, ws, scratch)
    theta = floats[R_THETA]
    free, start, candidate, chosen = ints[R_FREE], ints[R_START], ints[R_CANDIDATE], \
        ints[R_CHOSEN]
    trial, impulses = floats[R_TRIAL], wide[W_IMPULSES]
    unit_trial, unit_impulses = scratch[7], scratch[8]
    n_free = np.int64(0)   # not a literal 0: one compile of its callees
    for j in range(n):
        if phi[j] == 0.0:
            free[n_free] = j
            n_free += 1
    for j in range(n):
        start[j] = pattern[j]
    start[interface] = 0
    book[0], book[1], book[2], book[3], book[4] = 0.0, 0.0, math.inf, math.inf, n + 1
    rows = -1 if n <= FULL_ENUMERATION else lcp_solve(
        chain, theta, floats[R_THETA_DOT], pairs[P_VELOCITY], pairs[P_CENTROID], phi, start,
        held, scratch[9])
    widest = 0.0   # the widest block's width [m]: the rate tolerance's lever (past 3 blocks)
    for j in range(n if rows > 0 else 0):
        widest = max(widest, 2.0 * chain[0][j])
    for attempt in range(2 if rows > 0 else 0):
        # the complementarity pivot's solution, the one admissible set when there is one:
        # first with the corners that separate within the tolerance closed (as few
        # interfaces open as the tolerance allows), then as solved
        closing = 1.0 if attempt == 0 else -1.0
        if lcp_candidate(phi, scratch[9], rows, start, closing * rate_tolerance * widest,
                         closing * impulse_tolerance, candidate):
            plastic_candidate(chain, theta, floats[R_THETA_DOT], pairs[P_VELOCITY],
                              pairs[P_CENTROID], candidate, ws, impulses, trial)
            consider(scratch, candidate, trial, violation(
                candidate, trial, impulses, free, n_free, impulse_tolerance, rate_tolerance))
            if book[0] > 0.0:
                return plastic_choice(scratch, phi_dot_after, pattern_after)
    if book[3] < math.inf:
        # none admissible: a pivot would pull (the impact throws a block into flight, outside
        # the model): the pivot's solution, the pivots held (the least violating of its two)
        return plastic_choice(scratch, phi_dot_after, pattern_after)
    index = 0
    for count in range(n_free + 1):
        if n > FULL_ENUMERATION and book[4] < count:
            break   # an admissible set with fewer open interfaces is already found
        first_combination(chosen, count)
        going = True
        while going:
            for sides in range(1 << count):
                fill_candidate(start, free, n_free, chosen, count, sides, candidate)
                if held != 0 and opens_held(candidate, held):
                    continue
                if not cached:
                    plastic_candidate(chain, theta, floats[R_THETA_DOT], pairs[P_VELOCITY],
                                      pairs[P_CENTROID], candidate, ws, impulses, trial)
                if store >= 0:
                    for j in range(n):
                        if not cached:
                            unit_trial[store, index, j] = trial[j]
                        trial[j] = rate * unit_trial[store, index, j]
                        for c in range(4):
                            if not cached:
                                unit_impulses[store, index, j, c] = impulses[j, c]
                            impulses[j, c] = rate * unit_impulses[store, index, j, c]
                    index += 1
                consider(scratch, candidate, trial, violation(
                    candidate, trial, impulses, free, n_free, impulse_tolerance,
                    rate_tolerance))
            going = next_combination(chosen, count, n_free)
    if store >= 0:
        scratch[6][store] = 1
    return plastic_choice(scratch, phi_dot_after, pattern_after)


@inlined
def opens_held(candidate, held):
    """Whether ``candidate`` opens an interface of the bits ``held``."""
    for j in range(candidate.size):
        if (held >> j) & 1 and candidate[j] != 0:
            return True
    return False


@inlined
def cor_impact(phi_dot, pattern, interface, cor, phi_dot_after, pattern_after):
    """The constant-COR law: every absolute rate times ``cor``; the impacting interface onto
    its other corner (flat when its rate after is zero)."""
    previous_before, previous_after = 0.0, 0.0
    total = 0.0
    for i in range(phi_dot.size):
        total += phi_dot[i]
        after = cor * total
        phi_dot_after[i] = after - previous_after
        previous_after = after
        previous_before = total
        pattern_after[i] = pattern[i]
    pattern_after[interface] = -pattern[interface]
    if phi_dot_after[interface] == 0.0:
        pattern_after[interface] = 0
    return previous_before
