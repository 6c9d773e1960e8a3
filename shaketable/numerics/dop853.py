"""DOP853, the explicit Runge-Kutta pair of order 8 of Dormand & Prince, for compiled engines.

What every event-driven engine of the package integrates its smooth phases with: the
tableau (Hairer, Norsett & Wanner, Solving ODEs I, Sec. II.10; the numbers of SciPy's
``scipy/integrate/_ivp/dop853_coefficients.py``), one step with Hairer's error estimate
(estimators of orders 5 and 3), SciPy's step-size control constants and initial step, and
the continuous extension of order 7 (Hairer's contd8: three more stages) with its
evaluation, on which events are located (:mod:`shaketable.numerics.roots`).

The functions are written once for any right-hand side: a model passes its own as a
compiled function ``rhs(t, y, out, args)`` (z' at (t, y) into ``out``; ``args`` a tuple of
the model's data) and numba compiles the step for it. They are inlined into their caller
by numba (``inline="always"``, as the model's right-hand side should be): a model's
wrapper compiles the same machine code as one written for it alone, with no call between
the step and the right-hand side. None allocates (the work arrays are the caller's), so
that they run in functions compiled without numba's reference counting (``_nrt=False``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit

#: numba options of the shared functions: inlined into the caller before typing.
INLINE: Any = {"inline": "always", "error_model": "numpy"}

# DOP853 tableau (Hairer, Norsett & Wanner; the numbers of SciPy's dop853_coefficients.py)
C = np.array([
    0.0, 0.05260015195876773, 0.0789002279381516, 0.1183503419072274,
    0.2816496580927726, 0.3333333333333333, 0.25, 0.3076923076923077,
    0.6512820512820513, 0.6, 0.8571428571428571, 1.0])
B = np.array([
    0.054293734116568765, 0.0, 0.0, 0.0, 0.0, 4.450312892752409,
    1.8915178993145003, -5.801203960010585, 0.3111643669578199,
    -0.1521609496625161, 0.20136540080403034, 0.04471061572777259])
E3 = np.array([
    -0.18980075407240762, 0.0, 0.0, 0.0, 0.0, 4.450312892752409,
    1.8915178993145003, -5.801203960010585, -0.4226823213237919,
    -0.1521609496625161, 0.20136540080403034, 0.02265179219836082])
E5 = np.array([
    0.01312004499419488, 0.0, 0.0, 0.0, 0.0, -1.2251564463762044,
    -0.4957589496572502, 1.6643771824549864, -0.35032884874997366,
    0.3341791187130175, 0.08192320648511571, -0.022355307863886294])
A = np.zeros((12, 12))
A[1, 0] = 0.05260015195876773
A[2, 0] = 0.0197250569845379
A[2, 1] = 0.0591751709536137
A[3, 0] = 0.02958758547680685
A[3, 2] = 0.08876275643042054
A[4, 0] = 0.2413651341592667
A[4, 2] = -0.8845494793282861
A[4, 3] = 0.924834003261792
A[5, 0] = 0.037037037037037035
A[5, 3] = 0.17082860872947386
A[5, 4] = 0.12546768756682242
A[6, 0] = 0.037109375
A[6, 3] = 0.17025221101954405
A[6, 4] = 0.06021653898045596
A[6, 5] = -0.017578125
A[7, 0] = 0.03709200011850479
A[7, 3] = 0.17038392571223998
A[7, 4] = 0.10726203044637328
A[7, 5] = -0.015319437748624402
A[7, 6] = 0.008273789163814023
A[8, 0] = 0.6241109587160757
A[8, 3] = -3.3608926294469414
A[8, 4] = -0.868219346841726
A[8, 5] = 27.59209969944671
A[8, 6] = 20.154067550477894
A[8, 7] = -43.48988418106996
A[9, 0] = 0.47766253643826434
A[9, 3] = -2.4881146199716677
A[9, 4] = -0.590290826836843
A[9, 5] = 21.230051448181193
A[9, 6] = 15.279233632882423
A[9, 7] = -33.28821096898486
A[9, 8] = -0.020331201708508627
A[10, 0] = -0.9371424300859873
A[10, 3] = 5.186372428844064
A[10, 4] = 1.0914373489967295
A[10, 5] = -8.149787010746927
A[10, 6] = -18.52006565999696
A[10, 7] = 22.739487099350505
A[10, 8] = 2.4936055526796523
A[10, 9] = -3.0467644718982196
A[11, 0] = 2.273310147516538
A[11, 3] = -10.53449546673725
A[11, 4] = -2.0008720582248625
A[11, 5] = -17.9589318631188
A[11, 6] = 27.94888452941996
A[11, 7] = -2.8589982771350235
A[11, 8] = -8.87285693353063
A[11, 9] = 12.360567175794303
A[11, 10] = 0.6433927460157636

# DOP853's continuous extension of order 7 (Hairer's contd8; SciPy's dop853_coefficients.py):
# stage 13 is y' at the step's end (its A row is B), stages 14-16 the three extra ones
C_EXTRA = np.array([0.1, 0.2, 0.7777777777777778])
A_EXTRA = np.zeros((3, 16))
A_EXTRA[0, 0] = 0.056167502283047954
A_EXTRA[0, 6] = 0.25350021021662483
A_EXTRA[0, 7] = -0.2462390374708025
A_EXTRA[0, 8] = -0.12419142326381637
A_EXTRA[0, 9] = 0.15329179827876568
A_EXTRA[0, 10] = 0.00820105229563469
A_EXTRA[0, 11] = 0.007567897660545699
A_EXTRA[0, 12] = -0.008298
A_EXTRA[1, 0] = 0.03183464816350214
A_EXTRA[1, 5] = 0.028300909672366776
A_EXTRA[1, 6] = 0.053541988307438566
A_EXTRA[1, 7] = -0.05492374857139099
A_EXTRA[1, 10] = -0.00010834732869724932
A_EXTRA[1, 11] = 0.0003825710908356584
A_EXTRA[1, 12] = -0.00034046500868740456
A_EXTRA[1, 13] = 0.1413124436746325
A_EXTRA[2, 0] = -0.42889630158379194
A_EXTRA[2, 5] = -4.697621415361164
A_EXTRA[2, 6] = 7.683421196062599
A_EXTRA[2, 7] = 4.06898981839711
A_EXTRA[2, 8] = 0.3567271874552811
A_EXTRA[2, 12] = -0.0013990241651590145
A_EXTRA[2, 13] = 2.9475147891527724
A_EXTRA[2, 14] = -9.15095847217987
D = np.zeros((4, 16))
D[0, 0] = -8.428938276109013
D[0, 5] = 0.5667149535193777
D[0, 6] = -3.0689499459498917
D[0, 7] = 2.38466765651207
D[0, 8] = 2.117034582445028
D[0, 9] = -0.871391583777973
D[0, 10] = 2.2404374302607883
D[0, 11] = 0.6315787787694688
D[0, 12] = -0.08899033645133331
D[0, 13] = 18.148505520854727
D[0, 14] = -9.194632392478356
D[0, 15] = -4.436036387594894
D[1, 0] = 10.427508642579134
D[1, 5] = 242.28349177525817
D[1, 6] = 165.20045171727028
D[1, 7] = -374.5467547226902
D[1, 8] = -22.113666853125306
D[1, 9] = 7.733432668472264
D[1, 10] = -30.674084731089398
D[1, 11] = -9.332130526430229
D[1, 12] = 15.697238121770845
D[1, 13] = -31.139403219565178
D[1, 14] = -9.35292435884448
D[1, 15] = 35.81684148639408
D[2, 0] = 19.985053242002433
D[2, 5] = -387.0373087493518
D[2, 6] = -189.17813819516758
D[2, 7] = 527.8081592054236
D[2, 8] = -11.57390253995963
D[2, 9] = 6.8812326946963
D[2, 10] = -1.0006050966910838
D[2, 11] = 0.7777137798053443
D[2, 12] = -2.778205752353508
D[2, 13] = -60.19669523126412
D[2, 14] = 84.32040550667716
D[2, 15] = 11.99229113618279
D[3, 0] = -25.69393346270375
D[3, 5] = -154.18974869023643
D[3, 6] = -231.5293791760455
D[3, 7] = 357.6391179106141
D[3, 8] = 93.40532418362432
D[3, 9] = -37.45832313645163
D[3, 10] = 104.0996495089623
D[3, 11] = 29.8402934266605
D[3, 12] = -43.53345659001114
D[3, 13] = 96.32455395918828
D[3, 14] = -39.17726167561544
D[3, 15] = -149.72683625798564


#: Stages of a step (the 13th, f at the step's end, and three more build the extension).
N_STAGES = 12
#: Rows of the stage array a step and its extension need.
N_STAGES_EXTENDED = 16
#: Rows of the continuous extension's coefficients (:func:`dense_output`).
N_DENSE = 7
#: SciPy's step-size control of its Runge-Kutta methods: a new step is the old one times
#: SAFETY error^ERROR_EXPONENT, kept within [MIN_FACTOR, MAX_FACTOR] (the exponent
#: -1/(order of the error estimator + 1), order 7 here).
SAFETY, MIN_FACTOR, MAX_FACTOR, ERROR_EXPONENT = 0.9, 0.2, 10.0, -1.0 / 8.0
#: The machine epsilon of float64.
EPS = float(np.finfo(float).eps)


@njit(**INLINE)
def step(rhs, args, t, y, h, stages, y_new, work, atol, rtol):
    """One DOP853 step of size ``h`` [s] from (t, y): y(t + h) into ``y_new``.

    Parameters
    ----------
    rhs : numba function
        ``rhs(t, y, out, args)``: y' at (t, y) into ``out``.
    args : tuple
        The model's data, handed to ``rhs``.
    t, h : float
        Start and size of the step [s].
    y : ndarray
        State at t.
    stages : ndarray, shape (>= 12, y.size)
        Row 0: y'(t) (given); rows 1-11 receive the step's other stages.
    y_new : ndarray
        Receives the state at t + h.
    work : ndarray
        A work array of y.size (not a row of ``stages`` 0-11).
    atol : ndarray
        Absolute tolerances, one per component.
    rtol : float
        Relative tolerance [-].

    Returns
    -------
    float
        Hairer's error norm of the step on the scale atol + rtol max(|y|, |y_new|)
        (accepted when <= 1); 0 when both estimators vanish.
    """
    size = y.size
    for s in range(1, N_STAGES):
        for i in range(size):
            total = 0.0
            for j in range(s):
                total += A[s, j] * stages[j, i]
            work[i] = y[i] + h * total
        rhs(t + C[s] * h, work, stages[s], args)
    err5 = 0.0
    err3 = 0.0
    for i in range(size):
        total = 0.0
        e5 = 0.0
        e3 = 0.0
        for s in range(N_STAGES):
            total += B[s] * stages[s, i]
            e5 += E5[s] * stages[s, i]
            e3 += E3[s] * stages[s, i]
        y_new[i] = y[i] + h * total
        scale = atol[i] + rtol * max(abs(y[i]), abs(y_new[i]))
        err5 += (e5 / scale) ** 2
        err3 += (e3 / scale) ** 2
    if err5 == 0.0 and err3 == 0.0:
        return 0.0
    return abs(h) * err5 / math.sqrt((err5 + 0.01 * err3) * size)


@njit(**INLINE)
def initial_step(rhs, args, t0, y0, f0, t_bound, atol, rtol, work, f1):
    """SciPy's first step size [s] for DOP853 (``select_initial_step``, error estimator of
    order 7; Hairer, Norsett & Wanner, Sec. II.4): from y0 and f0 = y'(t0) and one more
    evaluation of ``rhs`` (into ``f1``; ``work`` a work array), at most ``t_bound - t0``."""
    size = y0.size
    length = abs(t_bound - t0)
    if length == 0.0:
        return 0.0
    d0, d1 = 0.0, 0.0
    for i in range(size):
        scale = atol[i] + abs(y0[i]) * rtol
        d0 += (y0[i] / scale) ** 2
        d1 += (f0[i] / scale) ** 2
    d0, d1 = math.sqrt(d0 / size), math.sqrt(d1 / size)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, length)
    for i in range(size):
        work[i] = y0[i] + h0 * f0[i]
    rhs(t0 + h0, work, f1, args)
    d2 = 0.0
    for i in range(size):
        scale = atol[i] + abs(y0[i]) * rtol
        d2 += ((f1[i] - f0[i]) / scale) ** 2
    d2 = math.sqrt(d2 / size) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    return min(100.0 * h0, h1, length)


@njit(**INLINE)
def dense_output(rhs, args, t, y_old, y, h, stages, dense, work):
    """DOP853's continuous extension of order 7 of the step (t, ``y_old``) -> (t + h, y)
    into ``dense`` (7 rows, for :func:`dense_state`; Hairer's contd8).

    ``stages`` (16 rows) holds the step's 12 stages and, in row 12, y'(t + h); rows 13-15
    receive the three extra stages (three evaluations of ``rhs``). ``work``: a work array
    of y.size, not a row of ``stages``.
    """
    size = y.size
    for s in range(N_STAGES + 1, N_STAGES_EXTENDED):
        for i in range(size):
            total = 0.0
            for j in range(s):
                total += A_EXTRA[s - 13, j] * stages[j, i]
            work[i] = y_old[i] + h * total
        rhs(t + C_EXTRA[s - 13] * h, work, stages[s], args)
    for i in range(size):
        delta = y[i] - y_old[i]
        dense[0, i] = delta
        dense[1, i] = h * stages[0, i] - delta
        dense[2, i] = 2.0 * delta - h * (stages[12, i] + stages[0, i])
        for row in range(4):
            total = 0.0
            for s in range(N_STAGES_EXTENDED):
                total += D[row, s] * stages[s, i]
            dense[3 + row, i] = h * total


@njit(**INLINE)
def dense_state(dense, y_old, fraction, out):
    """The state at ``fraction`` (0..1) of the step from ``y_old`` on its continuous
    extension ``dense`` (:func:`dense_output`) into ``out``."""
    for i in range(y_old.size):
        value = 0.0
        for row in range(6, -1, -1):
            value += dense[row, i]
            value *= fraction if row % 2 == 0 else 1.0 - fraction
        out[i] = y_old[i] + value
