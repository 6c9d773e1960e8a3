"""The planar rigid block on a moving table: five contact modes, their forces, start rules
and the impact law (the model that the compiled engine and the SciPy reference
solver both follow).

Everything is per unit mass, in the table's (non-inertial) frame, with the package's
sign convention (:mod:`shaketable.models.rocking.physics`): ``theta > 0`` pivots on the bottom
corner at -x (side ``s = +1``), ``theta < 0`` on the corner at +x (``s = -1``).
Coordinates: ``x`` the horizontal displacement of the centre of mass [m], ``y`` its
height above the table [m] (``y = h`` standing flat), ``theta`` [rad]. A body point
(u, w) is at ``X = x + u cos(theta) - w sin(theta)``, ``Y = y + u sin(theta) + w cos(theta)``;
the bottom corner of side ``s`` is (u, w) = (-s b, -h), and the vector from the centre to it

    r_x = -s b cos(theta) + h sin(theta),      r_y = -s b sin(theta) - h cos(theta).

Equations of motion with the contact force (F, N) per unit mass at the active corner
(Newton-Euler; Ic = R^2/3 the centroidal inertia per mass, I0 = 4 R^2 / 3):

    x'' = -ug + F,      y'' = -(g + vg) + N,      Ic theta'' = r_x N - r_y F.

Modes (integer codes): REST 0 (flat, sticking), SLIDE 1 (flat, slipping), ROCK 2 (one
corner, sticking), SLIDE_ROCK 3 (one corner, slipping), FLIGHT 4 (no contact).

* ROCK: theta'' is Eq. (2-13) as :func:`shaketable.models.rocking.physics.flight_acceleration`
  (so the rocking limit is the rocking engine's model); F and N follow from the fixed
  pivot's kinematics, :func:`rock_forces`.
* SLIDE_ROCK with slip direction ``sigma`` (the sign of the corner's velocity X_s'):
  F = -sigma mu_d N, and theta'', N from the constraint Y_s'' = 0 and the moment
  equation, :func:`slide_rock_accelerations`; the corner's X_s'' from the horizontal
  equation. The "effective mass" D = Ic + r_x (r_x + sigma mu_d r_y) must be positive;
  D <= 0 is Painleve's paradox (the run stops with status "painleve").
* REST, SLIDE, FLIGHT are closed forms in the solver (linear ground acceleration between
  samples); their conditions are :func:`rest_margins` and :func:`start_mode`.

Impacts (:func:`impact`): a plastic normal impulse at the striking corner k plus the
couple C = (rho - 1) H_k' with H_k' the angular momentum about k in the frame that moves
with the corner's incoming slip, (Ic + r_y^2) theta' - r_x y' (no dependence on a uniform
sliding speed; the table frame's H_k when the corner arrives without slipping, as in every
rock-to-rock impact), rho = cor / c_H (c_H = 1 - 1.5 sin^2(alpha), Housner's ratio) for a
numeric COR and rho = 1 for Housner's law (the plastic Newton law); sticking if the
tangential impulse needed is within mu_s times the normal one, else slipping with mu_d
toward sigma = -sign(sticking P_x). Decision beyond the model text: when the corner's
velocity after that slipping impact does not have the sign sigma, the other direction is
tried, and if neither is consistent the impact sticks (a plastic normal impact then has
no Coulomb solution). The normal impulse never pulls and the kinetic energy never grows
(in the table's frame nor in the slip frame): where the law at rho would, rho is moved
toward 1 (from either side) to the nearest root, the branch decided again there (at
most 8 times; counted as capped unless the gain was of rounding size). At theta = 0 with
both corners on the table, :func:`two_corner_impact` solves the plastic two-corner
problem (docs/planar.md, "Both corners on the table").

Every function here is compiled with numba and works on floats and the parameter
array of :func:`shaketable.models.rocking.physics.block_parameters` (rods are refused upstream).
"""

from __future__ import annotations

import math
from typing import Any

from numba import njit

from shaketable.core.constants import G
from shaketable.models.rocking.physics import (
    ALPHA,
    ALPHA_MINUS,
    ASYMMETRIC,
    CENTROIDAL,
    ERROR_MODEL,
    HALF_HEIGHT,
    HALF_WIDTH,
    HALF_WIDTH_MINUS,
    INERTIA,
    INERTIA_MINUS,
    flight_acceleration,
)

