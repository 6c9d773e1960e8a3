"""The compiled solvers' contract: method codes, statuses, the info array's layout, events.

Shared by the compiled engine (:mod:`shaketable.models.rocking.engine`), the SciPy
reference (:mod:`shaketable.models.rocking.reference`), which fills the same arrays,
and the code that turns them into results (:mod:`shaketable.models.rocking.run`).
Plain module constants: numba freezes them into the compiled code.
"""

METHOD_FAST = 0

METHOD_PREDICTOR_CORRECTOR = 1

METHOD_LINEAR = 2

STATUS_COMPLETED = 0

STATUS_OVERTURNED = 1

STATUS_AIRBORNE = 2

# Layout of the float summary array returned by ``integrate``.
(INFO_T_START, INFO_T_UNSTABLE, INFO_UNSTABLE_DIRECTION, INFO_T_OVERTURN,
 INFO_OVERTURN_DIRECTION, INFO_T_AIRBORNE, INFO_MAX_ABS_THETA, INFO_T_MAX,
 INFO_THETA_AT_MAX, INFO_T_END, INFO_THETA_END, INFO_THETA_DOT_END, INFO_STEPS,
 INFO_EVALUATIONS, INFO_REJECTED, INFO_CASCADES, INFO_STATUS, INFO_N_IMPACTS,
 INFO_N_OUTPUT, INFO_T_REST) = range(20)

N_INFO = 20

# Event codes. Floats on purpose: numba types an integer constant passed to a compiled
# function as a literal and compiles a separate copy of the callee for each value (four
# copies of events.locate, each with every stepper inlined, doubled the first-call compile time);
# floats have no literal type, so locate is compiled once and branches at run time.
EVENT_IMPACT = 0.0

EVENT_OVERTURN = 1.0

EVENT_PEAK = 2.0

EVENT_UNSTABLE = 3.0


#: Solvers by name. ``fast`` is the default.
#: The solver registry: every method :func:`~shaketable.models.api.simulate` accepts, with a
#: one-line description (the CLI offers these names).
METHODS = {
    "fast": "compiled Runge-Kutta-Nystrom 6(4), adaptive, with event location (numba)",
    "reference": "SciPy DOP853 with tight tolerances and Brent event location (slow)",
    "predictor-corrector": "the report's BLOKROC scheme: Heun steps, `subdivisions` per sample",
    "linear": "Housner's slender-block linearisation (Eq. 2-4), closed form between events",
}
