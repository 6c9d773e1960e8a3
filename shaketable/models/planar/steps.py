"""The steppers of the planar engine (:mod:`shaketable.models.planar.engine`), compiled with numba.

* ROCK and SLIDE_ROCK: the state z = [theta, theta', X_s, X_s', W_ground, W_friction]
  (X_s the active corner's horizontal position [m], fixed in ROCK; W the work per unit
  mass of the table's inertial force and of friction [m^2/s^2], integrated with the
  motion) advanced by the explicit Runge-Kutta pair DOP853 of Dormand & Prince (order 8,
  error estimators of orders 5 and 3; Hairer, Norsett & Wanner, Solving ODEs I, Sec. II.10),
  with the physics of :mod:`shaketable.models.planar.physics`. (The Nystrom pair of the
  rocking engine needs theta'' = f(t, theta); SLIDE_ROCK has theta'^2 terms.)
* Events are zeros of event functions of the state, located on the accepted step's
  continuous extension of order 7 (Hairer's contd8: three more stages, built only for a
  step in which an event is looked for) by Newton's step or the Illinois variant of
  regula falsi, safeguarded by bisection, to a bracket of a few ulps.
* REST, SLIDE and FLIGHT are closed forms (the table accelerations are linear between
  samples): the polynomial helpers here.

Every function is compiled with :data:`~shaketable.models.planar.physics.HELPER`'s options,
the error model :data:`~shaketable.models.rocking.physics.ERROR_MODEL` included.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from shaketable.core.constants import G
from shaketable.models.planar.physics import (
    HELPER,
    ROCK,
    block_angle,
    corner_vector,
    pivot_acceleration,
    rock_forces,
    slide_rock_accelerations,
)
from shaketable.models.rocking.physics import HALF_HEIGHT, HALF_WIDTH, HALF_WIDTH_MINUS

# DOP853 tableau (Hairer, Norsett & Wanner; the numbers of SciPy's dop853_coefficients.py)
_C = np.array([
    0.0, 0.05260015195876773, 0.0789002279381516, 0.1183503419072274,
    0.2816496580927726, 0.3333333333333333, 0.25, 0.3076923076923077,
    0.6512820512820513, 0.6, 0.8571428571428571, 1.0])
_B = np.array([
    0.054293734116568765, 0.0, 0.0, 0.0, 0.0, 4.450312892752409,
    1.8915178993145003, -5.801203960010585, 0.3111643669578199,
    -0.1521609496625161, 0.20136540080403034, 0.04471061572777259])
_E3 = np.array([
    -0.18980075407240762, 0.0, 0.0, 0.0, 0.0, 4.450312892752409,
    1.8915178993145003, -5.801203960010585, -0.4226823213237919,
    -0.1521609496625161, 0.20136540080403034, 0.02265179219836082])
_E5 = np.array([
    0.01312004499419488, 0.0, 0.0, 0.0, 0.0, -1.2251564463762044,
    -0.4957589496572502, 1.6643771824549864, -0.35032884874997366,
    0.3341791187130175, 0.08192320648511571, -0.022355307863886294])
_A = np.zeros((12, 12))
_A[1, 0] = 0.05260015195876773
_A[2, 0] = 0.0197250569845379
_A[2, 1] = 0.0591751709536137
_A[3, 0] = 0.02958758547680685
_A[3, 2] = 0.08876275643042054
_A[4, 0] = 0.2413651341592667
_A[4, 2] = -0.8845494793282861
_A[4, 3] = 0.924834003261792
_A[5, 0] = 0.037037037037037035
_A[5, 3] = 0.17082860872947386
_A[5, 4] = 0.12546768756682242
_A[6, 0] = 0.037109375
_A[6, 3] = 0.17025221101954405
_A[6, 4] = 0.06021653898045596
_A[6, 5] = -0.017578125
_A[7, 0] = 0.03709200011850479
_A[7, 3] = 0.17038392571223998
_A[7, 4] = 0.10726203044637328
_A[7, 5] = -0.015319437748624402
_A[7, 6] = 0.008273789163814023
_A[8, 0] = 0.6241109587160757
_A[8, 3] = -3.3608926294469414
_A[8, 4] = -0.868219346841726
_A[8, 5] = 27.59209969944671
_A[8, 6] = 20.154067550477894
_A[8, 7] = -43.48988418106996
_A[9, 0] = 0.47766253643826434
_A[9, 3] = -2.4881146199716677
_A[9, 4] = -0.590290826836843
_A[9, 5] = 21.230051448181193
_A[9, 6] = 15.279233632882423
_A[9, 7] = -33.28821096898486
_A[9, 8] = -0.020331201708508627
_A[10, 0] = -0.9371424300859873
_A[10, 3] = 5.186372428844064
_A[10, 4] = 1.0914373489967295
_A[10, 5] = -8.149787010746927
_A[10, 6] = -18.52006565999696
_A[10, 7] = 22.739487099350505
_A[10, 8] = 2.4936055526796523
_A[10, 9] = -3.0467644718982196
_A[11, 0] = 2.273310147516538
_A[11, 3] = -10.53449546673725
_A[11, 4] = -2.0008720582248625
_A[11, 5] = -17.9589318631188
_A[11, 6] = 27.94888452941996
_A[11, 7] = -2.8589982771350235
_A[11, 8] = -8.87285693353063
_A[11, 9] = 12.360567175794303
_A[11, 10] = 0.6433927460157636

# DOP853's continuous extension of order 7 (Hairer's contd8; SciPy's dop853_coefficients.py):
# stage 13 is z' at the step's end (the A row is _B), stages 14-16 the three extra ones
_C_EXTRA = np.array([0.1, 0.2, 0.7777777777777778])
_A_EXTRA = np.zeros((3, 16))
_A_EXTRA[0, 0] = 0.056167502283047954
_A_EXTRA[0, 6] = 0.25350021021662483
_A_EXTRA[0, 7] = -0.2462390374708025
_A_EXTRA[0, 8] = -0.12419142326381637
_A_EXTRA[0, 9] = 0.15329179827876568
_A_EXTRA[0, 10] = 0.00820105229563469
_A_EXTRA[0, 11] = 0.007567897660545699
_A_EXTRA[0, 12] = -0.008298
_A_EXTRA[1, 0] = 0.03183464816350214
_A_EXTRA[1, 5] = 0.028300909672366776
_A_EXTRA[1, 6] = 0.053541988307438566
_A_EXTRA[1, 7] = -0.05492374857139099
_A_EXTRA[1, 10] = -0.00010834732869724932
_A_EXTRA[1, 11] = 0.0003825710908356584
_A_EXTRA[1, 12] = -0.00034046500868740456
_A_EXTRA[1, 13] = 0.1413124436746325
_A_EXTRA[2, 0] = -0.42889630158379194
_A_EXTRA[2, 5] = -4.697621415361164
_A_EXTRA[2, 6] = 7.683421196062599
_A_EXTRA[2, 7] = 4.06898981839711
_A_EXTRA[2, 8] = 0.3567271874552811
_A_EXTRA[2, 12] = -0.0013990241651590145
_A_EXTRA[2, 13] = 2.9475147891527724
_A_EXTRA[2, 14] = -9.15095847217987
_D = np.zeros((4, 16))
_D[0, 0] = -8.428938276109013
_D[0, 5] = 0.5667149535193777
_D[0, 6] = -3.0689499459498917
_D[0, 7] = 2.38466765651207
_D[0, 8] = 2.117034582445028
_D[0, 9] = -0.871391583777973
_D[0, 10] = 2.2404374302607883
_D[0, 11] = 0.6315787787694688
_D[0, 12] = -0.08899033645133331
_D[0, 13] = 18.148505520854727
_D[0, 14] = -9.194632392478356
_D[0, 15] = -4.436036387594894
_D[1, 0] = 10.427508642579134
_D[1, 5] = 242.28349177525817
_D[1, 6] = 165.20045171727028
_D[1, 7] = -374.5467547226902
_D[1, 8] = -22.113666853125306
_D[1, 9] = 7.733432668472264
_D[1, 10] = -30.674084731089398
_D[1, 11] = -9.332130526430229
_D[1, 12] = 15.697238121770845
_D[1, 13] = -31.139403219565178
_D[1, 14] = -9.35292435884448
_D[1, 15] = 35.81684148639408
_D[2, 0] = 19.985053242002433
_D[2, 5] = -387.0373087493518
_D[2, 6] = -189.17813819516758
_D[2, 7] = 527.8081592054236
_D[2, 8] = -11.57390253995963
_D[2, 9] = 6.8812326946963
_D[2, 10] = -1.0006050966910838
_D[2, 11] = 0.7777137798053443
_D[2, 12] = -2.778205752353508
_D[2, 13] = -60.19669523126412
_D[2, 14] = 84.32040550667716
_D[2, 15] = 11.99229113618279
_D[3, 0] = -25.69393346270375
_D[3, 5] = -154.18974869023643
_D[3, 6] = -231.5293791760455
_D[3, 7] = 357.6391179106141
_D[3, 8] = 93.40532418362432
_D[3, 9] = -37.45832313645163
_D[3, 10] = 104.0996495089623
_D[3, 11] = 29.8402934266605
_D[3, 12] = -43.53345659001114
_D[3, 13] = 96.32455395918828
_D[3, 14] = -39.17726167561544
_D[3, 15] = -149.72683625798564

#: Components of the integrated state.
N_STATE = 6

#: Event-function kinds for :func:`locate`; KIND_RATE + j (j = 0..4): the rate of the
#: slip (j = 0) or of a corner's X (j = 1..4, :func:`horizontal_rate`), for their extrema.
KIND_TERMINAL, KIND_PEAK, KIND_ALPHA, KIND_RATE = 0.0, 1.0, 2.0, 3.0
N_RATES = 5

#: Terminal events of the contact modes (indices of :func:`events`).
E_IMPACT, E_NORMAL, E_FRICTION, E_OVERTURN, E_MASS = 0, 1, 2, 3, 4
N_EVENTS = 5


@njit(**HELPER)
def ground(segment, time):
    """Horizontal and vertical table acceleration [m/s^2] at ``time`` (linear in the interval).

    ``segment``: start [s], length [s], ug at the start [m/s^2] and its change, vg and its
    change, then (for :func:`slopes_ground`) the slopes of ug and vg [m/s^3]."""
    fraction = (time - segment[0]) / segment[1]
    return segment[2] + segment[3] * fraction, segment[4] + segment[5] * fraction


@njit(**HELPER)
def slopes_ground(segment, time):
    """:func:`ground` from the slopes ``segment[6:8]`` [m/s^3] (no division: the
    right-hand side's; the rest and start rules keep :func:`ground`, the rocking engine's)."""
    elapsed = time - segment[0]
    return segment[2] + segment[6] * elapsed, segment[4] + segment[7] * elapsed


@njit(**HELPER)
def rhs(mode, side, sigma, mu_d, t, z, segment, parameters, out):
    """z' of ROCK or SLIDE_ROCK into ``out``."""
    ug, vg = slopes_ground(segment, t)
    theta = z[0]
    omega = z[1]
    velocity = z[3]
    r_x, r_y = corner_vector(theta, side, parameters)
    friction_power = 0.0
    if mode == ROCK:
        acceleration = pivot_acceleration(theta, side, ug, vg, parameters)
        corner_dd = 0.0
    else:
        acceleration, corner_dd, friction, _, _ = slide_rock_accelerations(
            theta, omega, side, sigma, mu_d, ug, vg, parameters)
        friction_power = friction * velocity
    x_dot = velocity + r_y * omega
    y_dot = -r_x * omega
    out[0] = omega
    out[1] = acceleration
    out[2] = velocity
    out[3] = corner_dd
    out[4] = -ug * x_dot - vg * y_dot
    out[5] = friction_power


