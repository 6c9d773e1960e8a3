"""Running a scene: motion -> (table) -> block -> outputs and the comparison with the report.

Only the stages a scene names are run. The core never reads TOML; the scene
is parsed by :mod:`shaketable.scenes` first.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import motions as generators
from .constants import G
from .motion import Motion
from .results import RockingResult
from .scenes import Scene, SceneError
from .simulate import simulate
from .table_stage import TableRun, run_table, table_setup_from_dict


def build_motion(scene: Scene) -> Motion | None:
    """The table motion a scene names [m/s^2], or ``None`` for free rocking."""
    spec = dict(scene.motion)
    kind = spec.pop("kind")
    g = G
    try:
        if kind == "free":
            return None
        if kind == "harmonic":
            return generators.harmonic(
                spec["frequency"], spec["horizontal"] / g, spec.get("vertical", 0.0) / g,
                duration=spec["duration"], dt=spec.get("dt", 0.01), phase=spec.get("phase", 0.0),
                ramp=spec.get("ramp", 0.0), start=spec.get("start", 0.0))
        if kind == "half-sine":
            return generators.half_sine_pulse(
                spec["amplitude"] / g, spec["pulse_duration"], duration=spec["duration"],
                dt=spec.get("dt", 0.001), sign=spec.get("sign", 1))
        if kind == "constant-pulse":
            return generators.constant_pulse(
                spec["acceleration"] / g, spec["pulse_duration"], duration=spec["duration"],
                dt=spec.get("dt", 0.001))
        if kind == "artificial":
            options = {"seed": spec["seed"], "dt": spec.get("dt", 0.01)}
            if "duration" in spec:
                options["duration"] = spec["duration"]
            if "pga" in spec:
                options["pga_g"] = spec["pga"] / g
            if "vertical_pga" in spec:
                options["vertical_pga_g"] = spec["vertical_pga"] / g
            return generators.artificial(spec["preset"], **options)
        if kind == "record":
            return _record_motion(spec, scene)
    except SceneError:
        raise
    except (ValueError, KeyError) as error:
        raise SceneError(f"{scene.path}: [motion] ({kind}): {error}") from None
    raise SceneError(f"{scene.path}: motion.kind {kind!r} is not runnable")  # pragma: no cover


def _record_motion(spec: dict, scene: Scene) -> Motion:
    from . import records

    with_vertical = bool(spec.get("vertical", True))
    if "name" in spec:
        options = {}
        if "pacoima_vertical_sign" in spec:
            options["pacoima_vertical_sign"] = spec["pacoima_vertical_sign"]
        motion = records.load(spec["name"], vertical=with_vertical, **options)
    else:
        path = Path(spec["file"])
        if not path.is_absolute():
            path = Path(scene.path).parent / path
        options = {key: spec[key] for key in ("units", "dt") if key in spec}
        if "column" in spec:
            options["value_column"] = spec["column"]
        record = records.read(path, **options)
        motion = records.combine(record, name=path.stem)
    scale = spec.get("scale", 1.0)
    if scale != 1.0:
        motion = motion.scaled(float(scale))
    return motion


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


@dataclass(frozen=True)
class SceneResult:
    """The runs of one scene (one per COR) and their comparison with the report."""

    scene: Scene
    motion: Motion | None
    runs: tuple
    comparisons: tuple = field(default_factory=tuple)
    table: TableRun | None = None
    tests: tuple = ()

    @property
    def main(self) -> RockingResult:
        """The first run (the scene's first COR)."""
        return self.runs[0]

    def to_frame(self):
        """Time histories of every run, long format with a ``cor [-]`` column."""
        import pandas as pd

        frames = []
        for run in self.runs:
            frame = run.to_frame()
            frame.insert(0, "cor [-]", run.cor)
            frames.append(frame)
        return pd.concat(frames, ignore_index=True)

    def summary(self) -> dict:
        """JSON-ready scalars: scene identification, each run, each comparison."""
        summary = {
            "scene": self.scene.name, "source": self.scene.source,
            "description": self.scene.description,
            "runs": [run.summary() for run in self.runs],
            "comparisons": [{"quantity": c.quantity, "report": c.report,
                             "reproduced": c.reproduced, "unit": c.unit, "agrees": c.agrees}
                            for c in self.comparisons],
        }
        if self.table is not None:
            summary["table"] = {"limits exceeded": self.table.warnings()}
        if self.scene.mode() is not None:
            summary["mode (Section 2.1)"] = self.scene.mode()
        if self.tests:
            summary["test vs theory"] = [test.metrics() for test in self.tests]
        return summary

    def plot(self):
        """The Calcomp figure of the main run; other CORs overlaid on the displacement."""
        from .plots import calcomp

        title = f"{self.scene.source}: {self.scene.name}" if self.scene.source else None
        figure = calcomp(self.main, title=title)
        if len(self.runs) > 1:
            axis = figure.axes[3]
            for run in self.runs[1:]:
                axis.plot(run.t, run.theta, lw=0.9, label=f"COR = {run.cor:g}")
            axis.plot([], [], color="k", label=f"COR = {self.main.cor:g}")
            axis.legend(loc="upper right", fontsize=7, frameon=False)
        return figure

    def write(self, out) -> list[Path]:
        """Write the outputs the scene asks for into folder ``out``; return the paths."""
        from .plots import save

        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        written = []
        outputs = self.scene.outputs
        if outputs.get("csv", True):
            written.append(out / "history.csv")
            self.to_frame().to_csv(written[-1], index=False)
        if outputs.get("parquet", False):
            written.append(out / "history.parquet")
            self.to_frame().to_parquet(written[-1], index=False)
        written.append(out / "summary.json")
        written[-1].write_text(json.dumps(self.summary(), indent=2))
        if outputs.get("figure", True):
            for suffix in ("png", "svg") if outputs.get("svg", False) else ("png",):
                written.append(out / f"calcomp.{suffix}")
                save(self.plot(), written[-1])
                for index, test in enumerate(self.tests):
                    label = "" if len(self.tests) == 1 else f"-{index + 1}"
                    written.append(out / f"test-vs-theory{label}.{suffix}")
                    title = (f"{self.scene.source or self.scene.name}: test vs theory, "
                             f"{self.scene.block.describe()}")
                    save(test.plot(title=title), written[-1])
        for index, test in enumerate(self.tests):
            label = "" if len(self.tests) == 1 else f"-{index + 1}"
            written.append(out / f"record{label}.csv")
            test.to_frame().to_csv(written[-1], index=False)
        return written


def run_scene(scene: Scene) -> SceneResult:
    """Run every stage a scene names and compare with the report's values."""
    motion = build_motion(scene)
    table = None
    felt = motion
    if scene.table:
        setup = table_setup_from_dict(scene.table, scene.path)
        try:
            table = run_table(motion, setup, duration=scene.duration)
        except ValueError as error:
            raise SceneError(f"{scene.path}: [table]: {error}") from None
        felt = table.felt
    if scene.sensors is not None:
        return _run_virtual_tests(scene, motion, felt, table)
    runs = []
    for cor in scene.cors:
        try:
            runs.append(simulate(scene.block, felt, cor=cor, theta0=scene.theta0,
                                 theta_dot0=scene.theta_dot0, duration=scene.duration,
                                 method=scene.method, **scene.options))
        except ValueError as error:
            raise SceneError(f"{scene.path}: [rocking]: {error}") from None
    comparisons = compare_with_report(scene, runs[0])
    return SceneResult(scene=scene, motion=felt, runs=tuple(runs),
                       comparisons=tuple(comparisons), table=table)


def _run_virtual_tests(scene: Scene, commanded: Motion | None, felt: Motion | None,
                       table: TableRun | None) -> "SceneResult":
    """A scene with ``[sensors]``: one virtual test (and its theory run) per COR.

    The comparisons are (i) the report's values against the run they describe
    and (ii) the test against the theory (:func:`compare_test_with_theory`).
    For Figs. 3.4 and 3.7-3.9 the report's values are those of both curves and
    are compared with the theory run; Fig. 3.5 is *test data* (its caption),
    and every earthquake-type scene (:data:`EARTHQUAKE_KINDS`) is compared with
    the virtual test run, since the report gives no theory for earthquake
    motions (Section 3.7 (2)).
    """
    from .virtual_test import run_virtual_test, sensors_from_dict, theory_from_dict

    sensors = sensors_from_dict(scene.sensors, scene.path)
    theory = theory_from_dict(scene.theory, scene.path)
    tests = []
    for cor in scene.cors:
        try:
            tests.append(run_virtual_test(scene.block, felt, cor=cor, sensors=sensors,
                                          theory=theory, commanded=commanded,
                                          theta0=scene.theta0, duration=scene.duration,
                                          method=scene.method, **scene.options))
        except ValueError as error:
            raise SceneError(f"{scene.path}: virtual test: {error}") from None
    runs = tuple(test.test for test in tests)
    described = tests[0].test if is_earthquake(scene) else tests[0].theory
    comparisons = compare_with_report(scene, described) + compare_test_with_theory(scene,
                                                                                   tests[0])
    return SceneResult(scene=scene, motion=felt, runs=runs, comparisons=tuple(comparisons),
                       table=table, tests=tuple(tests))


#: Motion kinds that are earthquake accelerograms. For these the report shows test data
#: only (Fig. 3.5, "TEST DATA") and states that test and theory did not agree as well as
#: under harmonic motion: "Comparisons of test and theoretical results for earthquake-type
#: ground motions are not given, as these did not show the same level of agreement"
#: (Section 3.7 (2)).
EARTHQUAKE_KINDS = frozenset({"artificial", "record"})

#: Default largest |t_unstable(test) - t_unstable(theory)| [s] for "unstable at about the
#: same point" (Section 3.7 (2)): half a period of the report's 2 Hz table motion, i.e. the
#: block becomes unstable on the same excursion (each half cycle of the table pushes it
#: one way). A scene may state its own as ``tolerance = { test_theory_t_unstable = "..." }``.
TEST_THEORY_T_UNSTABLE = 0.25

#: Default half-width of the band of the peak ratio test/theory around 1 [-]: the report's
#: "about 10 %" agreement. A scene may state ``tolerance = { test_theory_peak_ratio = ... }``.
TEST_THEORY_PEAK_RATIO = 0.10

#: Default relative tolerance of a report value [-] (the report's "about 10 %").
REPORT_TOLERANCE = 0.10

#: Keys of a per-quantity ``[report] tolerance = { ... }`` table and what each accepts:
#: ``"time"`` a relative number or an absolute time with its unit ("0.5 s"); ``"number"`` a
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


def scene_tolerances(scene: Scene) -> dict:
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
    from .units import parse

    given = scene.report.get("tolerance", REPORT_TOLERANCE)
    where = f"{scene.path}: report.tolerance"
    common = REPORT_TOLERANCE
    table = {}
    if isinstance(given, dict):
        table = given
    elif isinstance(given, bool) or not isinstance(given, (int, float)) or not 0 <= given:
        raise SceneError(f"{where} must be a non-negative relative tolerance such as 0.1 or a "
                         f"table such as {{ t_overturn = '0.5 s' }}, got {given!r}")
    else:
        common = float(given)
    unknown = sorted(set(table) - set(TOLERANCE_KEYS))
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
    from .units import parse

    report = scene.report
    tolerances = scene_tolerances(scene)
    lines = []
    for key, value in report.items():
        if key in ("tolerance", "note"):
            continue
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
            reproduced = getattr(result, key)
            reproduced = None if reproduced is None or not math.isfinite(reproduced) else \
                round(float(reproduced), 3)
            lines.append(Comparison(f"{key.replace('_', ' ')} ({tolerance.describe('s')})",
                                    expected, reproduced, "s",
                                    reproduced is not None and
                                    tolerance.accepts(reproduced, expected)))
    return lines


def compare_test_with_theory(scene: Scene, test) -> list[Comparison]:
    """The virtual test against its theory run, as Section 3.7 (2) compares them.

    For free rocking and harmonic motion (Figs. 3.4, 3.7-3.9) the report states
    that test and theory agree: "the block becomes unstable at about the same
    point ... and overturning is in the same direction". Four lines score that:
    the same overturning verdict; the same direction of instability (sign of
    theta when |theta| first exceeds alpha, 0 when never); |t_unstable(test) -
    t_unstable(theory)| within ``test_theory_t_unstable`` (default
    :data:`TEST_THEORY_T_UNSTABLE`); the peak ratio test/theory (each curve
    up to its own instability, :meth:`shaketable.virtual_test.TestTheory.metrics`)
    within 1 +- ``test_theory_peak_ratio`` (default :data:`TEST_THEORY_PEAK_RATIO`).

    For earthquake-type motions (:data:`EARTHQUAKE_KINDS`) the report states the
    opposite: they "did not show the same level of agreement". One line then
    asks whether the four criteria all hold; the report's answer is *no*.

    Parameters
    ----------
    scene : Scene
    test : TestTheory
        One virtual test (:func:`shaketable.virtual_test.run_virtual_test`).
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
                   f"{metrics['direction test']:+d} / {metrics['direction theory']:+d}",
                   "sign of θ", same_direction),
        Comparison("test vs theory: difference of t unstable", f"≤ {window:g} s", delta, "",
                   close_in_time),
        Comparison("test vs theory: peak ratio", f"1 ± {band:g}", ratio, "-", ratio_in_band),
    ]


def _yes(flag: bool) -> str:
    return "yes" if flag else "no"


def _text(value) -> str:
    return "never" if value is None else f"{value:g} s"


def _close(value, expected, tolerance) -> bool:
    if expected == 0:
        return abs(value) <= tolerance
    return abs(value - expected) <= tolerance * abs(expected)


def _visible_cycles(result: RockingResult, visible_fraction: float = 0.03) -> float:
    """Cycles of free rocking whose amplitude stays above 3 % of the first (half cycles / 2)."""
    if result.impact_velocities.size == 0:
        return 0.0
    velocities = np.abs(result.impact_velocities)
    # impact velocity scales with amplitude for small amplitudes (Eq. 2-3 energy)
    from .theory import impact_velocity

    first = abs(result.theta[0]) if result.theta[0] != 0 else result.max_abs_theta
    limit = impact_velocity(result.block, visible_fraction * first)
    return float(np.sum(velocities > limit)) / 2.0
