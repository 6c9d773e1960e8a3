"""Report-vs-reproduced lines and the test-vs-theory criteria shared by studies and scenes."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Comparison:
    """One "report value vs reproduced value" line.

    Attributes
    ----------
    quantity : str
    report : object
        The report's value (with its unit in ``unit``).
    reproduced : object
    unit : str
    agrees : bool
        Within the stated tolerance (the report's own ~10 % unless the scene
        says otherwise, :func:`scene_tolerances`), the same verdict for yes/no
        quantities, or the criterion met for a test-vs-theory line
        (:func:`compare_test_with_theory`).
    key : str
        The scene's ``[report]`` key compared (e.g. ``"t_unstable"``), empty for
        lines that are not one of the report's values.
    """

    quantity: str
    report: object
    reproduced: object
    unit: str
    agrees: bool
    key: str = ""

    def __post_init__(self):
        object.__setattr__(self, "agrees", bool(self.agrees))


#: Default largest |t_unstable(test) - t_unstable(theory)| [s] for "unstable at about the
#: same point" (Section 3.7 (2)): half a period of the report's 2 Hz table motion, i.e. the
#: block becomes unstable on the same excursion (each half cycle of the table pushes it
#: one way). A scene may state its own as ``tolerance = { test_theory_t_unstable = "..." }``.
TEST_THEORY_T_UNSTABLE = 0.25


#: Default half-width of the band of the peak ratio test/theory around 1 [-]: the report's
#: "about 10 %" agreement. A scene may state ``tolerance = { test_theory_peak_ratio = ... }``.
TEST_THEORY_PEAK_RATIO = 0.10


#: The three kinds of comparison of the reproduction report, in the order its headline
#: gives them: against the report's own inputs (recorded earthquakes, harmonic and free
#: rocking, closed forms), against the package's SUBSTITUTE accelerograms (the report's
#: artificial records are not available: not expected to match), and values that match
#: by construction (a realisation chosen to match, Fig. 4.15).
COMPARISON_KINDS = ("report inputs", "substitute", "by construction")


@dataclass
class ComparisonTally:
    """Agreeing and differing comparisons of the reproduction report, counted by kind.

    Every "yes"/"no" line of the report is counted once, in one kind of
    :data:`COMPARISON_KINDS`.

    Attributes
    ----------
    counts : dict of str to list of int
        ``{kind: [agree, differ]}``.
    differing : list of (str, str)
        ``(kind, what)`` of each differing comparison counted with a description (the
        report's list of the comparisons that differ).
    """

    counts: dict = field(default_factory=lambda: {kind: [0, 0] for kind in COMPARISON_KINDS})
    differing: list = field(default_factory=list)

    def add(self, kind: str, agrees: bool, number: int = 1, what: str | None = None) -> None:
        """Count ``number`` comparisons of ``kind`` that agree (or differ); ``what``
        describes a differing one (kept in :attr:`differing`)."""
        if kind not in self.counts:
            raise ValueError(f"kind must be one of {', '.join(COMPARISON_KINDS)}, got {kind!r}")
        self.counts[kind][0 if agrees else 1] += int(number)
        if not agrees and what is not None:
            self.differing.append((kind, what))

    def add_many(self, kind: str, agreeing: int, total: int,
                 differing: list | None = None) -> None:
        """Count ``total`` comparisons of ``kind`` of which ``agreeing`` agree;
        ``differing`` describes the others (one text each)."""
        self.add(kind, True, agreeing)
        self.add(kind, False, total - agreeing)
        if differing is not None:
            if len(differing) != total - agreeing:
                raise ValueError(f"{len(differing)} descriptions for {total - agreeing} "
                                 "differing comparisons")
            self.differing.extend((kind, what) for what in differing)

    def console_line(self) -> str:
        """The counts in one line for a command's first line, the report's own inputs
        first and the other kinds apart: ``"against the report's own inputs 29 agree, 1
        differs; against SUBSTITUTE accelerograms (not expected to match) 15 agree, 3
        differ"``; "" when nothing was compared."""
        def counted(agree: int, differ: int) -> str:
            return f"{agree} agree{'s' if agree == 1 else ''}, {differ} differ{'s' if differ == 1 else ''}"
        words = {"report inputs": "against the report's own inputs",
                 "substitute": "against SUBSTITUTE accelerograms (not expected to match)",
                 "by construction": "by construction (not evidence)"}
        parts = [f"{words[kind]} {counted(*self.counts[kind])}" for kind in COMPARISON_KINDS
                 if sum(self.counts[kind]) or kind == "report inputs"]
        return "; ".join(parts) if any(sum(pair) for pair in self.counts.values()) else ""

    def headline(self) -> list[str]:
        """The report's headline: one bold line for the report's own inputs and one for each
        other kind the sections compared values of (one line saying so when the sections
        compare no value with the report's)."""
        if not any(sum(pair) for pair in self.counts.values()):
            return ["**These sections compare no value with the report's (figures and studies "
                    "without a number of the report to check).**"]
        agree, differ = self.counts["report inputs"]
        lines = [f"**Against the report's own inputs (recorded earthquakes, harmonic and free "
                 f"rocking, closed forms): {agree} comparisons agree, {differ} differ.**"]
        # the other kinds only where the sections compared values of theirs
        agree, differ = self.counts["substitute"]
        if agree + differ:
            lines.append(f"**Against SUBSTITUTE accelerograms (the report's artificial records "
                         f"are not available; not expected to match): {agree} agree, {differ} "
                         "differ.**")
        agree, differ = self.counts["by construction"]
        if agree + differ:
            lines.append(f"**By construction (a substitute realisation chosen among 200 to "
                         f"match, Fig. 4.15; not evidence): {agree} agree, {differ} differ.**")
        return lines
