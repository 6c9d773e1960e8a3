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
  runs half a pitch cycle apart, over the record and before either becomes
  unstable.

Every run continues after the end of the record with the table at rest
(:func:`run_to_the_end`) until the block rests or overturns, so that each
verdict is final: a block still falling when the record stops is not counted
as standing.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.lab.pitch import Pitch
from shaketable.lab.stage import TableSetup, pitch_sampled, run_table
from shaketable.models.api import simulate
from shaketable.models.rocking.result import RockingResult
from shaketable.studies.comparison import TEST_THEORY_T_UNSTABLE

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.axes import Axes

    from shaketable.studies.comparison import Comparison

#: Free rocking added after the record, first try [s]. The 30 x 6 in block
#: released at half its block angle comes to rest in about 6 s (Fig. 3.4,
#: Section 3.7 (1)); a run not yet final is extended by doubling the tail.
TAIL = 10.0

#: Longest tail tried [s]; a run still rocking then is reported as not final.
MAX_TAIL = 80.0

#: Largest spread of the time of instability over the pitch phases for a
#: repeatable test [s]: the same excursion of the block, half a period of
#: the report's 2 Hz table motion, as for test vs theory.
REPEATABLE_T_UNSTABLE = TEST_THEORY_T_UNSTABLE

#: Largest relative spread (max / min - 1) of the peak theta/alpha of the runs
#: that stand, for a repeatable test [-]: the report's "about 10 %".
REPEATABLE_PEAK = 0.10

#: Horizontal level [g] of the earthquake-type case that rocks the block
#: substantially without always overturning it: the Fig. 3.5 substitute scaled
#: down, vertical kept at 0.4 times the horizontal (0.2 g / 0.5 g in Fig. 3.5).
#: On a 0.01 g grid from 0.20 to 0.50 g (24 pitch phases) the verdict depends
#: on the phase only from 0.25 to 0.29 g (below, the block barely rocks; above,
#: every phase overturns it), and some phase leaves the block standing after
#: rocking beyond half its block angle at 0.26, 0.27 and 0.29 g. 0.27 g lies
#: inside that window.
EARTHQUAKE_ROCKING_LEVEL = 0.27

#: Section 3.7 (2): what the report found for each kind of motion.
REPORT_FINDING = {"harmonic": "pitch effect small",
                  "earthquake-type": "not repeatable"}


def is_final(result: RockingResult) -> bool:
    """True when the run's verdict cannot change any more.

    The block overturned (or left the ground, outside the model), or it rests
    (theta = theta' = 0) at the end of a run whose table is at rest.
    """
    if result.status != "completed":
        return True
    return bool(result.theta[-1] == 0.0 and result.theta_dot[-1] == 0.0)


