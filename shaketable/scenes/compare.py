"""Report against reproduction: the tolerances a scene states, the report's values compared
with a run, and the test-vs-theory criteria of Section 3.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from shaketable.core.validation import unknown_keys
from shaketable.models.rocking.result import RockingResult
from shaketable.scenes.parse import Scene, SceneError
from shaketable.studies.comparison import (
    TEST_THEORY_PEAK_RATIO,
    TEST_THEORY_T_UNSTABLE,
    Comparison,
)

if TYPE_CHECKING:
    from shaketable.scenes.virtual_test import VirtualTestResult

#: Motion kinds that are earthquake accelerograms. For these the report shows test data
#: only (Fig. 3.5, "TEST DATA") and states that test and theory did not agree as well as
#: under harmonic motion: "Comparisons of test and theoretical results for earthquake-type
#: ground motions are not given, as these did not show the same level of agreement"
#: (Section 3.7 (2)).
EARTHQUAKE_KINDS = frozenset({"artificial", "record"})


#: Default relative tolerance of a report value [-] (the report's "about 10 %").
REPORT_TOLERANCE = 0.10

#: Keys of a per-quantity ``[report] tolerance = {...}`` table and what each accepts.
#: ``"time"``: a relative number or an absolute time with its unit ("0.5 s"); ``"number"`` a
#: relative number; ``"band"`` the half-width of a band around 1; ``"absolute time"`` a time
#: with its unit only.
TOLERANCE_KEYS = {"t_rest": "time", "t_unstable": "time", "t_overturn": "time",
                  "cycles": "number", "max_theta_ratio": "number",
                  "test_theory_t_unstable": "absolute time", "test_theory_peak_ratio": "band"}


def is_earthquake(scene: Scene) -> bool:
    """True when the scene's table motion is an earthquake accelerogram (:data:`EARTHQUAKE_KINDS`)."""
    return scene.motion.get("kind") in EARTHQUAKE_KINDS


@dataclass(frozen=True)
class Tolerance:
    """How close a reproduced value must be to the report's.

    Attributes
    ----------
    value : float
        Relative tolerance [-] when ``absolute`` is False, else the absolute
        tolerance in SI units (seconds for times).
    absolute : bool
    """

    value: float
    absolute: bool = False

    def accepts(self, reproduced: float, expected: float) -> bool:
        """``|reproduced - expected|`` within the tolerance."""
        if self.absolute:
            return abs(reproduced - expected) <= self.value + 1e-12
        return _close(reproduced, expected, self.value)

    def describe(self, unit: str = "") -> str:
        """E.g. ``"±10 %"`` or ``"±0.5 s"``."""
        if self.absolute:
            return f"±{self.value:g} {unit}".rstrip()
        return f"±{100 * self.value:g} %"


