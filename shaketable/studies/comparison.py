"""Report-vs-reproduced lines and the test-vs-theory criteria shared by studies and scenes."""

from __future__ import annotations

from dataclasses import dataclass


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
    """

    quantity: str
    report: object
    reproduced: object
    unit: str
    agrees: bool

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