def run_to_the_end(block: Block, felt: Motion, *, cor: float, method: str = "fast",
                   tail: float = TAIL, max_tail: float = MAX_TAIL) -> RockingResult:
    """Run ``felt`` and continue with the table at rest until the block rests or overturns.

    :func:`shaketable.models.api` with ``duration`` longer than the record pads
    the motion (and the pitch's ``rotation``) with zeros: the table stops.

    Parameters
    ----------
    block : Block
    felt : Motion
        What the block feels [m/s^2].
    cor : float
        Coefficient of restitution [-].
    method : str
        Solver (:data:`shaketable.models.rocking.layout.METHODS`).
    tail : float
        First length of table at rest after the record [s], positive; doubled
        until the verdict is final (:func:`is_final`).
    max_tail : float
        Longest tail tried [s]; the run is returned as it is then.
    """
    if not (math.isfinite(tail) and tail > 0.0):
        raise ValueError(f"tail must be a positive time [s], got {tail!r}")
    record = float(felt.t[-1] - felt.t[0])
    while True:
        result = simulate(block, felt, cor=cor, duration=record + tail, method=method)
        if is_final(result) or tail >= max_tail:
            return result
        tail *= 2.0


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
        One per phase, continued past the record until final
        (:func:`run_to_the_end`).
    without_pitch : RockingResult
        The same motion on the same table without pitch.
    kind : str
        ``"harmonic"``, ``"earthquake-type"`` or ``""`` (not said): which
        finding of Section 3.7 (2) applies (:data:`REPORT_FINDING`).
    record_end : float
        End of the commanded record [s]; the runs continue after it.
    reference_spread : float or None
        The largest :meth:`spread` of the harmonic cases it is compared with
        (set by :func:`section_3_7_cases`).
    """

    name: str
    phases: np.ndarray
    runs: tuple[RockingResult, ...]
    without_pitch: RockingResult
    kind: str = ""
    record_end: float = math.inf
    reference_spread: float | None = None

    def to_frame(self) -> pd.DataFrame:
        """One row per phase: the scalar results of each run."""
        import pandas as pd

        return pd.DataFrame({
            "case": self.name,
            "pitch phase [rad]": self.phases,
            "overturned": [run.overturned for run in self.runs],
            "overturn direction": [run.overturn_direction for run in self.runs],
            "t unstable [s]": [run.t_unstable for run in self.runs],
            "max theta/alpha [-]": [run.max_theta_ratio for run in self.runs],
            "final": [is_final(run) for run in self.runs],
        })

    def pair_differences(self) -> np.ndarray:
        """RMS of theta/alpha differences between runs half the phases apart [-].

        Each pair (pitch phases pi apart) is compared on the common samples up
        to the end of the record and before either run's instability.
        """
        n = len(self.runs)
        values = []
        for k in range(n // 2):
            first, second = self.runs[k], self.runs[k + n // 2]
            end = min(_finite_or(first.t_unstable, math.inf),
                      _finite_or(second.t_unstable, math.inf), self.record_end)
            size = min(first.t.size, second.t.size)
            keep = first.t[:size] <= end
            if keep.sum() < 2:
                continue
            difference = (first.theta[:size][keep] - second.theta[:size][keep]) / first.block.alpha
            values.append(float(np.sqrt(np.mean(difference ** 2))))
        return np.asarray(values)

    def spread(self) -> float:
        """Median of :meth:`pair_differences` [-]: how visibly the runs differ (NaN if none)."""
        pairs = self.pair_differences()
        return float(np.median(pairs)) if pairs.size else math.nan

    def t_unstable_spread(self) -> float:
        """max - min of the time of instability over the runs that became unstable [s]."""
        times = np.array([run.t_unstable for run in self.runs], dtype=float)
        times = times[np.isfinite(times)]
        return float(times.max() - times.min()) if times.size else 0.0

    def repeatable(self) -> bool:
        """True when the pitch phase does not change the test visibly.

        Every run has the same verdict and the same directions of instability
        and of overturning; the times of instability lie within
        :data:`REPEATABLE_T_UNSTABLE`; the peaks of the runs that stand lie
        within :data:`REPEATABLE_PEAK`.
        """
        verdicts = {(run.overturned, run.unstable_direction, run.overturn_direction)
                    for run in self.runs}
        if len(verdicts) > 1:
            return False
        if self.t_unstable_spread() > REPEATABLE_T_UNSTABLE:
            return False
        peaks = np.array([run.max_theta_ratio for run in self.runs if not run.overturned])
        return not (peaks.size and peaks.min() > 0 and peaks.max() / peaks.min() - 1.0
                    > REPEATABLE_PEAK)

    def summary(self) -> dict[str, Any]:
        """The spread of the outcomes over the phases and the report's finding (JSON-ready)."""
        frame = self.to_frame()
        standing = frame.loc[~frame["overturned"], "max theta/alpha [-]"].to_numpy()
        unstable = frame["t unstable [s]"].to_numpy()
        unstable = unstable[np.isfinite(unstable)]
        reference = self.without_pitch
        spread = self.spread()
        summary = {
            "case": self.name,
            "phases": int(len(self.runs)),
            "verdicts final": int(frame["final"].sum()),
            "without pitch": ("F" if reference.overturned else
                              round(float(reference.max_theta_ratio), 3)),
            "overturned fraction": round(float(frame["overturned"].mean()), 3),
            "overturn directions": sorted({int(d) for d in frame["overturn direction"] if d}),
            "t unstable min [s]": _rounded(unstable.min()) if unstable.size else None,
            "t unstable max [s]": _rounded(unstable.max()) if unstable.size else None,
            "max theta/alpha min": _rounded(standing.min()) if standing.size else None,
            "max theta/alpha max": _rounded(standing.max()) if standing.size else None,
            "median RMS difference of theta/alpha between runs": (
                None if math.isnan(spread) else _rounded(spread)),
        }
        if self.reference_spread is not None and not math.isnan(spread):
            summary["spread / largest harmonic spread"] = round(
                spread / self.reference_spread, 2) if self.reference_spread > 0 else None
        if self.kind in REPORT_FINDING:
            reproduced = "pitch effect small" if self.repeatable() else "not repeatable"
            summary["report (Section 3.7 (2))"] = REPORT_FINDING[self.kind]
            summary["reproduced"] = reproduced
            summary["agrees"] = reproduced == REPORT_FINDING[self.kind]
        return summary

    def plot(self, ax: Axes | None = None) -> Axes:
        """theta/alpha of every phase (thin lines) and without pitch (black)."""
        from shaketable.plots.studies import plot_pitch_repeatability

        return plot_pitch_repeatability(self, ax=ax)