def scene_tolerances(scene: Scene) -> dict[str, Tolerance]:
    """The tolerance of every quantity of :data:`TOLERANCE_KEYS` for ``scene``.

    ``[report] tolerance`` is either one relative number for every report value
    (``tolerance = 0.15``) or a table per quantity that says how the report gives
    each number, e.g. ``tolerance = { t_overturn = "0.5 s" }`` for "after about
    4 seconds" (a time stated to the nearest second). Quantities not named keep
    :data:`REPORT_TOLERANCE`, :data:`TEST_THEORY_T_UNSTABLE` and
    :data:`TEST_THEORY_PEAK_RATIO`.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    dict of str to Tolerance
        One per key of :data:`TOLERANCE_KEYS`; times in seconds.

    Raises
    ------
    SceneError
        An unknown key or a value of the wrong kind, naming the file and the key.
    """
    from shaketable.core.units import parse

    given = scene.report.get("tolerance", REPORT_TOLERANCE)
    where = f"{scene.path}: report.tolerance"
    common = REPORT_TOLERANCE
    table: dict[str, object] = {}
    if isinstance(given, dict):
        table = given
    elif isinstance(given, bool) or not isinstance(given, (int, float)) or not 0 <= given:
        raise SceneError(f"{where} must be a non-negative relative tolerance such as 0.1 or a "
                         f"table such as {{ t_overturn = '0.5 s' }}, got {given!r}")
    else:
        common = float(given)
    unknown = unknown_keys(table, TOLERANCE_KEYS)
    if unknown:
        raise SceneError(f"{where}: unknown key {unknown[0]!r}; expected one of "
                         f"{', '.join(sorted(TOLERANCE_KEYS))}")
    tolerances = {key: Tolerance(common) for key, kind in TOLERANCE_KEYS.items()
                  if kind in ("time", "number")}
    tolerances["test_theory_t_unstable"] = Tolerance(TEST_THEORY_T_UNSTABLE, absolute=True)
    tolerances["test_theory_peak_ratio"] = Tolerance(TEST_THEORY_PEAK_RATIO)
    for key, value in table.items():
        kind = TOLERANCE_KEYS[key]
        if isinstance(value, str) and kind in ("time", "absolute time"):
            tolerances[key] = Tolerance(parse(value, "time", where=f"{where}.{key}"),
                                        absolute=True)
        elif (kind != "absolute time" and not isinstance(value, bool)
              and isinstance(value, (int, float)) and value >= 0):
            tolerances[key] = Tolerance(float(value))
        else:
            expected = {"time": "a relative number such as 0.1 or a time such as '0.5 s'",
                        "number": "a relative number such as 0.1",
                        "band": "the half-width of a band around 1, such as 0.1",
                        "absolute time": "a time with its unit such as '0.25 s'"}[kind]
            raise SceneError(f"{where}.{key} must be {expected}, got {value!r}")
    return tolerances


def compare_with_report(scene: Scene, result: RockingResult) -> list[Comparison]:
    """The scene's ``[report]`` values against one run.

    Each value is judged with its tolerance from :func:`scene_tolerances`,
    shown in the quantity's label.

    Parameters
    ----------
    scene : Scene
    result : RockingResult
        The run the report's values describe (the theory run of a virtual test,
        or its test run for earthquake-type motions, see :func:`run_scene`).
    """
    from shaketable.core.units import parse

    report = scene.report
    tolerances = scene_tolerances(scene)
    lines: list[Comparison] = []
    for key, value in report.items():
        if key in ("tolerance", "note", "by_construction"):
            continue
        before = len(lines)
        if key == "overturned":
            lines.append(Comparison("overturns", bool(value), result.overturned, "",
                                    bool(value) == result.overturned))
        elif key == "overturn_direction":
            lines.append(Comparison("overturn direction", int(value), result.overturn_direction,
                                    "sign of θ", int(value) == result.overturn_direction))
        elif key == "max_theta_ratio":
            tolerance = tolerances[key]
            label = f"max θ/α ({tolerance.describe()})"
            if result.overturned:
                lines.append(Comparison(label, float(value), "F (overturns)", "-", False))
                continue
            reproduced = round(result.max_theta_ratio, 3)
            lines.append(Comparison(label, float(value), reproduced, "-",
                                    tolerance.accepts(reproduced, float(value))))
        elif key == "cycles":
            tolerance = tolerances[key]
            reproduced = _visible_cycles(result)
            lines.append(Comparison(f"cycles to rest ({tolerance.describe()})", float(value),
                                    reproduced, "-", tolerance.accepts(reproduced, float(value))))
        else:  # times
            tolerance = tolerances[key]
            expected = parse(value, "time", where=f"{scene.path}: report.{key}")
            run_time = getattr(result, key)
            reproduced_time = None if run_time is None or not math.isfinite(run_time) else \
                round(float(run_time), 3)
            lines.append(Comparison(f"{key.replace('_', ' ')} ({tolerance.describe('s')})",
                                    expected, reproduced_time, "s",
                                    reproduced_time is not None and
                                    tolerance.accepts(reproduced_time, expected)))
        lines[before:] = [replace(line, key=key) for line in lines[before:]]
    return lines