@njit(**HELPER)
def dop853_step(mode, side, sigma, mu_d, t, z, k1, h, segment, parameters, stages, z_new,
                scale_abs, rtol):
    """One DOP853 step of size ``h`` from (t, z) with z'(t) = ``k1``; z(t + h) into ``z_new``.

    Returns the error norm (<= 1: accepted) of Hairer's DOP853 estimator on the
    mixed absolute (``scale_abs``) / relative (``rtol``) scale. ``stages`` (16 rows)
    receives the 12 stages; its row 15 is the work array (the continuous extension,
    :func:`dense_output`, fills rows 12-15 after the step).
    """
    work = stages[15]   # free during a step (the continuous extension's last stage)
    for i in range(N_STATE):
        stages[0, i] = k1[i]
    for s in range(1, 12):
        for i in range(N_STATE):
            total = 0.0
            for j in range(s):
                total += _A[s, j] * stages[j, i]
            work[i] = z[i] + h * total
        row = stages[s]
        rhs(mode, side, sigma, mu_d, t + _C[s] * h, work, segment, parameters, row)
    err5 = 0.0
    err3 = 0.0
    for i in range(N_STATE):
        total = 0.0
        e5 = 0.0
        e3 = 0.0
        for s in range(12):
            total += _B[s] * stages[s, i]
            e5 += _E5[s] * stages[s, i]
            e3 += _E3[s] * stages[s, i]
        z_new[i] = z[i] + h * total
        scale = scale_abs[i] + rtol * max(abs(z[i]), abs(z_new[i]))
        err5 += (e5 / scale) ** 2
        err3 += (e3 / scale) ** 2
    if err5 == 0.0 and err3 == 0.0:
        return 0.0
    return abs(h) * err5 / math.sqrt((err5 + 0.01 * err3) * N_STATE)