#: Mode codes, in the order of the model text (their names:
#: :data:`shaketable.models.planar.result.MODES`).
REST, SLIDE, ROCK, SLIDE_ROCK, FLIGHT = 0, 1, 2, 3, 4

#: Outcome of :func:`start_mode` when no mode is consistent.
INCONSISTENT = -1

#: Outcome of :func:`impact` / :func:`slide_rock_accelerations` with D <= 0 (Painleve).
PAINLEVE = -2

#: Relative kinetic-energy gain of an impact below which the energy cap is rounding (a
#: COR 1 impact conserves the energy to its last ulps) and the impact is not counted as
#: capped [-].
ENERGY_ROUNDING = 1e-12

#: numba options of the compiled functions that only compiled code calls (here and in the
#: planar engine's modules): no Python entry point (nor C callback) is built for them,
#: about 0.05 s less of a first compile each. Those that Python calls keep ``cache=True``.
HELPER: Any = {"cache": True, "no_cpython_wrapper": True, "no_cfunc_wrapper": True,
               "error_model": ERROR_MODEL}


@njit(**HELPER)
def centroidal_inertia(parameters):
    """Ic per unit mass [m^2]: R^2 / 3 = I0 / 4 of a rectangle, k^2 of an asymmetric block."""
    if parameters[ASYMMETRIC] == 0.0:
        return 0.25 * parameters[INERTIA]
    return parameters[CENTROIDAL]


@njit(**HELPER)
def half_width(side, parameters):
    """b_s [m]: the horizontal distance from the centre of mass to the bottom corner of
    ``side`` (+1: the corner at -x, the pivot of theta > 0; -1: the corner at +x)."""
    return parameters[HALF_WIDTH] if side > 0.0 else parameters[HALF_WIDTH_MINUS]


@njit(**HELPER)
def block_angle(side, parameters):
    """alpha_s = atan(b_s / h) [rad] of the pivot ``side``."""
    return parameters[ALPHA] if side > 0.0 else parameters[ALPHA_MINUS]


@njit(cache=True, error_model=ERROR_MODEL)
def pivot_acceleration(theta, side, ug, vg, parameters):
    """theta'' [rad/s^2] of the block turning about its corner ``side`` held fixed: Eq.
    (2-13) with that pivot's b_s and I0_s (:func:`~shaketable.models.rocking.physics.flight_acceleration`
    for a symmetric block, exactly)."""
    if parameters[ASYMMETRIC] == 0.0:
        return flight_acceleration(theta, side, ug, vg, 0.0, parameters)
    b = half_width(side, parameters)
    h = parameters[HALF_HEIGHT]
    cosine = math.cos(theta)
    sine = math.sin(theta)
    moment = ug * (h * cosine + side * b * sine) - (G + vg) * (side * b * cosine - h * sine)
    return moment / (parameters[INERTIA] if side > 0.0 else parameters[INERTIA_MINUS])


@njit(cache=True, error_model=ERROR_MODEL)
def corner_vector(theta, side, parameters):
    """(r_x, r_y) [m]: from the centre of mass to the bottom corner of ``side``."""
    b = half_width(side, parameters)
    h = parameters[HALF_HEIGHT]
    cosine = math.cos(theta)
    sine = math.sin(theta)
    return -side * b * cosine + h * sine, -side * b * sine - h * cosine


@njit(cache=True, error_model=ERROR_MODEL)
def rock_forces(theta, omega, side, ug, vg, parameters):
    """ROCK about ``side``: theta'' [rad/s^2] (Eq. 2-13), the centre's x'', y'' [m/s^2]
    and the contact force F, N per unit mass [m/s^2] that hold the pivot."""
    acceleration = pivot_acceleration(theta, side, ug, vg, parameters)
    r_x, r_y = corner_vector(theta, side, parameters)
    omega2 = omega * omega
    x_dd = r_y * acceleration + r_x * omega2
    y_dd = -r_x * acceleration + r_y * omega2
    return acceleration, x_dd, y_dd, x_dd + ug, y_dd + G + vg


