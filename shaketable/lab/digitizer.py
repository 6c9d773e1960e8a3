"""The acquisition: anti-alias filter, sampler and ADC (report Sections 3.5-3.6: 50
samples/s).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import scipy.signal

from shaketable.core.constants import G
from shaketable.core.validation import integer, nonnegative, positive
from shaketable.core.validation import number as _number


@dataclass(frozen=True)
class Digitizer:
    """Anti-alias filter, sampler and analog-to-digital converter.

    Parameters
    ----------
    rate : float
        Samples per second [1/s] (report: 50 for the block records, Sections
        3.5-3.6; the table system ran at 100, Section 3.4).
    anti_alias : bool
        Apply the anti-alias filter before sampling.
    cutoff : float, optional
        -3 dB frequency of the anti-alias filter [Hz], below rate / 2
        (default 0.4 x rate: 20 Hz at 50 samples/s).
    filter_order : int
        Poles of the causal Butterworth low-pass (default 4: -24 dB/octave;
        gain 0.19 at 1.5 x cutoff, 0.025 at 2.5 x cutoff).
    bits : int
        ADC resolution [bits]; 0 means no quantisation.
    displacement_full_scale : float, optional
        ADC full scale of the potentiometer channel, +-value [m] (default: the
        potentiometer's stroke).
    acceleration_full_scale : float
        ADC full scale of the acceleration channels, +-value [m/s^2]
        (default 2 g).
    noise : float
        ADC noise [LSB rms], white at the samples (default 0.5).
    oversample : int
        Fine-grid points per sample on which the continuous signals and the
        filter are computed (default 8).
    start, end : float, optional
        Times of the first and last sample [s]. Default: the start and end of
        the motion. A record may begin before the run: the block is then held
        at its initial rotation and the table is at rest (a free-rocking test
        recorded before the release).
    """

    rate: float = 50.0
    anti_alias: bool = True
    cutoff: float | None = None
    filter_order: int = 4
    bits: int = 12
    displacement_full_scale: float | None = None
    acceleration_full_scale: float = 2.0 * G
    noise: float = 0.5
    oversample: int = 8
    start: float | None = None
    end: float | None = None

    def __post_init__(self):
        rate = positive("rate", self.rate, " [samples/s]")
        object.__setattr__(self, "rate", rate)
        if not isinstance(self.anti_alias, (bool, np.bool_)):
            raise ValueError(f"anti_alias must be True or False, got {self.anti_alias!r}")
        cutoff = 0.4 * rate if self.cutoff is None else positive("cutoff", self.cutoff, " [Hz]")
        if cutoff >= 0.5 * rate:
            raise ValueError(f"cutoff ({cutoff!r} Hz) must be below the Nyquist frequency "
                             f"{0.5 * rate:g} Hz of rate {rate:g} samples/s")
        object.__setattr__(self, "cutoff", cutoff)
        object.__setattr__(self, "filter_order", integer("filter_order", self.filter_order, 1, 8))
        object.__setattr__(self, "bits", integer("bits", self.bits, 0, 24))
        if self.displacement_full_scale is not None:
            object.__setattr__(self, "displacement_full_scale",
                               positive("displacement_full_scale",
                                         self.displacement_full_scale, " [m]"))
        object.__setattr__(self, "acceleration_full_scale",
                           positive("acceleration_full_scale", self.acceleration_full_scale, " [m/s^2]"))
        object.__setattr__(self, "noise", nonnegative("noise", self.noise, " [LSB]"))
        object.__setattr__(self, "oversample", integer("oversample", self.oversample, 2, 64))
        for key in ("start", "end"):
            value = getattr(self, key)
            if value is not None:
                object.__setattr__(self, key, _number(key, value))
        if self.start is not None and self.end is not None and self.end <= self.start:
            raise ValueError(f"end ({self.end!r} s) must be after start ({self.start!r} s)")

    @property
    def dt(self) -> float:
        """Sample interval 1 / rate [s]."""
        return 1.0 / self.rate

    @property
    def cutoff_frequency(self) -> float:
        """Cutoff of the anti-alias filter [Hz]: ``cutoff``, whose default 0.4 x ``rate`` is
        filled in when the digitizer is made (so never None)."""
        if self.cutoff is None:   # only if __post_init__ was bypassed
            raise ValueError("Digitizer.cutoff is not set")
        return self.cutoff

    def filter_sos(self, fine_rate: float | None = None) -> np.ndarray:
        """Second-order sections of the anti-alias filter on the fine grid.

        A Butterworth low-pass designed by the bilinear transform (with the
        cutoff pre-warped by ``scipy.signal.butter``) at ``fine_rate``
        (default ``oversample x rate``) samples/s: the discrete stand-in for
        the analog filter of the acquisition system.
        """
        fine_rate = self.rate * self.oversample if fine_rate is None else fine_rate
        return scipy.signal.butter(self.filter_order, self.cutoff, btype="low", fs=fine_rate,
                                   output="sos")

    def gain(self, frequency: npt.ArrayLike) -> np.ndarray:
        """|H(f)| of the anti-alias filter [-] at ``frequency`` [Hz] (1 without filter)."""
        frequency = np.atleast_1d(np.asarray(frequency, dtype=float))
        if not self.anti_alias:
            return np.ones_like(frequency)
        _, response = scipy.signal.sosfreqz(self.filter_sos(), worN=frequency,
                                            fs=self.rate * self.oversample)
        return np.abs(response)

    def apply_filter(self, values: np.ndarray, initial_value: float | None = None) -> np.ndarray:
        """The anti-alias filter applied to fine-grid ``values``.

        The filter starts at rest on ``initial_value`` (default ``values[0]``):
        the steady state of a signal that was constant before the record.
        """
        if not self.anti_alias:
            return np.asarray(values, dtype=float)
        sos = self.filter_sos()
        start = values[0] if initial_value is None else initial_value
        initial = scipy.signal.sosfilt_zi(sos) * start
        filtered, _ = scipy.signal.sosfilt(sos, values, zi=initial)
        return filtered

    def noise_gain(self) -> float:
        """RMS of the filter's output for unit-RMS white fine-grid noise [-]."""
        if not self.anti_alias:
            return 1.0
        impulse = np.zeros(64 * self.oversample * 8)
        impulse[0] = 1.0
        response = scipy.signal.sosfilt(self.filter_sos(), impulse)
        return float(np.sqrt(np.sum(response**2)))

    def lsb(self, full_scale: float) -> float:
        """One ADC step [unit of full scale] for a +-``full_scale`` channel (0 if bits = 0)."""
        return 0.0 if self.bits == 0 else 2.0 * full_scale / 2**self.bits


def digitize(fine: np.ndarray, digitizer: Digitizer, full_scale: float, rng: np.random.Generator,
             sensor_noise: float, sensor_range: float | None) -> tuple[np.ndarray, np.ndarray]:
    """Sensor noise, sensor range, filter, sampling, ADC. Returns (samples, clipped)."""
    values = fine.copy()
    # the signal was steady before the record: start the filter on its noise-free value
    initial_value = float(fine[0]) if sensor_range is None else float(
        np.clip(fine[0], -sensor_range, sensor_range))
    if sensor_noise > 0.0:
        values += rng.standard_normal(values.size) * (sensor_noise / digitizer.noise_gain())
    clipped_fine = np.zeros(values.size, dtype=bool)
    if sensor_range is not None:
        clipped_fine = np.abs(values) >= sensor_range
        values = np.clip(values, -sensor_range, sensor_range)
    values = digitizer.apply_filter(values, initial_value)
    step = digitizer.oversample
    samples = values[::step].copy()
    clipped = clipped_fine[::step].copy()
    lsb = digitizer.lsb(full_scale)
    if digitizer.noise > 0.0 and lsb > 0.0:
        samples += rng.standard_normal(samples.size) * digitizer.noise * lsb
    if lsb > 0.0:
        samples = np.round(samples / lsb) * lsb
    saturated = np.abs(samples) >= full_scale
    samples = np.clip(samples, -full_scale, full_scale)
    return samples, clipped | saturated
