"""The planar engine's contract: statuses, event kinds, the info array's layout, its limits.

Shared by the compiled engine (:mod:`shaketable.models.planar.engine` and its mode helpers in
:mod:`shaketable.models.planar.phases`) and the code that turns its arrays into results
(:mod:`shaketable.models.planar.run`, :mod:`shaketable.models.planar.batch`), which
reads them as ``planar.<NAME>``. Plain module constants: numba freezes them into the
compiled code.
"""

from __future__ import annotations

import numpy as np

from shaketable.models.planar.physics import FLIGHT, REST, ROCK, SLIDE, SLIDE_ROCK
from shaketable.models.planar.steps import N_EVENTS, N_STATE
from shaketable.models.planar.track import P_PEAK_BASE_SLIP

#: Why a run stopped (index = status code).
STATUSES = ("completed", "overturned", "painleve", "inconsistent", "chatter", "stalled")
STATUS_COMPLETED, STATUS_OVERTURNED, STATUS_PAINLEVE, STATUS_INCONSISTENT, STATUS_CHATTER, \
    STATUS_STALLED = range(6)

#: Event kinds (index = code): a mode change that is not an impact, a corner impact,
#: a reversal of the slip, the end of a summed cascade of impacts, |theta| first
#: exceeding alpha, overturning, a flat landing of the whole base.
EVENT_KINDS = ("mode change", "impact", "slip reverses", "cascade summed", "unstable",
               "overturned", "flat landing")
# int64 values, not Python ints: numba types a module's int constants as literals and
# compiles a helper once for every distinct literal it is called with (the event record
# was compiled 16 times on a cold cache); so are the mode codes given to it (MODE_*)
EV_MODE, EV_IMPACT, EV_REVERSAL, EV_CASCADE, EV_UNSTABLE, EV_OVERTURN, EV_LANDING = (
    np.int64(code) for code in range(7))
#: The mode codes of :mod:`shaketable.models.planar.physics` as int64 (see above).
MODE_REST, MODE_SLIDE, MODE_ROCK, MODE_SLIDE_ROCK, MODE_FLIGHT = (
    np.int64(code) for code in (REST, SLIDE, ROCK, SLIDE_ROCK, FLIGHT))

#: Columns of the event array: time [s], kind, mode before, mode after, theta' [rad/s]
#: (before an impact; else at the event), slip of the base midpoint [m].
EVENT_COLUMNS = 6

#: Layout of the info array.
(I_STATUS, I_T_END, I_N_IMPACTS, I_CAPPED, I_CASCADES, I_T_START, I_T_UNSTABLE,
 I_UNSTABLE_DIRECTION, I_T_OVERTURN, I_OVERTURN_DIRECTION, I_MAX_ABS_THETA, I_T_MAX,
 I_PEAK_SLIP, I_T_PEAK_SLIP, I_PEAK_EXCURSION, I_W_TABLE, I_W_FRICTION, I_IMPACT_LOSS,
 I_STEPS, I_REJECTED, I_EVALUATIONS, I_N_EVENTS, I_N_OUTPUT, I_TIME_REST, I_TIME_SLIDE,
 I_TIME_ROCK, I_TIME_SLIDE_ROCK, I_TIME_FLIGHT, I_VISITED, I_T_REST, I_E0, I_E_END,
 I_FAILED_MODE, I_PEAK_BASE_SLIP, I_T_PEAK_BASE_SLIP) = range(35)
N_INFO = 35
assert I_PEAK_BASE_SLIP - I_MAX_ABS_THETA == P_PEAK_BASE_SLIP   # planar_track's layout

#: Where planar_track's peaks start in info, as an int64 (track is compiled for the type
#: its callers give ``first``: a literal would compile it once more).
PEAKS = np.int64(I_MAX_ABS_THETA)

#: The sizes of the engine's work arrays (engine.work_arrays), as int64.
ONE, SIX, STATE, EVENTS = np.int64(1), np.int64(6), np.int64(N_STATE), np.int64(N_EVENTS)

#: Transitions allowed at one instant before the run stops with status "chatter".
MAX_TRANSITIONS_AT_ONE_TIME = 200

#: Impacts at one instant (each turning the block onto the other corner) before the run
#: stops with status "inconsistent": a safeguard (the two-corner problem of
#: :func:`~shaketable.models.planar.modes.strike` ends every such sequence at once).
MAX_IMMEDIATE_IMPACTS = 1000

#: Transitions allowed in one sample interval before the run stops with status "chatter"
#: (a safeguard against a Zeno sequence the cascade rule does not sum; never reached in
#: the tests).
MAX_TRANSITIONS_PER_INTERVAL = 100_000