@njit(cache=True, error_model=ERROR_MODEL)
def slide_rock_accelerations(theta, omega, side, sigma, mu_d, ug, vg, parameters):
    """SLIDE_ROCK about ``side`` slipping toward ``sigma``.

    Returns theta'' [rad/s^2], the corner's X_s'' [m/s^2], F, N [m/s^2] and the
    effective mass D = Ic + r_x (r_x + sigma mu_d r_y) [m^2] (Painleve when D <= 0:
    theta'', X_s'', F, N are then returned as 0 and the caller stops).
    """
    inertia = centroidal_inertia(parameters)
    r_x, r_y = corner_vector(theta, side, parameters)
    c = r_x + sigma * mu_d * r_y
    d = inertia + c * r_x
    if not d > 0.0:
        return 0.0, 0.0, 0.0, 0.0, d
    normal = (G + vg + r_y * omega * omega) * inertia / d
    acceleration = normal * c / inertia
    friction = -sigma * mu_d * normal
    corner_dd = -ug + friction - r_y * acceleration - r_x * omega * omega
    return acceleration, corner_dd, friction, normal, d


@njit(**HELPER)
def rest_margins(ug, vg, mu_s, parameters):
    """The three REST conditions as margins that are positive when they FAIL.

    Returns (lift, slip, tip): lift = -(g + vg) (N > 0 fails), slip = |ug| - mu_s N,
    tip = |ug| h - b N (Eq. 2-1).
    """
    normal = G + vg
    return (-normal, abs(ug) - mu_s * normal,
            abs(ug) * parameters[HALF_HEIGHT]
            - half_width(1.0 if ug > 0.0 else -1.0, parameters) * normal)


@njit(**HELPER)
def start_mode(ug, vg, mu_s, mu_d, parameters):
    """The start rules: the mode a flat block at rest takes when REST fails.

    Returns (mode, side, sigma): side s = sign(ug) for the rocking modes, the slip
    direction sigma = -sign(ug) for the slipping ones. REST when all rest conditions
    hold; :data:`INCONSISTENT` when no mode is consistent.
    """
    normal = G + vg
    if normal <= 0.0:
        return FLIGHT, 1.0, 0.0
    h = parameters[HALF_HEIGHT]
    side = 1.0 if ug > 0.0 else -1.0
    # a flat slide toward -side has its centre of pressure sigma mu_d h from the centre's
    # foot, within the base if mu_d h <= b_side
    b = half_width(side, parameters)
    # Eq. (2-1) as the rocking engine tests it: the moment toward ``side`` at theta = 0
    tipping = side * pivot_acceleration(0.0, side, ug, vg, parameters) > 0.0
    if tipping:
        _, _, _, friction, normal_rock = rock_forces(0.0, 0.0, side, ug, vg, parameters)
        if normal_rock > 0.0 and abs(friction) <= mu_s * normal_rock:
            return ROCK, side, 0.0
        sigma = -side
        acceleration, corner_dd, _, normal_slip, d = slide_rock_accelerations(
            0.0, 0.0, side, sigma, mu_d, ug, vg, parameters)
        if d > 0.0 and normal_slip > 0.0 and side * acceleration > 0.0 \
                and sigma * corner_dd > 0.0:
            return SLIDE_ROCK, side, sigma
    if abs(ug) > mu_s * normal:
        if mu_d <= b / h:
            return SLIDE, side, -side
        return INCONSISTENT, side, -side
    if tipping:
        return INCONSISTENT, side, -side
    return REST, side, 0.0


@njit(cache=True, error_model=ERROR_MODEL)
def housner_ratio(parameters):
    """c_H = 1 - 1.5 sin^2(alpha) [-]: angular velocity ratio of Housner's impact."""
    sine = math.sin(parameters[ALPHA])
    return 1.0 - 1.5 * sine * sine


@njit(cache=True, error_model=ERROR_MODEL)
def kinetic_energy(x_dot, y_dot, omega, parameters):
    """Kinetic energy per unit mass [m^2/s^2]."""
    return 0.5 * (x_dot * x_dot + y_dot * y_dot
                  + centroidal_inertia(parameters) * omega * omega)