@njit(**HELPER)
def events(mode, side, sigma, mu_s, mu_d, t, z, segment, parameters, out):
    """The terminal event functions of ROCK / SLIDE_ROCK at (t, z) into ``out``; each is
    positive while the mode holds: side theta (impact), N (lift-off), the friction margin
    mu_s N - |F| (ROCK) or the slip speed sigma X_s' (SLIDE_ROCK), pi/2 - side theta
    (overturn), the effective mass D (SLIDE_ROCK; Painleve)."""
    ug, vg = ground(segment, t)
    theta = z[0]
    omega = z[1]
    out[E_IMPACT] = side * theta
    out[E_OVERTURN] = 0.5 * math.pi - side * theta
    if mode == ROCK:
        _, _, _, friction, normal = rock_forces(theta, omega, side, ug, vg, parameters)
        out[E_NORMAL] = normal
        out[E_FRICTION] = min(mu_s * normal - friction, mu_s * normal + friction)
        out[E_MASS] = 1.0
    else:
        _, _, _, normal, d = slide_rock_accelerations(theta, omega, side, sigma, mu_d, ug, vg,
                                                      parameters)
        out[E_NORMAL] = normal if d > 0.0 else 0.0
        out[E_FRICTION] = sigma * z[3]
        out[E_MASS] = d


