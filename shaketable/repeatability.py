"""Repeatability of a table test under the table's pitch (Section 3.7 (2)).

The report could not repeat its earthquake tests: "the response of the block
was not repeatable using the same horizontal and vertical command
displacements because the pitch of the shaking table was different in each
case", while under 2 Hz harmonic motion "the effect of the pitch was
relatively small". Here the same commanded motion is run on a table pitching
with ``phases`` different phases (everything else equal) and the spread of
the outcomes is measured:

* the fraction of runs that overturn, and their overturning directions;
* the spread of the time of instability (|theta| first above alpha);
* the spread of max |theta| / alpha among the runs that do not overturn;
* how *visibly* two runs differ: the RMS difference of theta/alpha between
  runs half a pitch cycle apart, before either becomes unstable.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .geometry import Block
from .motion import Motion
from .simulate import simulate
from .table import Pitch
from .table_stage import TableSetup, run_table


@dataclass(frozen=True)
class RepeatabilityResult:
    """Runs of one commanded motion on a table pitching with different phases.

    Attributes
    ----------
    name : str
        Label of the case.
    phases : ndarray
        Pitch phases [rad].
    runs : tuple of RockingResult
        One per phase.
    without_pitch : RockingResult
        The same motion on a table that does not pitch.
    """

    name: str
    phases: np.ndarray
    runs: tuple
    without_pitch: object

    def to_frame(self):
        """One row per phase: the scalar results of each run."""
        import pandas as pd

        return pd.DataFrame({
            "case": self.name,
            "pitch phase [rad]": self.phases,
            "overturned": [run.overturned for run in self.runs],
            "overturn direction": [run.overturn_direction for run in self.runs],
            "t unstable [s]": [run.t_unstable for run in self.runs],
            "max theta/alpha [-]": [run.max_theta_ratio for run in self.runs],
        })

    def pair_differences(self) -> np.ndarray:
        """RMS of theta/alpha differences between runs half the phases apart [-].

        Each pair is compared on the common samples before either run's
        instability (all samples if neither becomes unstable).
        """
        n = len(self.runs)
        values = []
        for k in range(n // 2):
            first, second = self.runs[k], self.runs[k + n // 2]
            end = min(_finite_or(first.t_unstable, math.inf), _finite_or(second.t_unstable,
                                                                            math.inf))
            t = first.t
            size = min(first.t.size, second.t.size)
            keep = t[:size] <= end
            if keep.sum() < 2:
                continue
            difference = (first.theta[:size][keep] - second.theta[:size][keep]) / first.block.alpha
            values.append(float(np.sqrt(np.mean(difference ** 2))))
        return np.asarray(values)

    def summary(self) -> dict:
        """The spread of the outcomes over the phases (JSON-ready)."""
        frame = self.to_frame()
        standing = frame.loc[~frame["overturned"], "max theta/alpha [-]"].to_numpy()
        unstable = frame["t unstable [s]"].to_numpy()
        unstable = unstable[np.isfinite(unstable)]
        pairs = self.pair_differences()
        reference = self.without_pitch
        return {
            "case": self.name,
            "phases": int(len(self.runs)),
            "without pitch": ("F" if reference.overturned else
                              round(float(reference.max_theta_ratio), 3)),
            "overturned fraction": float(frame["overturned"].mean()),
            "overturn directions": sorted({int(d) for d in frame["overturn direction"] if d}),
            "t unstable min [s]": _rounded(unstable.min()) if unstable.size else None,
            "t unstable max [s]": _rounded(unstable.max()) if unstable.size else None,
            "max theta/alpha min": _rounded(standing.min()) if standing.size else None,
            "max theta/alpha max": _rounded(standing.max()) if standing.size else None,
            "median RMS difference of theta/alpha between runs": (
                _rounded(np.median(pairs)) if pairs.size else None),
        }

    def plot(self, ax=None):
        """theta/alpha of every phase (thin lines) and without pitch (black)."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(8, 3))
        alpha = self.without_pitch.block.alpha
        for run in self.runs:
            ax.plot(run.t, run.theta / alpha, lw=0.5, alpha=0.6)
        ax.plot(self.without_pitch.t, self.without_pitch.theta / alpha, color="k", lw=1.2,
                label="no pitch")
        for level in (-1, 1):
            ax.axhline(level, color="0.4", ls="--", lw=0.8)
        ax.set_ylim(-2.0, 2.0)
        ax.set_ylabel("θ/α [-]")
        ax.set_xlabel("time [s]")
        summary = self.summary()
        ax.set_title(f"{self.name}: {len(self.runs)} pitch phases, "
                     f"{100 * summary['overturned fraction']:.0f} % overturn", fontsize=9)
        ax.legend(loc="upper left", fontsize=7, frameon=False)
        return ax