def compare_test_with_theory(scene: Scene, test: VirtualTestResult) -> list[Comparison]:
    """The virtual test against its theory run, as Section 3.7 (2) compares them.

    For free rocking and harmonic motion (Figs. 3.4, 3.7-3.9) the report states
    that test and theory agree: "the block becomes unstable at about the same
    point ... and overturning is in the same direction". Four lines score that:
    the same overturning verdict; the same direction of instability (sign of
    theta when |theta| first exceeds alpha, 0 when never); the difference
    |t_unstable(test) - t_unstable(theory)| within ``test_theory_t_unstable`` (default
    :data:`TEST_THEORY_T_UNSTABLE`); the peak ratio test/theory (each curve
    up to its own instability, :meth:`shaketable.scenes.virtual_test.VirtualTestResult.metrics`)
    within 1 +- ``test_theory_peak_ratio`` (default :data:`TEST_THEORY_PEAK_RATIO`).

    For earthquake-type motions (:data:`EARTHQUAKE_KINDS`) the report states the
    opposite: they "did not show the same level of agreement". One line then
    asks whether the four criteria all hold; the report's answer is *no*.

    Parameters
    ----------
    scene : Scene
    test : VirtualTestResult
        One virtual test (:func:`shaketable.scenes.virtual_test.run_virtual_test`).
    """
    metrics = test.metrics()
    tolerances = scene_tolerances(scene)
    window = tolerances["test_theory_t_unstable"].value
    band = tolerances["test_theory_peak_ratio"].value
    same_verdict = metrics["overturned test"] == metrics["overturned theory"]
    same_direction = metrics["direction test"] == metrics["direction theory"]
    t_test, t_theory = metrics["t unstable test [s]"], metrics["t unstable theory [s]"]
    if t_test is None and t_theory is None:
        delta, close_in_time = "never unstable", True
    elif t_test is None or t_theory is None:
        delta, close_in_time = f"test {_text(t_test)}, theory {_text(t_theory)}", False
    else:
        difference = abs(t_test - t_theory)
        delta, close_in_time = f"{difference:.3g} s", difference <= window + 1e-9
    ratio = metrics["peak ratio test/theory"]
    ratio_in_band = ratio is not None and abs(ratio - 1.0) <= band + 1e-9
    if is_earthquake(scene):
        agree = same_verdict and same_direction and close_in_time and ratio_in_band
        return [Comparison(
            f"test vs theory as close as under harmonic motion (same verdict and direction, "
            f"times of instability within {window:g} s, peak ratio 1 ± {band:g})", False, agree,
            "",
            not agree)]
    return [
        Comparison("test vs theory: overturns", "same",
                   f"test {_yes(metrics['overturned test'])}, theory "
                   f"{_yes(metrics['overturned theory'])}", "", same_verdict),
        Comparison("test vs theory: direction of instability", "same",
                   _directions(metrics["direction test"], metrics["direction theory"]),
                   "", same_direction),
        Comparison("test vs theory: difference of t unstable", f"≤ {window:g} s", delta, "",
                   close_in_time),
        Comparison("test vs theory: peak ratio", f"1 ± {band:g}", ratio, "-", ratio_in_band),
    ]


def _direction(sign: int) -> str:
    """A direction of instability in words: "+", "−" or "never unstable"."""
    return "never unstable" if sign == 0 else ("+" if sign > 0 else "−")


def _directions(test: int, theory: int) -> str:
    """Test's and theory's directions of instability (the sign of θ when |θ| first
    exceeds α) as a phrase: "the same (neither becomes unstable)", "the same (θ + in
    both)" or "test +, theory never unstable"."""
    if test != theory:
        return f"test {_direction(test)}, theory {_direction(theory)}"
    return ("the same (neither becomes unstable)" if test == 0
            else f"the same (θ {_direction(test)} in both)")


def _yes(flag: bool) -> str:
    return "yes" if flag else "no"


def _text(value: float | None) -> str:
    return "never" if value is None else f"{value:g} s"


def _close(value: float, expected: float, tolerance: float) -> bool:
    if expected == 0:
        return abs(value) <= tolerance
    return abs(value - expected) <= tolerance * abs(expected)


def _visible_cycles(result: RockingResult) -> float:
    """Cycles of free rocking whose amplitude stays above 3 % of the first (half cycles / 2;
    :func:`shaketable.studies.free_rocking.visible_impacts`)."""
    from shaketable.studies.free_rocking import visible_impacts

    return visible_impacts(result) / 2.0
