"""Result of the planar reference solver (:mod:`shaketable.models.planar.reference`).

The planar block (``docs/planar.md``): rest, slide, rock, slide-rock and
free flight; mode codes and names of :mod:`shaketable.models.planar.shenton`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.models.base import ModelResult
from shaketable.models.planar.result import VERDICTS, planar_frame, planar_summary
from shaketable.models.planar.shenton import MODE_NAMES
from shaketable.models.sliding.result import Friction

#: Statuses of a run.
STATUSES = ("completed", "overturned", "painleve", "inconsistent")


@dataclass(frozen=True)
class PlanarReferenceResult(ModelResult):
    """Time history, events and scalar results of one reference run.

    Attributes
    ----------
    block : Block
    motion : Motion
        Table accelerations [m/s^2].
    cor : float or str
        Coefficient of restitution [-] or ``"housner"``.
    friction : Friction
    t : ndarray
        Output times [s] (the motion's samples, up to the end of the run).
    x, y, theta : ndarray
        Centre's horizontal displacement from its start [m], centre's height
        above the table [m], rotation [rad] at ``t``.
    x_dot, y_dot, theta_dot : ndarray
        Their rates [m/s], [m/s], [rad/s].
    mode : ndarray of int
        Mode at ``t`` (codes of :mod:`shaketable.models.planar.shenton`).
    event_times : ndarray
        Times of the located events [s].
    event_kinds : tuple of str
        "start", "stick", "slip", "reverse", "lift-off", "landing", "impact",
        "flat landing", "cascade", "unstable", "overturn", "painleve".
    event_mode_before, event_mode_after : ndarray of int
        Mode codes on both sides of each event.
    impact_times, impact_velocities : ndarray
        Time [s] and pre-impact theta' [rad/s] of each corner impact.
    peak_slip, t_peak_slip, residual_slip : float
        Largest |slip| of the base midpoint (x + h sin(theta)) [m], its time [s],
        and the slip at the end [m].
    max_abs_theta, t_max : float
        Largest |theta| [rad] and its time [s].
    t_unstable, t_overturn : float
        First |theta| = alpha [s]; overturn (|theta| = pi/2) [s]; NaN if never.
    t_rest : float
        End of the last summed cascade of impacts [s] (NaN if none).
    friction_work, input_work, impact_loss : float
        Work of friction on the block (<= 0), work of the table's inertial
        forces -m ug, -m vg on the block, and kinetic energy lost in impacts
        (>= 0), per unit mass [J/kg].
    energy_start, energy_end : float
        Kinetic + potential energy per mass, 0.5 (x'^2 + y'^2 + Ic theta'^2)
        + g (y - h) [J/kg]; energy_end - energy_start = friction_work +
        input_work - impact_loss.
    capped_impacts : int
        Impacts whose rho was lowered so as not to add energy.
    time_in_mode : dict
        Seconds spent in each mode, by name.
    peak_base_slip, t_peak_base_slip : float
        How far the base slid [m] (the corner the block stands or turns on; x when flat)
        and when [s], at the located events and the steps' ends.
    status : str
        One of :data:`STATUSES`.
    message : str
        Why a run stopped early (empty otherwise).
    """

    block: Block
    motion: Motion
    cor: float | str
    friction: Friction
    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    theta: np.ndarray
    x_dot: np.ndarray
    y_dot: np.ndarray
    theta_dot: np.ndarray
    mode: np.ndarray
    event_times: np.ndarray
    event_kinds: tuple
    event_mode_before: np.ndarray
    event_mode_after: np.ndarray
    impact_times: np.ndarray
    impact_velocities: np.ndarray
    peak_slip: float
    t_peak_slip: float
    residual_slip: float
    max_abs_theta: float
    t_max: float
    t_unstable: float
    t_overturn: float
    t_rest: float
    friction_work: float
    input_work: float
    impact_loss: float
    energy_start: float
    energy_end: float
    capped_impacts: int
    status: str
    message: str = ""
    time_in_mode: dict = field(default_factory=dict)
    peak_base_slip: float = math.nan
    t_peak_base_slip: float = math.nan

    @property
    def overturned(self) -> bool:
        """Whether the block overturned (|theta| reached pi/2)."""
        return self.status == "overturned"

    @property
    def max_theta_over_alpha(self) -> float:
        """max |theta| / alpha [-]."""
        return self.max_abs_theta / self.block.alpha

    @property
    def max_theta_ratio(self) -> float:
        """max |theta| / alpha [-]; NaN for an overturned run (the report's "F"), as
        :attr:`shaketable.models.planar.result.PlanarResult.max_theta_ratio`."""
        if self.overturned:
            return math.nan
        return self.max_theta_over_alpha

    @property
    def n_impacts(self) -> int:
        """Number of corner impacts."""
        return len(self.impact_times)

    @property
    def work_table(self) -> float:
        """Work of the table's inertial forces on the block [J/kg] (:attr:`input_work`, the
        name of :attr:`shaketable.models.planar.result.PlanarResult.work_table`)."""
        return self.input_work

    @property
    def work_friction(self) -> float:
        """Work of friction on the block [J/kg], <= 0 (:attr:`friction_work`)."""
        return self.friction_work

    @property
    def energy_residual(self) -> float:
        """E_end - E_start - (W_table + W_friction - impact losses) [J/kg]: zero up to the
        integration error, as :attr:`shaketable.models.planar.result.PlanarResult.energy_residual`."""
        return (self.energy_end - self.energy_start
                - (self.work_table + self.work_friction - self.impact_loss))

    @property
    def overturn_direction(self) -> int:
        """Sign of theta at the overturn (0: did not overturn) [-]."""
        if not self.overturned or self.theta.size == 0:
            return 0
        return 1 if self.theta[-1] > 0 else -1

    @property
    def modes_visited(self) -> tuple:
        """Modes the block was in for some time, or entered (names, in code order)."""
        entered = {int(code) for code in self.mode} | {int(c) for c in self.event_mode_after}
        return tuple(name for code, name in enumerate(MODE_NAMES)
                     if code in entered or self.time_in_mode.get(name, 0.0) > 0.0)

    def verdict(self) -> str:
        """The largest mode visited in words, as
        :meth:`shaketable.models.planar.result.PlanarResult.verdict`: stayed < slid < rocked
        < slide-rocked < flew, and overturned above all."""
        if self.overturned:
            return "overturned"
        largest = max(MODE_NAMES.index(name) for name in self.modes_visited)
        return VERDICTS[largest]

    @property
    def slip(self) -> np.ndarray:
        """Slip of the base midpoint relative to the table, x + h sin(theta) [m]."""
        return self.x + self.block.h * np.sin(self.theta)

    def events_of(self, kind: str) -> np.ndarray:
        """Times [s] of the events of one kind."""
        return np.array([t for t, k in zip(self.event_times, self.event_kinds) if k == kind])

    def to_frame(self):
        """Time history as a :class:`pandas.DataFrame`, units in the column names: the
        columns of :meth:`shaketable.models.planar.result.PlanarResult.to_frame` (ground
        acceleration [g], x, y, theta, their rates, slip, theta/alpha, mode name)."""
        return planar_frame(self)

    def events_frame(self):
        """The located events as a :class:`pandas.DataFrame`: time [s], kind and the mode
        names on both sides (the names of :meth:`PlanarResult.events_frame
        <shaketable.models.planar.result.PlanarResult.events_frame>`)."""
        import pandas as pd

        return pd.DataFrame({
            "time [s]": self.event_times,
            "event": list(self.event_kinds),
            "mode before": [MODE_NAMES[int(k)] for k in self.event_mode_before],
            "mode after": [MODE_NAMES[int(k)] for k in self.event_mode_after],
        })

    def plot(self, fig=None, title: str | None = None):
        """The Calcomp layout with a slip panel and a mode band, the figure of
        :meth:`shaketable.models.planar.result.PlanarResult.plot`; see
        :func:`shaketable.plots.planar.planar_figure`."""
        from shaketable.plots.planar import planar_figure

        return planar_figure(self, fig=fig, title=title)

    def summary(self) -> dict:
        """Scalar results as a JSON-ready dict (NaN written as None): the keys of
        :meth:`shaketable.models.planar.result.PlanarResult.summary` for every quantity both
        compute (:func:`~shaketable.models.planar.result.planar_summary`), and ``model``."""
        return planar_summary(self, model="planar reference (SciPy DOP853)")