@njit(**HELPER)
def event_value(kind, mode, side, sigma, mu_s, mu_d, t, z, segment, parameters, armed, sign,
                values):
    """The event function of ``kind`` at (t, z): positive before the event, <= 0 at and after.

    KIND_TERMINAL: the least of the armed terminal events (the first to fire);
    KIND_PEAK: sign * theta' (a turning point); KIND_ALPHA: alpha - |theta|.
    """
    if kind == KIND_PEAK:
        return sign * z[1]
    if kind == KIND_ALPHA:
        return block_angle(side, parameters) - abs(z[0])
    if kind >= KIND_RATE:
        _, r_y = corner_vector(z[0], side, parameters)
        return sign * horizontal_rate(int(kind - KIND_RATE), z[0], z[3] + r_y * z[1], z[1],
                                      parameters)
    events(mode, side, sigma, mu_s, mu_d, t, z, segment, parameters, values)
    least = math.inf
    for i in range(N_EVENTS):
        if armed[i] and values[i] < least:
            least = values[i]
    return least


@njit(**HELPER)
def dense_output(mode, side, sigma, mu_d, t, z, z_end, h, segment, parameters, stages, dense):
    """DOP853's continuous extension of order 7 on the accepted step (t, z) -> (t + h,
    ``z_end``) into ``dense`` (7, N_STATE), for :func:`dense_state`.

    ``stages`` (16 rows) holds the step's 12 stages (:func:`dop853_step`); the
    extension adds z'(t + h) and three more stages (Hairer, Norsett & Wanner, Sec. II.6,
    their code's contd8). Returns the right-hand-side evaluations made (4).
    """
    work = np.empty(N_STATE)
    rhs(mode, side, sigma, mu_d, t + h, z_end, segment, parameters, stages[12])
    for s in range(13, 16):
        for i in range(N_STATE):
            total = 0.0
            for j in range(s):
                total += _A_EXTRA[s - 13, j] * stages[j, i]
            work[i] = z[i] + h * total
        rhs(mode, side, sigma, mu_d, t + _C_EXTRA[s - 13] * h, work, segment, parameters,
            stages[s])
    for i in range(N_STATE):
        delta = z_end[i] - z[i]
        dense[0, i] = delta
        dense[1, i] = h * stages[0, i] - delta
        dense[2, i] = 2.0 * delta - h * (stages[12, i] + stages[0, i])
        for row in range(4):
            total = 0.0
            for s in range(16):
                total += _D[row, s] * stages[s, i]
            dense[3 + row, i] = h * total
    return 4