@njit(**HELPER)
def _impact_post(x_dot, y_dot, omega, r_x, r_y, rho, force, mu_s, mu_d, parameters):
    """Post-impact state for a given rho: ``force`` 0 decides, 1 forces sticking,
    +-2 forces slipping with sigma = +-1. Returns (x', y', omega, kind, sigma, P_y) with
    kind ROCK (sticking), SLIDE_ROCK (slipping) or PAINLEVE, P_y the normal impulse [m/s].

    The couple is C = (rho - 1) H_k', H_k' the angular momentum about the striking corner
    in the frame that moves with the corner's incoming slip u = x' - r_y omega:
    H_k' = H_k - r_y u = (Ic + r_y^2) omega - r_x y' (H_k the table frame's).
    """
    inertia = centroidal_inertia(parameters)
    # I0 about the striking corner (of an asymmetric block: Ic + |r|^2, that corner's)
    i0 = parameters[INERTIA] if parameters[ASYMMETRIC] == 0.0 \
        else inertia + r_x * r_x + r_y * r_y
    momentum = inertia * omega - r_x * y_dot + r_y * x_dot
    slip = x_dot - r_y * omega
    # a corner that does not slip in (every sticking rock-to-rock impact): the table
    # frame's H_k, evaluated as before
    frame_momentum = momentum if slip == 0.0 else momentum - r_y * slip
    couple = (rho - 1.0) * frame_momentum
    # I0 omega+ = H_k+ = H_k + C about the corner that sticks
    omega_stick = rho * momentum / i0 if slip == 0.0 else (momentum + couple) / i0
    xs = omega_stick * r_y
    ys = -omega_stick * r_x
    px = xs - x_dot
    py = ys - y_dot
    if force == 1.0 or (force == 0.0 and py > 0.0 and abs(px) <= mu_s * py):
        return xs, ys, omega_stick, ROCK, 0.0, py
    if force != 0.0:
        return _slipping_impact(x_dot, y_dot, omega, r_x, r_y, couple, 0.5 * force, mu_d,
                                parameters)
    # the corner slips the way the sticking impulse could not stop it; if its velocity
    # after the impact does not have that sign, the other direction is tried; if neither
    # is consistent (no Coulomb solution with a plastic normal impact), it sticks
    sigma = 1.0 if px < 0.0 else -1.0
    for trial in (sigma, -sigma):
        xa, ya, wa, kind, _, pa = _slipping_impact(x_dot, y_dot, omega, r_x, r_y, couple,
                                                   trial, mu_d, parameters)
        if kind == PAINLEVE:
            return xa, ya, wa, kind, trial, pa
        if trial * (xa - wa * r_y) >= 0.0:
            return xa, ya, wa, SLIDE_ROCK, trial, pa
    return xs, ys, omega_stick, ROCK, 0.0, py


@njit(**HELPER)
def _slipping_impact(x_dot, y_dot, omega, r_x, r_y, couple, sigma, mu_d, parameters):
    """Post-impact state of a corner slipping toward ``sigma``: P_x = -sigma mu_d P_y,
    the couple, Y_k'+ = 0. Returns (x', y', omega, kind, sigma, P_y)."""
    inertia = centroidal_inertia(parameters)
    c = r_x + sigma * mu_d * r_y
    d = inertia + r_x * c
    if not d > 0.0:
        return x_dot, y_dot, omega, PAINLEVE, sigma, 0.0
    corner_normal = y_dot + r_x * omega
    py = -(corner_normal + r_x * couple / inertia) * inertia / d
    x_new = x_dot - sigma * mu_d * py
    y_new = y_dot + py
    omega_new = omega + (couple + py * c) / inertia
    return x_new, y_new, omega_new, SLIDE_ROCK, sigma, py


@njit(**HELPER)
def _energy_fraction(x1, y1, w1, xa, ya, wa, shift, before, inertia_root):
    """The fraction f in [0, 1] of the way from the post state at rho = 1 (x1, y1, w1) to
    the one at rho_eff (xa, ya, wa) where the kinetic energy, in the frame moving at
    ``shift`` along x, reaches ``before`` (1 when it does not; 0 when even rho = 1 gains)."""
    b0, b1, b2 = x1 - shift, y1, inertia_root * w1
    d0, d1, d2 = xa - x1, ya - y1, inertia_root * (wa - w1)
    qa = d0 * d0 + d1 * d1 + d2 * d2
    qb = 2.0 * (b0 * d0 + b1 * d1 + b2 * d2)
    qc = b0 * b0 + b1 * b1 + b2 * b2 - 2.0 * before
    fraction = 0.0
    if qa > 0.0 and qc <= 0.0:
        root = (-qb + math.sqrt(max(qb * qb - 4.0 * qa * qc, 0.0))) / (2.0 * qa)
        fraction = min(max(root, 0.0), 1.0)
    return fraction