def pitch_repeatability(block: Block, motion: Motion, *, cor: float, phases: int = 24,
                        pitch: Pitch | None = None, name: str = "",
                        method: str = "fast", setup: TableSetup | None = None,
                        kind: str = "", tail: float = TAIL) -> RepeatabilityResult:
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
        The pitch (default: ``setup``'s, else ``Pitch()``: 12 Hz, 0.22 rad/s^2,
        Section 3.7 (2)); its phase is replaced by each of the phases.
    name : str
        Label of the case.
    method : str
        Solver.
    setup : TableSetup, optional
        The table between command and block (e.g. ``command=True``, as in the
        scenes of Figs. 3.7-3.9); default: pitch only.
    kind : str
        ``"harmonic"``, ``"earthquake-type"`` or ``""`` (see
        :class:`RepeatabilityResult`).
    tail : float
        First length of table at rest after the record [s]
        (:func:`run_to_the_end`).
    """
    if isinstance(phases, bool) or not isinstance(phases, int) or phases < 2:
        raise ValueError(f"phases must be an integer of at least 2, got {phases!r}")
    if kind not in ("", *REPORT_FINDING):
        raise ValueError(f"kind must be one of {', '.join(REPORT_FINDING)} or '', got {kind!r}")
    setup = TableSetup() if setup is None else setup
    if pitch is None:
        pitch = setup.pitch if setup.pitch is not None else Pitch()
    setup = replace(setup, pitch=pitch)
    values = np.linspace(0.0, 2.0 * math.pi, phases, endpoint=False)
    runs = []
    for phase in values:
        felt = _felt(motion, setup.with_pitch_phase(phase))
        runs.append(run_to_the_end(block, felt, cor=cor, method=method, tail=tail))
    # the reference: the same table without pitch, on the same (finer) time grid
    plain = pitch_sampled(_felt(motion, replace(setup, pitch=None)), pitch)
    without = run_to_the_end(block, plain, cor=cor, method=method, tail=tail)
    return RepeatabilityResult(name or motion.name, values, tuple(runs), without, kind=kind,
                               record_end=float(motion.t[-1]))


def _felt(motion: Motion, setup: TableSetup) -> Motion:
    """What the block feels on ``setup`` for ``motion`` [m/s^2] (a motion is commanded, so
    :func:`~shaketable.lab.stage.run_table` always gives one)."""
    felt = run_table(motion, setup).felt
    assert felt is not None, "run_table gives a felt motion for a commanded motion"
    return felt


def largest_spread(cases: Sequence[RepeatabilityResult]) -> float:
    """The largest spread of ``cases`` (NaN ones, with no usable pair of runs, ignored).

    Raises
    ------
    ValueError
        When no case has a spread, naming the cases.
    """
    spreads = np.array([case.spread() for case in cases], dtype=float)
    if not np.isfinite(spreads).any():
        raise ValueError("no spread to compare with: every run of "
                         f"{', '.join(case.name for case in cases) or 'no case'} lacks a "
                         "usable pair of phases")
    return float(np.nanmax(spreads))


def section_3_7_contrast(cases: Sequence[RepeatabilityResult]) -> list[Comparison]:
    """The report's contrast of Section 3.7 (2) as "report vs reproduced" lines.

    One line per earthquake-type case: is the spread of the harmonic tests
    (the largest of them, :meth:`RepeatabilityResult.spread`) smaller than
    that earthquake-type case's? The report's answer is yes ("the effect of
    the pitch was relatively small" for the 2 Hz tests; the earthquake test
    "was not repeatable").

    Returns
    -------
    list of shaketable.scenes.compare.Comparison
    """
    from shaketable.studies.comparison import Comparison

    harmonic = [case for case in cases if case.kind == "harmonic"]
    if not harmonic:
        raise ValueError("section_3_7_contrast needs at least one case of kind 'harmonic'")
    largest = largest_spread(harmonic)
    lines = []
    for case in cases:
        if case.kind != "earthquake-type":
            continue
        spread = case.spread()
        lines.append(Comparison(
            f"spread over pitch phases (median RMS Δθ/α): harmonic < {case.name}", True,
            f"{largest:.3f} < {spread:.3f}" if largest < spread else
            f"{largest:.3f} ≥ {spread:.3f}", "-", largest < spread))
    return lines


def _finite_or(value: float | None, default: float) -> float:
    return value if value is not None and math.isfinite(value) else default


def _rounded(value: float, digits: int = 3) -> float:
    return round(float(value), digits)
