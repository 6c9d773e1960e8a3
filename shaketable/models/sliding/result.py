"""Inputs and results of the sliding (Coulomb stick-slip) response mode.

The report treats sliding in Section 2.1 (the start condition, Eq. (2-2), and
the boundary with rocking) and Section 4.5 / Table 4.4 (maximum sliding
displacement for dynamic friction 0.1, 0.2, 0.3); the model itself is that of
its companion report, reference (1). Nomenclature:

=================  =====================  ===================================
report             code                   meaning
=================  =====================  ===================================
mu (Sec. 2.1)      ``Friction.static``    static coefficient mu_s [-]
mu_d (Sec. 4.5)    ``Friction.dynamic``   dynamic coefficient [-]
u-double-dot       ``ug``                 horizontal table acceleration [m/s^2]
v-double-dot       ``vg``                 vertical table acceleration, up [m/s^2]
(none)             ``x``                  block displacement relative to the table [m]
=================  =====================  ===================================

Sign convention: ``x`` is the block's displacement relative to the table along
+x; a table accelerating toward +x leaves the block behind (``x`` < 0).

References
----------
.. [1] M. Aslam, W. G. Godden and D. T. Scalise, "Rocking and overturning
   response of rigid bodies to earthquake motions", Lawrence Berkeley
   Laboratory, University of California, Berkeley.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from shaketable.core.constants import INCH
from shaketable.core.equality import fields_equal
from shaketable.core.motion import Motion
from shaketable.core.validation import nonnegative
from shaketable.models.base import ModelResult

#: Phases of the block on the table, the ``state`` codes of :class:`SlidingResult`.
STATES = {0: "stuck", 1: "sliding +x", -1: "sliding -x", 2: "airborne"}

#: Event codes of :attr:`SlidingResult.event_kinds`.
EVENTS = {1: "slip starts", 2: "sticks", 3: "reverses", 4: "lifts off (g + vg <= 0)",
          5: "lands"}

#: Overall outcomes of a run.
STATUSES = ("at rest", "slid", "airborne")



@dataclass(frozen=True)
class Friction:
    """Coulomb friction between block and table (Section 2.1 and 4.5 of [1]_).

    Attributes
    ----------
    static : float
        Static coefficient mu_s [-]: slip starts when |ug| > mu_s (g + vg),
        Eq. (2-2); it is also mu_s that decides between sliding and rocking
        (Section 2.1, and the last paragraph of Section 4.5).
    dynamic : float
        Dynamic coefficient mu_d [-] while sliding, 0 <= mu_d <= mu_s; the
        coefficient of Table 4.4. Default: equal to ``static``.

    Raises
    ------
    ValueError
        Negative, non-finite or non-numeric coefficients, or mu_d > mu_s; the
        message names the parameter.
    """

    static: float
    dynamic: float | None = None

    def __post_init__(self):
        static = nonnegative("static friction mu_s", self.static, " [-]")
        dynamic = static if self.dynamic is None else nonnegative(
            "dynamic friction mu_d", self.dynamic, " [-]")
        if dynamic > static:
            raise ValueError(f"dynamic friction mu_d ({dynamic!r}) must not exceed static "
                             f"friction mu_s ({static!r})")
        object.__setattr__(self, "static", static)
        object.__setattr__(self, "dynamic", dynamic)

    @classmethod
    def coulomb(cls, mu: float) -> Friction:
        """One coefficient for starting and sliding (mu_s = mu_d = ``mu``)."""
        return cls(mu, mu)


@dataclass(frozen=True)
class SlidingResult(ModelResult):
    """Time history and scalar results of one sliding (stick-slip) run.

    Attributes
    ----------
    motion : Motion
        The table motion [m/s^2].
    friction : Friction
        Coefficients used.
    t : ndarray
        Output times [s] (the motion's samples).
    x : ndarray
        Block displacement relative to the table [m].
    v : ndarray
        Relative velocity [m/s].
    state : ndarray of int
        Phase at each output time (:data:`STATES`; the phase entered at that
        instant).
    event_times : ndarray
        Times of the located events [s] (exact, not on samples).
    event_kinds : ndarray of int
        Codes of :data:`EVENTS`.
    event_x : ndarray
        Relative displacement at each event [m].
    peak_slip : float
        Largest |x| over the run [m], at samples and events (a turning point
        of x is a zero of v, so an event): the quantity of Table 4.4.
    t_peak : float
        Time of ``peak_slip`` [s].
    residual_slip : float
        x at the end of the run [m].
    slip_episodes : int
        Number of times the block, stuck, started to slip.
    reversals : int
        Zero crossings of the relative velocity that did not end in sticking.
    time_sliding : float
        Total time spent sliding [s].
    time_airborne : float
        Total time with g + vg <= 0 (no normal force: the block would leave
        the table, outside this model; it is carried on without friction) [s].
    t_first_slip : float
        First slip [s]; NaN if the block never slipped.
    status : str
        One of :data:`STATUSES`.
    mode_choice : dict
        Section 2.1 record of the run (empty unless a block was given to
        :func:`shaketable.models.sliding.engine.slide`): which mode the model used
        and when each threshold was first reached.
    """

    __eq__ = fields_equal   # arrays compared by value; equal after a pickle round trip

    motion: Motion
    friction: Friction
    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    state: np.ndarray
    event_times: np.ndarray
    event_kinds: np.ndarray
    event_x: np.ndarray
    peak_slip: float
    t_peak: float
    residual_slip: float
    slip_episodes: int
    reversals: int
    time_sliding: float
    time_airborne: float
    t_first_slip: float
    status: str
    mode_choice: dict = field(default_factory=dict)

    @property
    def peak_slip_inches(self) -> float:
        """``peak_slip`` in inches, the unit of Table 4.4 [in]."""
        return self.peak_slip / INCH

    def ground_at(self, times) -> tuple[np.ndarray, np.ndarray]:
        """Horizontal and vertical table acceleration at ``times`` (linear) [m/s^2]."""
        return self.motion.at(times)

    def to_frame(self):
        """Time history as a :class:`pandas.DataFrame`, units in the column names."""
        import pandas as pd

        return pd.DataFrame({
            "time [s]": self.t,
            **self.motion.columns_in_g(self.t),
            "relative displacement [m]": self.x,
            "relative velocity [m/s]": self.v,
            "state": [STATES[int(code)] for code in self.state],
        })

    def events_frame(self):
        """The located events as a :class:`pandas.DataFrame`."""
        import pandas as pd

        return pd.DataFrame({"time [s]": self.event_times,
                             "event": [EVENTS[int(k)] for k in self.event_kinds],
                             "relative displacement [m]": self.event_x})

    def summary(self) -> dict:
        """Scalar results as a JSON-ready dict (NaN written as None)."""
        from shaketable.core.files import json_ready_dict

        data = {
            "response mode": "sliding", "motion": self.motion.name, "status": self.status,
            "static friction mu_s [-]": self.friction.static,
            "dynamic friction mu_d [-]": self.friction.dynamic,
            "peak slip [m]": self.peak_slip, "peak slip [in]": self.peak_slip_inches,
            "t_peak [s]": self.t_peak, "residual slip [m]": self.residual_slip,
            "slip episodes": self.slip_episodes, "reversals": self.reversals,
            "time sliding [s]": self.time_sliding, "time airborne [s]": self.time_airborne,
            "t_first_slip [s]": self.t_first_slip,
        }
        data.update(self.mode_choice)
        return json_ready_dict(data)

    def plot(self, fig=None, title: str | None = None, length_unit: str = "in"):
        """Table acceleration, relative velocity and displacement (lengths in
        ``length_unit``, the user's: m, cm, mm, in or ft); see
        :func:`shaketable.plots.sliding.sliding_figure`."""
        from shaketable.plots.sliding import sliding_figure

        return sliding_figure(self, fig=fig, title=title, length_unit=length_unit)
