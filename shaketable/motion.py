"""Ground motion: sampled horizontal and vertical ground accelerations.

Sign convention (stated once for the whole package, see ``docs/conventions.md``):

* ``horizontal`` is the table (ground) acceleration along +x [m/s^2].
* ``vertical`` is the table acceleration, positive **upward** [m/s^2].

Between samples the accelerations vary linearly (Section 2.8 of the report).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .constants import G


def _as_float_array(name: str, values) -> np.ndarray:
    try:
        array = np.asarray(values, dtype=float)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name} must be an array of numbers: {error}") from None
    if array.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional, got shape {array.shape}")
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        raise ValueError(
            f"{name} contains {bad.size} non-finite value(s) (NaN or inf), "
            f"first at index {bad[0]}"
        )
    return array


@dataclass(frozen=True)
class Motion:
    """Ground (table) acceleration history, linear between samples.

    Parameters
    ----------
    t : array_like
        Sample times [s], strictly increasing.
    horizontal : array_like
        Horizontal ground acceleration [m/s^2], positive along +x.
    vertical : array_like, optional
        Vertical ground acceleration [m/s^2], positive upward. ``None`` means
        no vertical component (zeros).
    name : str, optional
        A label used in plots and summaries.
    rotation : array_like, optional
        Angular acceleration of the table (pitch) [rad/s^2], positive in the
        sense of positive theta. ``None`` means a table that does not rotate.
        Its other effects (tilt of gravity, vertical acceleration at the block's
        distance from the pitch axis) are folded into ``horizontal`` and
        ``vertical`` by :mod:`shaketable.table`.

    Notes
    -----
    The arrays are copied and made read-only: a motion never changes after it
    is built, and running a simulation never changes it.
    """

    t: np.ndarray
    horizontal: np.ndarray
    vertical: np.ndarray | None = None
    name: str = ""
    rotation: np.ndarray | None = None

    def __post_init__(self):
        t = _as_float_array("Motion.t", self.t)
        if t.size < 2:
            raise ValueError(f"Motion.t needs at least 2 samples, got {t.size}")
        steps = np.diff(t)
        if np.any(steps <= 0):
            index = int(np.flatnonzero(steps <= 0)[0])
            raise ValueError(
                "Motion.t must be strictly increasing; "
                f"t[{index + 1}] = {t[index + 1]!r} <= t[{index}] = {t[index]!r}"
            )
        horizontal = _as_float_array("Motion.horizontal", self.horizontal)
        if horizontal.size != t.size:
            raise ValueError(
                f"Motion.horizontal has {horizontal.size} samples but Motion.t has {t.size}"
            )
        vertical = None
        if self.vertical is not None:
            vertical = _as_float_array("Motion.vertical", self.vertical)
            if vertical.size != t.size:
                raise ValueError(
                    f"Motion.vertical has {vertical.size} samples but Motion.t has {t.size}"
                )
        rotation = None
        if self.rotation is not None:
            rotation = _as_float_array("Motion.rotation", self.rotation)
            if rotation.size != t.size:
                raise ValueError(
                    f"Motion.rotation has {rotation.size} samples but Motion.t has {t.size}"
                )
        for key, value in (("t", t), ("horizontal", horizontal), ("vertical", vertical),
                           ("rotation", rotation)):
            if value is not None:
                value.setflags(write=False)
            object.__setattr__(self, key, value)

    # ------------------------------------------------------------------ builders
    @classmethod
    def from_g(cls, t, horizontal_g, vertical_g=None, name: str = "") -> "Motion":
        """Build a motion from accelerations given in units of g.

        Parameters
        ----------
        t : array_like
            Sample times [s].
        horizontal_g : array_like
            Horizontal acceleration [g].
        vertical_g : array_like, optional
            Vertical acceleration, positive upward [g].
        """
        horizontal = np.asarray(horizontal_g, dtype=float) * G
        vertical = None if vertical_g is None else np.asarray(vertical_g, dtype=float) * G
        return cls(t, horizontal, vertical, name=name)

    @classmethod
    def uniform(cls, dt: float, horizontal, vertical=None, t0: float = 0.0,
                name: str = "") -> "Motion":
        """Build a motion sampled every ``dt`` seconds starting at ``t0``.

        Parameters
        ----------
        dt : float
            Sample interval [s], positive.
        horizontal : array_like
            Horizontal acceleration [m/s^2].
        vertical : array_like, optional
            Vertical acceleration, positive upward [m/s^2].
        """
        if not (np.isfinite(dt) and dt > 0):
            raise ValueError(f"dt must be a positive finite number of seconds, got {dt!r}")
        n = len(horizontal)
        return cls(t0 + dt * np.arange(n), horizontal, vertical, name=name)

    @classmethod
    def at_rest(cls, duration: float, dt: float = 0.005) -> "Motion":
        """A table at rest for ``duration`` seconds (free rocking)."""
        if not (np.isfinite(duration) and duration > 0):
            raise ValueError(f"duration must be positive [s], got {duration!r}")
        n = int(np.ceil(duration / dt - 1e-9)) + 1
        t = np.linspace(0.0, (n - 1) * dt, n)
        return cls(t, np.zeros(n), None, name="at rest")

    # ------------------------------------------------------------------ queries
    @property
    def vertical_or_zero(self) -> np.ndarray:
        """Vertical acceleration [m/s^2], zeros when the motion has none."""
        return self.vertical if self.vertical is not None else np.zeros_like(self.t)

    @property
    def rotation_or_zero(self) -> np.ndarray:
        """Table angular acceleration [rad/s^2], zeros when the table does not rotate."""
        return self.rotation if self.rotation is not None else np.zeros_like(self.t)

    @property
    def duration(self) -> float:
        """Time from first to last sample [s]."""
        return float(self.t[-1] - self.t[0])

    @property
    def dt(self) -> float:
        """Median sample interval [s]."""
        return float(np.median(np.diff(self.t)))

    @property
    def pga(self) -> float:
        """Peak absolute horizontal acceleration [m/s^2]."""
        return float(np.max(np.abs(self.horizontal)))

    def scaled(self, factor: float) -> "Motion":
        """Return a copy with both components multiplied by ``factor``."""
        vertical = None if self.vertical is None else self.vertical * factor
        rotation = None if self.rotation is None else self.rotation * factor
        return Motion(self.t, self.horizontal * factor, vertical, name=self.name,
                      rotation=rotation)

    def mirrored(self) -> "Motion":
        """Return the mirror image: horizontal and rotation reversed in sign."""
        rotation = None if self.rotation is None else -self.rotation
        return Motion(self.t, -self.horizontal, self.vertical, name=self.name,
                      rotation=rotation)

    def subdivided(self, parts: int) -> "Motion":
        """Insert ``parts - 1`` equally spaced samples in every interval.

        The report's BLOKROC subdivided each digitized interval into equal
        parts with a straight line between given points (Section 2.8); the
        linear interpolation here reproduces that exactly.
        """
        parts = int(parts)
        if parts < 1:
            raise ValueError(f"parts must be a positive integer, got {parts!r}")
        if parts == 1:
            return self
        fractions = np.arange(parts) / parts
        t = (self.t[:-1, None] + np.diff(self.t)[:, None] * fractions).ravel()
        t = np.append(t, self.t[-1])

        def resample(values):
            return None if values is None else np.interp(t, self.t, values)

        return Motion(t, resample(self.horizontal), resample(self.vertical),
                      name=self.name, rotation=resample(self.rotation))