def pitch_repeatability(block: Block, motion: Motion, *, cor: float, phases: int = 24,
                        pitch: Pitch | None = None, name: str = "",
                        method: str = "fast") -> RepeatabilityResult:
    """Run ``motion`` on a table pitching with ``phases`` equally spaced phases.

    Parameters
    ----------
    block : Block
    motion : Motion
        The commanded table accelerations [m/s^2].
    cor : float
        Coefficient of restitution [-].
    phases : int
        Number of pitch phases in [0, 2 pi), at least 2.
    pitch : Pitch, optional
        The pitch (default ``Pitch()``: 12 Hz, 0.22 rad/s^2, Section 3.7 (2));
        its phase is replaced by each of the phases.
    name : str
        Label of the case.
    """
    if isinstance(phases, bool) or not isinstance(phases, int) or phases < 2:
        raise ValueError(f"phases must be an integer of at least 2, got {phases!r}")
    pitch = Pitch() if pitch is None else pitch
    setup = TableSetup(pitch=pitch)
    values = np.linspace(0.0, 2.0 * math.pi, phases, endpoint=False)
    runs = []
    for phase in values:
        felt = run_table(motion, setup.with_pitch_phase(phase)).felt
        runs.append(simulate(block, felt, cor=cor, method=method))
    # the reference on the same (finer) time grid as the pitched runs
    plain = run_table(motion, setup).felt
    plain = Motion(plain.t, np.interp(plain.t, motion.t, motion.horizontal),
                   None if motion.vertical is None else np.interp(plain.t, motion.t,
                                                                  motion.vertical),
                   name=motion.name)
    without = simulate(block, plain, cor=cor, method=method)
    return RepeatabilityResult(name or motion.name, values, tuple(runs), without)


def section_3_7_cases(phases: int = 24) -> list[RepeatabilityResult]:
    """The report's harmonic tests (Figs. 3.7-3.9) and earthquake-type motions, 30 x 6 in block.

    The earthquake-type motions are the package's ``olive-view`` SUBSTITUTE
    (the report's table records are not available) at 0.25 g and 0.5 g
    horizontal with a vertical of 0.4 times that, the latter as in Fig. 3.5.
    """
    from .motions import artificial, harmonic

    block = Block.parse("30x6in")
    cases = [
        ("Fig. 3.7: 2 Hz, 0.5 g H", harmonic(2.0, 0.5, duration=10.0, dt=0.01)),
        ("Fig. 3.8: 2 Hz, 0.38 g H + 0.33 g V", harmonic(2.0, 0.38, 0.33, duration=10.0,
                                                          dt=0.01)),
        ("Fig. 3.9: 2 Hz, 0.45 g H + 0.26 g V", harmonic(2.0, 0.45, 0.26, duration=10.0,
                                                          dt=0.01)),
        ("earthquake-type 0.25 g H + 0.1 g V (substitute)",
         artificial("olive-view", seed=3, pga_g=0.25, vertical_pga_g=0.1)),
        ("Fig. 3.5: earthquake-type 0.5 g H + 0.2 g V (substitute)",
         artificial("olive-view", seed=3, pga_g=0.5, vertical_pga_g=0.2)),
    ]
    return [pitch_repeatability(block, motion, cor=0.925, phases=phases, name=label)
            for label, motion in cases]


def _finite_or(value, default):
    return value if value is not None and math.isfinite(value) else default


def _rounded(value, digits=3):
    return round(float(value), digits)
