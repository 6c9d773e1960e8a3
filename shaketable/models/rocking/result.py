"""The result of one simulation."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from shaketable.core.equality import fields_equal
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.models.base import ModelResult

#: Why a run stopped.
STATUSES = ("completed", "overturned", "airborne")


@dataclass(frozen=True)
class RockingResult(ModelResult):
    """Time history and scalar results of one rocking simulation.

    Attributes
    ----------
    block : Block
        The block simulated.
    motion : Motion
        The ground motion it stood on (``Motion.at_rest`` for free rocking).
    cor : float
        Coefficient of restitution [-].
    method : str
        Solver that produced the result.
    t : ndarray
        Output times [s]: the motion's samples up to the end of the run; an
        overturned or airborne run ends with its event time.
    theta : ndarray
        Rotation [rad] (positive: pivot on the -x corner, see the docs).
    theta_dot : ndarray
        Angular velocity [rad/s].
    theta_ddot : ndarray
        Angular acceleration [rad/s^2] (zero while the block rests).
    impact_times : ndarray
        Times of the resolved impacts [s].
    impact_velocities : ndarray
        Angular velocity just before each impact [rad/s].
    t_start : float
        First uplift [s]; NaN when the block never rocked.
    t_unstable : float
        First time |theta| exceeded alpha [s]; NaN if never.
    unstable_direction : int
        Sign of theta when it first exceeded alpha (0 if never).
    t_overturn : float
        Time |theta| reached pi/2 [s]; NaN if the block did not overturn.
    overturn_direction : int
        +1 or -1 (sign of theta), 0 if the block did not overturn.
    t_airborne : float
        Time the vertical ground acceleration reached -g (the block leaves
        the ground, outside the model) [s]; NaN if never. The run stops there.
    t_rest : float
        Time the block last came to rest after a cascade of impacts [s]; NaN if never.
    max_abs_theta : float
        Peak |theta| [rad] (located at the turning point, not only at samples).
    t_max : float
        Time of the peak [s].
    n_impacts : int
        Number of impacts resolved one by one (the summed tail of a cascade is
        not counted).
    cascades : int
        Number of endless impact cascades summed in closed form.
    statistics : dict
        Solver work: steps, rejected steps, right-hand-side evaluations.
    """

    __eq__ = fields_equal   # arrays compared by value; equal after a pickle round trip

    block: Block
    motion: Motion
    cor: float
    method: str
    t: np.ndarray
    theta: np.ndarray
    theta_dot: np.ndarray
    theta_ddot: np.ndarray
    impact_times: np.ndarray
    impact_velocities: np.ndarray
    t_start: float
    t_unstable: float
    unstable_direction: int
    t_overturn: float
    overturn_direction: int
    t_airborne: float
    t_rest: float
    max_abs_theta: float
    t_max: float
    n_impacts: int
    cascades: int
    status: str
    statistics: dict = field(default_factory=dict)

    @property
    def overturned(self) -> bool:
        """True when the block reached |theta| = pi/2."""
        return self.status == "overturned"

    @property
    def unstable(self) -> bool:
        """True when |theta| exceeded alpha at some time."""
        return bool(np.isfinite(self.t_unstable))

    @property
    def max_theta_ratio(self) -> float:
        """max |theta| / alpha [-], the quantity of Tables 4.1-4.3; NaN for an overturned run.

        An overturned run is the report's "F": the run stops at |theta| = pi/2,
        and (pi/2)/alpha is where the run was stopped, not a peak. Its largest
        rocking before the fatal excursion is :attr:`max_theta_ratio_before_instability`.
        """
        if self.overturned:
            return math.nan
        return self.max_abs_theta / self.block.alpha

    @property
    def max_theta_ratio_before_instability(self) -> float:
        """Largest |theta| / alpha [-] before the excursion on which |theta| first passed alpha.

        The rocking that preceded instability: the samples before the last
        change of sign of theta (or the first uplift) that precedes
        ``t_unstable``; 0 when the block became unstable on its first
        excursion. For a run that never became unstable it is
        :attr:`max_theta_ratio`. Read at the output samples (the peak of the
        whole run, :attr:`max_abs_theta`, is located exactly).
        """
        if not self.unstable:
            return self.max_theta_ratio
        before = self.t < self.t_unstable
        theta = self.theta[before]
        crossings = np.flatnonzero(np.sign(theta[1:]) * np.sign(theta[:-1]) < 0)
        if crossings.size == 0:
            return 0.0
        return float(np.max(np.abs(theta[:crossings[-1] + 1]))) / self.block.alpha

    @property
    def fate(self):
        """Whether the block will overturn once the motion has ended, decided by energy.

        The table is at rest after the motion; the state at the end of the run
        settles the block's fate in closed form (:mod:`shaketable.core.fate`:
        the exact model's energy for the exact methods, the linearised one's
        for ``method="linear"``), so no free tail has to be simulated. An
        overturned run has ``reason == "overturned"``; a run with prestress rods
        or a block that left the ground is ``"undecided: ..."`` (the rules
        assume a bare block; a constant top force is not known to the result
        and is ignored). A run cut short of its motion by ``duration`` is judged
        as if the table stopped where the run ends.

        Returns
        -------
        shaketable.core.fate.Fate
        """
        from shaketable.core.fate import Fate, fate_of

        if self.overturned:
            return Fate(True, 0, "overturned", math.nan)
        if self.status == "airborne" or self.block.rods is not None:
            why = "the block left the ground" if self.status == "airborne" else "prestress rods"
            return Fate(False, 0, f"undecided: {why}", math.nan)
        return fate_of(float(self.theta[-1]), float(self.theta_dot[-1]), self.block.alpha,
                       self.block.p, self.cor, "linear" if self.method == "linear" else "exact")

    @property
    def will_overturn(self) -> bool:
        """True when the block overturned or will overturn after the motion (:attr:`fate`)."""
        return self.fate.will_overturn

    def verdict(self) -> str:
        """The run in words: "overturned (+) at 6.42 s", "max θ/α = 0.78", or the airborne
        time; a block released on a still table that rocked, when it came to rest and after
        how many cycles (:func:`~shaketable.models.rocking.free_rocking.free_rocking_verdict`)."""
        if self.status == "completed" and math.isfinite(self.t_start):
            from shaketable.models.rocking.free_rocking import free_rocking_verdict, is_free

            if is_free(self):
                return free_rocking_verdict(self)
        if self.overturned:
            side = "+" if self.overturn_direction > 0 else "−"
            return f"overturned ({side}) at {self.t_overturn:.2f} s"
        if self.status == "airborne":
            return (f"leaves the ground at {self.t_airborne:.2f} s (vertical ≤ −g), "
                    f"max θ/α = {self.max_theta_ratio:.2f} until then")
        return f"max θ/α = {self.max_theta_ratio:.2f}"

    @property
    def max_rod_force(self) -> float:
        """Largest total tension in the prestress rods [W] (Section 4.4); 0 without rods.

        The report's "0.4W + 0.4W Delta": F0 + K Delta, with the rods'
        extension at the largest rotation. A rod at distance d from the pivot
        stretches d sin|theta|; the pair's arms S and B - S add up to B, each
        rod having half of K, so F = F0 + K (B/2) sin(max |theta|), which grows
        with |theta|: its maximum is at the exactly located max |theta|.
        """
        rods = self.block.rods
        if rods is None:
            return 0.0
        return float(rods.force + rods.stiffness * self.block.width / 2.0
                     * math.sin(min(self.max_abs_theta, math.pi / 2.0)))

    def ground_at(self, times) -> tuple[np.ndarray, np.ndarray]:
        """Horizontal and vertical ground acceleration at ``times`` [m/s^2]."""
        return self.motion.at(times)

    def to_frame(self):
        """Time history as a :class:`pandas.DataFrame` with units in the column names."""
        import pandas as pd

        return pd.DataFrame({
            "time [s]": self.t,
            **self.motion.columns_in_g(self.t),
            "theta [rad]": self.theta,
            "theta_dot [rad/s]": self.theta_dot,
            "theta_ddot [rad/s^2]": self.theta_ddot,
            "theta/alpha [-]": self.theta / self.block.alpha,
        })

    def events_frame(self):
        """The run's events as a :class:`pandas.DataFrame`, in time order: ``uplift``
        (rocking starts), each resolved ``impact`` (with theta' just before it [rad/s]),
        ``unstable`` (|theta| past alpha), ``overturn``, ``airborne`` and ``rest`` (the
        last cascade summed to rest); an event that did not happen has no row."""
        import pandas as pd

        times = [self.t_start, self.t_unstable, self.t_overturn, self.t_airborne, self.t_rest]
        kinds = ["uplift", "unstable", "overturn", "airborne", "rest"]
        once = [(t, kind) for t, kind in zip(times, kinds) if not math.isnan(t)]
        frame = pd.DataFrame({
            "time [s]": np.concatenate([[t for t, _ in once], self.impact_times]),
            "event": [kind for _, kind in once] + ["impact"] * len(self.impact_times),
            "theta_dot before [rad/s]": np.concatenate([np.full(len(once), np.nan),
                                                        self.impact_velocities])})
        return frame.sort_values("time [s]", kind="stable", ignore_index=True)

    def summary(self) -> dict:
        """Scalar results as a JSON-ready dict (NaN written as None).

        The fields are described in ``docs/conventions.md`` ("Results of a run"):
        an overturned run has ``overturned`` true, ``t_overturn [s]`` and
        ``overturn_direction``, ``max_theta_ratio [-]`` None (the report's F) and
        its earlier rocking in ``max_theta_ratio_before_instability [-]``;
        ``verdict`` says it in words.
        """
        from shaketable.core.files import json_ready_dict

        block = self.block
        data = {
            "block_height [m]": block.height, "block_width [m]": block.width,
            "alpha [rad]": block.alpha, "p [rad/s]": block.p, "cor [-]": self.cor,
            "method": self.method, "motion": self.motion.name, "status": self.status,
            "verdict": self.verdict(),
            "overturned": self.overturned, "max_theta_ratio [-]": self.max_theta_ratio,
            "max_theta_ratio_before_instability [-]": self.max_theta_ratio_before_instability,
            "max_abs_theta [rad]": self.max_abs_theta, "t_max [s]": self.t_max,
            "t_start [s]": self.t_start, "t_unstable [s]": self.t_unstable,
            "unstable_direction": self.unstable_direction,
            "t_overturn [s]": self.t_overturn, "overturn_direction": self.overturn_direction,
            "t_airborne [s]": self.t_airborne, "t_rest [s]": self.t_rest,
            "n_impacts": self.n_impacts, "cascades": self.cascades,
        }
        if block.rods is not None:
            data["max_rod_force [W]"] = self.max_rod_force
        data.update({f"solver {key}": value for key, value in self.statistics.items()})
        return json_ready_dict(data)

    def plot(self, fig=None, title: str | None = None):
        """The report's Calcomp layout (Figs. 2.8, 4.1); see :func:`shaketable.plots.calcomp`."""
        from shaketable.plots.calcomp import calcomp

        return calcomp(self, fig=fig, title=title)