@njit(**HELPER)
def dense_state(dense, z, fraction, out):
    """The state at ``fraction`` (0..1) of the step from z on the continuous extension."""
    for i in range(N_STATE):
        value = 0.0
        for row in range(6, -1, -1):
            value += dense[row, i]
            value *= fraction if row % 2 == 0 else 1.0 - fraction
        out[i] = z[i] + value


@njit(**HELPER)
def locate(kind, mode, side, sigma, mu_s, mu_d, t, z, step, z_step, stages, dense, ready,
           upper, z_upper, armed, sign, segment, parameters, z_out):
    """First zero of an event function on (0, upper] of the accepted step (t, z) ->
    (t + ``step``, ``z_step``), on the step's continuous extension of order 7.

    The extension is built on the first call for the step (``ready[0]`` False; ``z_step``
    is read before ``z_out`` is written, so they may be the same array). The function is
    taken as positive at tau = 0 (an event armed at the step start, or one zero there by
    construction, e.g. theta = 0 when rocking begins) and is <= 0 at ``upper`` (state
    ``z_upper``). Trials on the extension: Newton's step where the impact event decides
    (its rate is side theta'), else Illinois regula falsi, and bisection when two trials
    did not halve the bracket, until the bracket is a few ulps of t wide. The state at
    the right end of the bracket (the event has happened) goes into ``z_out``.

    Returns tau and the right-hand-side evaluations made (4 if the extension was built).
    """
    evaluations = 0
    if not ready[0]:
        evaluations = dense_output(mode, side, sigma, mu_d, t, z, z_step, step, segment,
                                   parameters, stages, dense)
        ready[0] = True
    values = np.empty(N_EVENTS)
    trial = np.empty(N_STATE)
    for i in range(N_STATE):
        z_out[i] = z_upper[i]
    a = 0.0
    b = upper
    gb = event_value(kind, mode, side, sigma, mu_s, mu_d, t + upper, z_upper, segment,
                     parameters, armed, sign, values)
    ga = event_value(kind, mode, side, sigma, mu_s, mu_d, t, z, segment, parameters, armed,
                     sign, values)
    known = ga > 0.0
    tolerance = 4e-16 * (abs(t) + upper) + 1e-300
    kept = 0
    # Newton on the impact event (its rate side * theta' is known) from the last trial,
    # else Illinois regula falsi; bisection whenever two trials did not halve the bracket
    newton = math.nan
    if kind == KIND_TERMINAL and gb == side * z_upper[0] and z_upper[1] != 0.0:
        newton = upper - gb / (side * z_upper[1])
    width_before = math.inf
    width_last = math.inf
    for _ in range(300):
        if b - a <= tolerance or gb == 0.0:
            break
        candidate = math.nan
        if newton == newton and a < newton < b:
            candidate = newton
        elif known and ga != gb:
            candidate = b - gb * (b - a) / (gb - ga)
        if not (a < candidate < b) or (b - a) > 0.5 * width_before:
            candidate = 0.5 * (a + b)
        width_before = width_last
        width_last = b - a
        dense_state(dense, z, candidate / step, trial)
        g = event_value(kind, mode, side, sigma, mu_s, mu_d, t + candidate, trial, segment,
                        parameters, armed, sign, values)
        newton = math.nan
        if kind == KIND_TERMINAL and g == side * trial[0] and trial[1] != 0.0:
            newton = candidate - g / (side * trial[1])
        if g > 0.0:
            a = candidate
            ga = g
            known = True
            if kept == 1:
                gb *= 0.5
            kept = 1
        else:
            b = candidate
            gb = g
            for i in range(N_STATE):
                z_out[i] = trial[i]
            if kept == -1:
                ga *= 0.5
            kept = -1
    return b, evaluations