@njit(cache=True, error_model=ERROR_MODEL)
def impact(theta, x_dot, y_dot, omega, side, rho, mu_s, mu_d, parameters):
    """Impact of the bottom corner ``side`` (striking with Y' < 0) on the table.

    Parameters
    ----------
    theta : float
        Rotation at impact [rad].
    x_dot, y_dot, omega : float
        Pre-impact centre velocity [m/s] and angular velocity [rad/s].
    side : float
        The striking corner, +1 (at -x) or -1.
    rho : float
        Angular momentum ratio about the corner [-]: cor / c_H, or 1 (Housner).
    mu_s, mu_d : float
        Friction coefficients [-].

    Returns
    -------
    tuple
        (x', y', omega after, mode after (ROCK, SLIDE_ROCK or PAINLEVE), slip
        direction sigma, kinetic energy lost [m^2/s^2], capped (1.0 when rho was
        lowered to keep the kinetic energy from growing, else 0.0)).
    """
    r_x, r_y = corner_vector(theta, side, parameters)
    before = kinetic_energy(x_dot, y_dot, omega, parameters)
    xa, ya, wa, kind, sigma, pa = _impact_post(x_dot, y_dot, omega, r_x, r_y, rho, 0.0,
                                               mu_s, mu_d, parameters)
    if kind == PAINLEVE:
        return xa, ya, wa, PAINLEVE, sigma, 0.0, 0.0
    after = kinetic_energy(xa, ya, wa, parameters)
    # the slip frame (moving with the corner's incoming slip u): no gain there either, so
    # that the capped law, like the couple, does not depend on a uniform sliding speed
    u = x_dot - r_y * omega
    before_u = kinetic_energy(x_dot - u, y_dot, omega, parameters)
    after_u = kinetic_energy(xa - u, ya, wa, parameters)
    capped = 0.0
    rho_eff = rho
    inertia_root = math.sqrt(centroidal_inertia(parameters))
    for _ in range(8):
        if rho_eff == 1.0 or (after <= before and after_u <= before_u and pa >= 0.0):
            break
        if pa < 0.0 or after - before > ENERGY_ROUNDING * before \
                or after_u - before_u > ENERGY_ROUNDING * before_u:
            capped = 1.0   # not a gain of rounding size (a COR 1 impact's last ulps)
        # the post state is affine in rho along one branch: move rho toward 1 (from
        # either side: rho > 1 when cor > c_H, rho < 1 when the couple with a slipping
        # corner adds energy) to where KE+ = KE- (in both frames) and the normal impulse
        # does not pull (P_y >= 0; at rho = 1 the plastic impulse of a striking corner
        # pushes), and decide the branch again there
        force = 1.0 if kind == ROCK else 2.0 * sigma
        x1, y1, w1, _, _, p1 = _impact_post(x_dot, y_dot, omega, r_x, r_y, 1.0, force,
                                            mu_s, mu_d, parameters)
        fraction = min(_energy_fraction(x1, y1, w1, xa, ya, wa, 0.0, before, inertia_root),
                       _energy_fraction(x1, y1, w1, xa, ya, wa, u, before_u, inertia_root))
        if pa < 0.0:
            fraction = min(fraction, max(p1, 0.0) / (p1 - pa))
        rho_eff = 1.0 + fraction * (rho_eff - 1.0)
        xa, ya, wa, kind, sigma, pa = _impact_post(x_dot, y_dot, omega, r_x, r_y, rho_eff,
                                                   0.0, mu_s, mu_d, parameters)
        if kind == PAINLEVE:
            return xa, ya, wa, PAINLEVE, sigma, 0.0, 1.0
        after = kinetic_energy(xa, ya, wa, parameters)
        after_u = kinetic_energy(xa - u, ya, wa, parameters)
    return xa, ya, wa, kind, sigma, before - after, capped


@njit(**HELPER)
def flat_landing(x_dot, y_dot, mu_s, mu_d):
    """Plastic landing of the whole base (theta = theta' = 0): (x' after, mode after).

    Sticks (REST) if |x'| <= mu_s |y'|, else slides on with x' reduced by mu_d |y'|.
    """
    if abs(x_dot) <= mu_s * abs(y_dot):
        return 0.0, REST
    return x_dot - math.copysign(mu_d * abs(y_dot), x_dot), SLIDE


