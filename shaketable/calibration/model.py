"""The model the COR fit adjusts: the free-rocking solution of Eq. (2-13) with the impact
map (Eq. 2-16), sampled and filtered as the record was, and its Jacobian.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
import numpy.typing as npt

from shaketable.calibration.filters import (
    analog_butterworth_foh,
    butterworth_delay,
    foh_filter,
)
from shaketable.calibration.record import FreeRockingRecord
from shaketable.core.geometry import Block
from shaketable.core.motion import MIN_SAMPLE_INTERVAL, Motion
from shaketable.lab.digitizer import Digitizer
from shaketable.models.api import simulate

#: Order of the parameters in vectors and covariance matrices (a fifth, ``filter_u`` =
#: tau^2 [s^2] of the fitted filter, follows with ``anti_alias="fit"``; ``t_release`` is
#: there the apparent release time, see :class:`Calibration`).
PARAMETERS = ("cor", "theta0", "t_release", "offset")

#: Smallest filter time constant modelled [s]: below it the fitted filter is the identity.
TAU_FLOOR = 1e-6

# (alpha, gain, direct) of analog_butterworth_foh: complex mode poles, complex gains and
# the real feed-through.
_FohCoefficients = tuple[np.ndarray, np.ndarray, float]


class FreeRockingModel:
    """FreeRockingRecord-space prediction y(t_k; x) with the engine in the loop.

    ``x = (cor, theta0, t_release, offset)`` and, when the anti-alias filter is
    fitted (``filter="fit"``), a fifth parameter u = tau^2 [s^2], the square of
    the time constant tau = 1 / (2 pi f_c) of an analog Butterworth low-pass of
    ``order`` poles. The fitted filter is delay-compensated: the model is
    S_tau[F theta](t + d tau) (d = :func:`butterworth_delay`), so that
    ``t_release`` stays the *apparent* release time (the filter's delay stays
    in it, as without a filter) and u enters at second order; u = 0 is the
    unfiltered model, reached smoothly, which keeps the Jacobian regular there.
    """

    def __init__(self, record: FreeRockingRecord, block: Block, mode: str, digitizer: Digitizer | None,
                 order: int, rtol: float, method: str = "fast") -> None:
        self.record, self.block, self.mode, self.rtol = record, block, mode, rtol
        self.digitizer, self.order, self.method = digitizer, int(order), method
        self.evaluations = 0
        self.delay = butterworth_delay(self.order)
        if mode == "known":
            self.fine_dt = 1.0 / (self._known_digitizer.rate * self._known_digitizer.oversample)
        elif mode == "fit":
            self.fine_dt = record.dt / 8.0
        self._filters: dict[float, _FohCoefficients] = {}
        # the last engine runs by their inputs: a finite-difference column in t_release,
        # offset or the filter's u (and the first point of each filter order) asks again
        # for a run it already has (on the fine grid the run depends on cor, theta0 and
        # the grid's length only); the same inputs give the same run, bit for bit
        self._runs: dict[tuple, np.ndarray] = {}

    @property
    def _known_digitizer(self) -> Digitizer:
        """The digitizer of ``mode="known"`` (the fit passes one in that mode)."""
        if self.digitizer is None:
            raise ValueError("FreeRockingModel: mode 'known' needs a digitizer")
        return self.digitizer

    @property
    def size(self) -> int:
        """Number of parameters."""
        return 5 if self.mode == "fit" else 4

    def theta(self, cor: float, theta0: float, t_release: float, times: np.ndarray) -> np.ndarray:
        """Rotation [rad] at ``times`` [s] (held at theta0 before the release)."""
        key = (float(cor), float(theta0), float(t_release), times.size, times.tobytes())
        if key not in self._runs:
            if len(self._runs) >= 8:
                del self._runs[next(iter(self._runs))]
            self._runs[key] = self._theta(cor, theta0, t_release, times)
        return self._runs[key].copy()

    def _theta(self, cor: float, theta0: float, t_release: float,
               times: np.ndarray) -> np.ndarray:
        """:meth:`theta` computed: one engine run (counted in ``evaluations``)."""
        self.evaluations += 1
        tau = times - t_release
        # a sample within MIN_SAMPLE_INTERVAL (1 ns) after the release is still at theta0
        # (it moves by theta''.tau^2/2 < 1e-16 rad there); simulating it would ask for a
        # motion with an interval below the shortest a Motion accepts: a record starting at
        # the release, t[0] = t_release to within the fit's rounding, would fail so
        after = tau > MIN_SAMPLE_INTERVAL
        out = np.full(times.shape, theta0)
        if not np.any(after):
            return out
        grid = np.concatenate([[0.0], tau[after]])
        run = simulate(self.block, Motion(grid, np.zeros_like(grid)), cor=cor, theta0=theta0,
                       rtol=self.rtol, method=self.method)
        values = run.theta
        if values.size < grid.size:            # the run stopped (overturned): hold the end
            values = np.concatenate([values[:grid.size], np.full(grid.size - values.size,
                                                                 values[-1])])
        out[after] = values[1:grid.size]
        return out

    def _filter(self, tau: float) -> _FohCoefficients:
        key = float(tau)
        if key not in self._filters:
            if len(self._filters) > 64:
                self._filters.clear()
            self._filters[key] = analog_butterworth_foh(self.order, tau, self.fine_dt)
        return self._filters[key]

    def cutoff(self, x: np.ndarray) -> float:
        """Cutoff frequency [Hz] of the filter in the model (inf: none)."""
        if self.mode == "known":
            digitizer = self._known_digitizer
            return float(digitizer.cutoff_frequency) if digitizer.anti_alias else math.inf
        if self.mode == "fit":
            tau = math.sqrt(max(float(x[4]), 0.0))
            return 1.0 / (2.0 * math.pi * tau) if tau > TAU_FLOOR else math.inf
        return math.inf

    def __call__(self, x: np.ndarray) -> np.ndarray:
        cor, theta0, t_release, offset = x[:4]
        t = self.record.t
        if self.mode == "none":
            return self.record.to_quantity(self.theta(cor, theta0, t_release, t),
                                           self.block) + offset
        # run on a fine grid from the release, filter (at rest on the held value before
        # it), read at the samples
        shift = 0.0
        if self.mode == "fit":
            tau = math.sqrt(max(float(x[4]), 0.0))
            shift = self.delay * tau
        span = t[-1] - t_release + shift
        fine = self.fine_dt * np.arange(int(math.ceil(max(span, 0.0) / self.fine_dt)) + 2)
        theta = self.theta(cor, theta0, 0.0, fine)
        theta[0] = theta0
        quantity = self.record.to_quantity(theta, self.block)
        if self.mode == "known":
            filtered = self._known_digitizer.apply_filter(quantity)
        elif tau > TAU_FLOOR:
            filtered = foh_filter(self._filter(tau), quantity, quantity[0])
        else:
            filtered = quantity
        return np.interp(t - t_release + shift, fine, filtered, left=quantity[0]) + offset


def model_jacobian(model: Callable[[np.ndarray], np.ndarray], x: npt.ArrayLike,
                   steps: Sequence[float], lower: Sequence[float],
                   upper: Sequence[float]) -> np.ndarray:
    """Central differences, one-sided where a step would cross a bound."""
    columns = []
    for index, step in enumerate(steps):
        up, down = np.array(x, dtype=float), np.array(x, dtype=float)
        up[index] = min(up[index] + step, upper[index])
        down[index] = max(down[index] - step, lower[index])
        columns.append((model(up) - model(down)) / (up[index] - down[index]))
    return np.column_stack(columns)
