"""The result of one run of an asymmetric block."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaketable.core.equality import fields_equal
from shaketable.core.geometry import AsymmetricBlock
from shaketable.core.motion import Motion
from shaketable.models.base import ModelResult
from shaketable.models.rocking.layout import (
    INFO_MAX_ABS_THETA,
    INFO_N_IMPACTS,
    INFO_STATUS,
    INFO_T_MAX,
    INFO_T_OVERTURN,
    INFO_T_REST,
    INFO_T_START,
    INFO_T_UNSTABLE,
)
from shaketable.models.rocking.result import STATUSES

# the engine's info layout, under the short names this module reads it by
_T_START, _T_UNSTABLE, _T_OVERTURN, _MAX_ABS, _T_MAX, _N_IMPACTS, _STATUS, _T_REST = (
    INFO_T_START, INFO_T_UNSTABLE, INFO_T_OVERTURN, INFO_MAX_ABS_THETA, INFO_T_MAX,
    INFO_N_IMPACTS, INFO_STATUS, INFO_T_REST)


@dataclass(frozen=True, eq=False)
class AsymmetricResult(ModelResult):
    """Time history and scalar results of one run of an :class:`AsymmetricBlock`.

    Attributes
    ----------
    block : AsymmetricBlock
    motion : Motion
        The motion run (cut or padded to the run's duration).
    cor_onto_plus, cor_onto_minus : float
        COR of an impact landing on the pivot of theta > 0 / theta < 0 [-].
    method : str
        ``"fast"`` or ``"reference"``.
    t, theta, theta_dot : ndarray
        Samples of the motion up to the end of the run [s], rotation [rad] (> 0: pivot on
        the -x corner) and angular velocity [rad/s].
    impact_times : ndarray
        Times of the first impacts [s].
    info : ndarray
        The solvers' scalar results (layout of :mod:`shaketable.models.rocking.layout`).
    """

    block: AsymmetricBlock
    motion: Motion
    cor_onto_plus: float
    cor_onto_minus: float
    method: str
    t: np.ndarray
    theta: np.ndarray
    theta_dot: np.ndarray
    impact_times: np.ndarray
    info: np.ndarray

    def __eq__(self, other: object) -> bool:
        return fields_equal(self, other)

    __hash__ = None  # type: ignore[assignment]

    @property
    def status(self) -> str:
        """``"completed"``, ``"overturned"`` or ``"airborne"``."""
        return STATUSES[int(self.info[_STATUS])]

    @property
    def overturned(self) -> bool:
        """True when |theta| reached pi/2."""
        return self.status == "overturned"

    @property
    def t_start(self) -> float:
        """First uplift [s]; NaN if the block never rocked."""
        return float(self.info[_T_START])

    @property
    def t_overturn(self) -> float:
        """Time |theta| reached pi/2 [s]; NaN if it did not."""
        return float(self.info[_T_OVERTURN])

    @property
    def max_abs_theta(self) -> float:
        """Largest |theta| [rad]."""
        return float(self.info[_MAX_ABS])

    @property
    def n_impacts(self) -> int:
        """Impacts resolved."""
        return int(self.info[_N_IMPACTS])

    def energy(self) -> np.ndarray:
        """Mechanical energy per unit mass at each sample while rocking [m^2/s^2].

        0.5 I0_s theta'^2 + g R_s cos(alpha_s - |theta|) on the active side s, minus the
        rest value g h; a block at rest has 0.
        """
        from shaketable.core.constants import G

        block = self.block
        side = np.where(self.theta > 0, 1.0, np.where(self.theta < 0, -1.0,
                                                      np.sign(self.theta_dot)))
        inertia = np.where(side >= 0, block.I0_of(1.0), block.I0_of(-1.0))
        radius = np.where(side >= 0, block.R_of(1.0), block.R_of(-1.0))
        alpha = np.where(side >= 0, block.alpha_plus, block.alpha_minus)
        return (0.5 * inertia * self.theta_dot ** 2
                + G * (radius * np.cos(alpha - np.abs(self.theta)) - block.h))

    def to_frame(self):
        """Time history as a :class:`pandas.DataFrame` with units in the column names."""
        import pandas as pd

        alpha = np.where(self.theta >= 0, self.block.alpha_plus, self.block.alpha_minus)
        horizontal, _ = self.motion.at(self.t)
        return pd.DataFrame({"time [s]": self.t, "ug [m/s^2]": horizontal,
                             "theta [rad]": self.theta, "theta_dot [rad/s]": self.theta_dot,
                             "theta/alpha_side [-]": self.theta / alpha})

    def events_frame(self):
        """The run's events as a :class:`pandas.DataFrame`, in time order: ``uplift``, each
        resolved ``impact`` (the first ones, as :attr:`impact_times`), ``unstable``,
        ``overturn`` and ``rest``; an event that did not happen has no row."""
        import pandas as pd

        once = [(float(self.info[index]), kind) for index, kind in (
            (_T_START, "uplift"), (_T_UNSTABLE, "unstable"), (_T_OVERTURN, "overturn"),
            (_T_REST, "rest")) if not math.isnan(self.info[index])]
        frame = pd.DataFrame({
            "time [s]": np.concatenate([[t for t, _ in once], self.impact_times]),
            "event": [kind for _, kind in once] + ["impact"] * len(self.impact_times)})
        return frame.sort_values("time [s]", kind="stable", ignore_index=True)

    def summary(self) -> dict:
        """Scalar results (NaN: never happened)."""
        block = self.block
        return {"alpha_plus [rad]": block.alpha_plus, "alpha_minus [rad]": block.alpha_minus,
                "h [m]": block.h, "cor_onto_plus [-]": self.cor_onto_plus,
                "cor_onto_minus [-]": self.cor_onto_minus, "method": self.method,
                "status": self.status, "t_start [s]": self.t_start,
                "t_unstable [s]": float(self.info[_T_UNSTABLE]),
                "t_overturn [s]": self.t_overturn, "max_abs_theta [rad]": self.max_abs_theta,
                "t_max [s]": float(self.info[_T_MAX]), "n_impacts": self.n_impacts,
                "t_rest [s]": float(self.info[_T_REST]) if not math.isnan(
                    self.info[_T_REST]) else math.nan}

    def plot(self, fig=None, title: str | None = None):
        """Table acceleration and theta / alpha_s against time."""
        from shaketable.plots.validation import asymmetric_history

        return asymmetric_history(self, fig=fig, title=title)