@njit(**HELPER)
def terminal_event(mode, side, sigma, mu_s, mu_d, t, z, step, z_new, stages, dense, ready,
                   segment, parameters, armed, g_end, z_event, z_turn, no_events):
    """The first of the ``armed`` terminal events in the accepted contact step (t, z) ->
    (t + ``step``, ``z_new``), or an impact passed inside it (theta turned back away from 0
    on the far side of 0), located by :func:`locate`.

    Returns (the event's index, -1 if none; tau [s]; right-hand-side evaluations made). On
    an event, ``z_new`` becomes the state at t + tau; ``g_end`` holds the event functions
    at t + tau; ``z_event`` and ``z_turn`` are work arrays, ``no_events`` all False.
    """
    evaluations = 0
    events(mode, side, sigma, mu_s, mu_d, t + step, z_new, segment, parameters,
           g_end)
    tau = step
    upper = step
    for i in range(N_STATE):
        z_event[i] = z_new[i]
    fire = False
    for i in range(N_EVENTS):
        if armed[i] and g_end[i] <= 0.0:
            fire = True
    if not fire and side * z[1] < 0.0 and side * z_new[1] > 0.0:
        # theta turned back away from 0 inside the step: did it pass 0?
        tau_turn, used = locate(KIND_PEAK, mode, side, sigma, mu_s, mu_d, t, z,
                                step, z_new, stages, dense, ready, step, z_new,
                                no_events, -side, segment, parameters, z_turn)
        evaluations += used
        if side * z_turn[0] <= 0.0:
            fire = True
            upper = tau_turn
            for i in range(N_STATE):
                z_event[i] = z_turn[i]
    terminal = -1
    if fire:
        armed[E_IMPACT] = True
        tau, used = locate(KIND_TERMINAL, mode, side, sigma, mu_s, mu_d, t, z,
                           step, z_new, stages, dense, ready, upper, z_event,
                           armed, 0.0, segment, parameters, z_new)
        evaluations += used
        events(mode, side, sigma, mu_s, mu_d, t + tau, z_new, segment,
               parameters, g_end)
        least = math.inf
        for i in range(N_EVENTS):
            if armed[i] and g_end[i] < least:
                least = g_end[i]
                terminal = i
    return terminal, tau, evaluations


@njit(**HELPER)
def polynomial_work(p0, p1, q0, q1, q2, span):
    """Integral over [0, span] of (p0 + p1 tau)(q0 + q1 tau + q2 tau^2)."""
    return (p0 * q0 * span + (p0 * q1 + p1 * q0) * span ** 2 / 2.0
            + (p0 * q2 + p1 * q1) * span ** 3 / 3.0 + p1 * q2 * span ** 4 / 4.0)


@njit(**HELPER)
def flight_state(tau, x, y, theta, x_dot, y_dot, omega, ua, ka, va, kv):
    """Ballistic state after ``tau`` [s] (x'' = -ug, y'' = -(g + vg), theta'' = 0, the table
    accelerations ua + ka tau, va + kv tau)."""
    gravity = G + va
    return (x + x_dot * tau - ua * tau * tau / 2.0 - ka * tau ** 3 / 6.0,
            y + y_dot * tau - gravity * tau * tau / 2.0 - kv * tau ** 3 / 6.0,
            theta + omega * tau,
            x_dot - ua * tau - ka * tau * tau / 2.0,
            y_dot - gravity * tau - kv * tau * tau / 2.0,
            omega)


@njit(**HELPER)
def lowest_corner(y, theta, parameters):
    """Height of the lower bottom corner [m] and its side."""
    h = parameters[HALF_HEIGHT]
    sine = math.sin(theta)
    cosine = math.cos(theta)
    plus = y - parameters[HALF_WIDTH] * sine - h * cosine
    minus = y + parameters[HALF_WIDTH_MINUS] * sine - h * cosine
    if plus <= minus:
        return plus, 1.0
    return minus, -1.0


@njit(**HELPER)
def horizontal_rate(which, theta, x_dot, omega, parameters):
    """d/dt of the slip of the base's midpoint (``which`` 0) or of the X of a corner
    (1..4: body points (-b, -h), (b, -h), (-b, h), (b, h)) [m/s]: zero at their extrema."""
    return horizontal_rate_at(which, math.cos(theta), math.sin(theta), x_dot, omega,
                              parameters)


@njit(**HELPER)
def horizontal_rate_at(which, cosine, sine, x_dot, omega, parameters):
    """:func:`horizontal_rate` with cos(theta) and sin(theta) given."""
    h = parameters[HALF_HEIGHT]
    if which == 0:
        return x_dot + h * cosine * omega
    u = -parameters[HALF_WIDTH] if which == 1 or which == 3 else parameters[HALF_WIDTH_MINUS]
    w = -h if which <= 2 else h
    return x_dot - omega * (u * sine + w * cosine)


@njit(**HELPER)
def zeros(n):
    """A float array of n zeros (np.empty: compiled once for all the engine's arrays)."""
    array = np.empty(n)
    for i in range(n):
        array[i] = 0.0
    return array


@njit(**HELPER)
def falses(n):
    """A bool array of n False."""
    array = np.empty(n, dtype=np.bool_)
    for i in range(n):
        array[i] = False
    return array
