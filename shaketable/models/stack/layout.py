"""The compiled stack engine's run state: the slots of its float, int and parameter arrays.

:mod:`shaketable.models.stack.compiled` keeps a run's state in a tuple ``run`` = (phi, phi',
pattern, fs, ist, par, atol, the event arrays); ``fs`` (floats), ``ist`` (int64) and ``par``
(the run's parameters) are indexed by these names.
"""

import numpy as np

#: What ends a segment of one pattern: nothing (the interval's end), a landing, an overturn,
#: a corner force reaching zero. int64 values, not Python ints: numba types a module's int
#: constants as literals and compiles a function once for every distinct literal.
ENDS_NONE, ENDS_IMPACT, ENDS_OVERTURN, ENDS_LIFT = (np.int64(code) for code in range(-1, 3))
#: No interface; the int64 zero.
NONE, ZERO = np.int64(-1), np.int64(0)

# slots of the run's float state ``fs``: the table's work [J], rest until [s], overturn and
# airborne times [s], the time of an error [s], the one-DOF stepper's step size [s], its
# controller's memory (the last accepted error) [-], the time of the last impact [s] and the
# step size of DOP853 (multi-DOF patterns) carried from one segment to the next [s], the
# energy of the stack at rest [J] (NaN until needed), the last sample's phi'' of a one-DOF
# pattern [rad/s^2], and the rocking body's energy [J] where the last one-DOF segment ended,
# with its phi [rad], phi' [rad/s] and pattern (2 j + s); a stack of one block: the
# stepper's theta'' [rad/s^2] where its last segment reached the end of an input interval
# (NaN after an event), carried into the next interval as the single-block engine carries it
F_WORK, F_REST_UNTIL, F_T_OVERTURN, F_T_AIRBORNE, F_ERROR_TIME, F_STEP, F_PREVIOUS_ERROR, \
    F_LAST_IMPACT, F_DOP_STEP, F_REST_ENERGY, F_SAMPLE_ACCELERATION, F_ENERGY, \
    F_ENERGY_THETA, F_ENERGY_OMEGA, F_ENERGY_SIDE, F_ONE_ACCELERATION = range(16)
N_FLOATS = 16
# slots of the int state ``ist``: events counted and recorded, events in a row without
# progress, status, the overturned block, steps, evaluations, the error, the pattern whose
# closed forms are current (interface, side), whether the last sample's one-DOF state (its
# phi'' in F_SAMPLE_ACCELERATION, its forces in the closed forms' workspace) is the state
# the next input interval starts from (1) or not (0), the events counted when the current
# input interval began
I_EVENTS, I_RECORDED, I_STALLED, I_STATUS, I_OVERTURNED, I_STEPS, I_EVALUATIONS, I_ERROR, \
    I_RIGID_J, I_RIGID_S, I_SAMPLED, I_INTERVAL_EVENTS = range(12)
N_INTS = 12
# slots of the parameters ``par``: the pattern check's look-ahead [s], the force tolerance
# [N], the angle and rate scales [rad, rad/s], rtol, the rest tolerance [s], the COR, the
# law (0 plastic, 1 COR); a stack of one block: Housner's ratio 1 - 1.5 sin^2(alpha) as the
# single-block engine is given it [-], then from P_BLOCK the block's parameters as that
# engine packs them (shaketable.models.rocking.physics.block_parameters, N_BLOCK of them)
P_DELTA, P_TOL_FORCE, P_ALPHA, P_ALPHA_P, P_RTOL, P_REST, P_COR, P_LAW, P_HOUSNER, \
    P_BLOCK = range(10)
N_BLOCK = 10
#: Errors of a run.
NO_PATTERN, STALLED, STEP_FAILED, ENDLESS = 1, 2, 3, 4
#: Event kinds (the Python engine's ``kind``) and the reasons of a choice. The codes that
#: compiled functions are called with are int64 values, not Python ints: numba types a
#: module's int constants (and literal ints and bools in a call) as literals and compiles a
#: function once for every distinct literal it is called with.
KINDS = ("uplift", "impact", "rest", "overturn", "airborne")
UPLIFT, IMPACT, REST, OVERTURN, AIRBORNE = (np.int64(code) for code in range(5))
REASONS = ("start", "uplift", "after impact", "after rest", "after a noise-level landing")
R_START, R_UPLIFT, R_IMPACT, R_REST, R_NOISE = (np.int64(code) for code in range(5))
#: Statuses of a run.
STATUSES = ("completed", "overturned", "airborne")