@njit(**HELPER)
def flat_impulses_push(moment, total, parameters):
    """Whether both corners push when the base lands flat.

    With the normal impulses ``P+`` at ``-b+`` and ``P-`` at ``+b-`` from the centre's foot,
    their sum ``total`` and the angular impulse they must supply about the centre,
    ``-moment`` (``moment = Ic theta'- + h F``), ``P+ = (b- total + moment) / (b+ + b-)``
    must lie in [0, total]."""
    return -parameters[HALF_WIDTH_MINUS] * total <= moment <= parameters[HALF_WIDTH] * total


@njit(**HELPER)
def two_corner_impact(x_dot, y_dot, omega, mu_s, mu_d, parameters):
    """Plastic impact of the block at theta = 0 with both bottom corners on the table.

    The two-corner contact problem at the impulse level (plastic Newton law, the limit
    of Moreau-Jean time-stepping; Coulomb friction): normal impulses ``P_s >= 0``, gap rates
    ``Y_s'+ >= 0``, ``P_s Y_s'+ = 0`` (s = +-1), the tangential impulse F within mu_s sum(P) if
    the base's slip x' + h omega stops, else -sigma mu_d sum(P). At theta = 0 both
    corners slip alike, so only F's sum matters. Its solutions are enumerated: both
    corners push (the base lands flat: y'+ = omega+ = 0, ``P_+ - P_- = (Ic omega + h F) / b``
    with both ``P_s >= 0``, i.e. |Ic omega + h F| <= b sum(P)), else one corner s pushes
    (:func:`impact` at s with rho = 1: Housner's plastic impact) and the other rises
    (s omega+ >= 0). The flat solution is taken first (a landing with mu_d <= b/h is the
    sliding model's); none consistent leaves the flat solution with F at the limit.

    Returns
    -------
    tuple
        (x', y', omega after, mode after: REST, SLIDE, ROCK, SLIDE_ROCK or PAINLEVE,
        side s of the corner that pushes alone (0.0 when flat), slip direction sigma).
    """
    b = parameters[HALF_WIDTH]
    h = parameters[HALF_HEIGHT]
    inertia = centroidal_inertia(parameters)
    total = -y_dot
    if total >= 0.0:
        spin = inertia * omega
        if parameters[ASYMMETRIC] == 0.0:
            holds = abs(spin - h * x_dot) <= b * total
        else:
            holds = flat_impulses_push(spin - h * x_dot, total, parameters)
        if abs(x_dot) <= mu_s * total and holds:
            return 0.0, 0.0, 0.0, REST, 0.0, 0.0
        direction = 1.0 if x_dot > 0.0 else -1.0
        friction = -direction * mu_d * total
        if parameters[ASYMMETRIC] == 0.0:
            holds = abs(spin + h * friction) <= b * total
        else:
            holds = flat_impulses_push(spin + h * friction, total, parameters)
        if abs(x_dot) > mu_d * total and holds:
            return x_dot - math.copysign(mu_d * total, x_dot), 0.0, 0.0, SLIDE, 0.0, \
                direction
    for side in (1.0, -1.0):
        if y_dot - side * half_width(side, parameters) * omega >= 0.0:
            continue   # this corner does not move into the table
        r_x, r_y = corner_vector(0.0, side, parameters)
        xa, ya, wa, kind, sigma, pa = _impact_post(x_dot, y_dot, omega, r_x, r_y, 1.0, 0.0,
                                                   mu_s, mu_d, parameters)
        if kind == PAINLEVE:
            return xa, ya, wa, PAINLEVE, side, sigma
        if pa >= 0.0 and side * wa >= 0.0:
            return xa, ya, wa, kind, side, sigma
    direction = 1.0 if x_dot > 0.0 else -1.0
    slipped = abs(x_dot) > mu_s * max(total, 0.0)
    x_new = x_dot - math.copysign(mu_d * max(total, 0.0), x_dot) if slipped else 0.0
    return x_new, 0.0, 0.0, SLIDE if slipped else REST, 0.0, direction if slipped else 0.0


@njit(inline="always", error_model=ERROR_MODEL)   # one caller: inlined there
def corner_height(y, theta, side, parameters):
    """Height Y_s of the bottom corner of ``side`` above the table [m]."""
    return (y - side * half_width(side, parameters) * math.sin(theta)
            - parameters[HALF_HEIGHT] * math.cos(theta))


@njit(**HELPER)
def corner_height_rate(y_dot, theta, omega, side, parameters):
    """Y_s' [m/s] of the bottom corner of ``side``."""
    r_x, _ = corner_vector(theta, side, parameters)
    return y_dot + omega * r_x
