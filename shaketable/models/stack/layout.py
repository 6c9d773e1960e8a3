"""The compiled stack engine's run state: the slots of its float, int and parameter arrays.

:mod:`shaketable.models.stack.compiled` keeps a run's state in a tuple ``run`` = (phi, phi',
pattern, fs, ist, par, atol, the event arrays); ``fs`` (floats), ``ist`` (int64) and ``par``
(the run's parameters) are indexed by these names.
"""

# slots of the run's float state ``fs``: the table's work [J], rest until [s], overturn and
# airborne times [s], the time of an error [s], the one-DOF stepper's step size [s], its
# controller's memory (the last accepted error) [-] and the time of the last impact [s]
F_WORK, F_REST_UNTIL, F_T_OVERTURN, F_T_AIRBORNE, F_ERROR_TIME, F_STEP, F_PREVIOUS_ERROR, \
    F_LAST_IMPACT = range(8)
N_FLOATS = 8
# slots of the int state ``ist``: events counted and recorded, events in a row without
# progress, status, the overturned block, steps, evaluations, the error, the pattern whose
# closed forms are current (interface, side)
I_EVENTS, I_RECORDED, I_STALLED, I_STATUS, I_OVERTURNED, I_STEPS, I_EVALUATIONS, I_ERROR, \
    I_RIGID_J, I_RIGID_S = range(10)
N_INTS = 10
# slots of the parameters ``par``: the pattern check's look-ahead [s], the force tolerance
# [N], the angle and rate scales [rad, rad/s], rtol, the rest tolerance [s], the COR, the
# law (0 plastic, 1 COR), the one-DOF patterns' method (0 the single block's RKN6(4),
# 1 DOP853 as the multi-DOF ones)
P_DELTA, P_TOL_FORCE, P_ALPHA, P_ALPHA_P, P_RTOL, P_REST, P_COR, P_LAW, P_DOP853 = range(9)
#: Errors of a run.
NO_PATTERN, STALLED, STEP_FAILED = 1, 2, 3
