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
        says otherwise), or the same verdict for yes/no quantities.
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
    """A scene with ``[sensors]``: one virtual test (and its theory run) per COR."""
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
    comparisons = compare_with_report(scene, tests[0].theory)
    return SceneResult(scene=scene, motion=felt, runs=runs, comparisons=tuple(comparisons),
                       table=table, tests=tuple(tests))


def compare_with_report(scene: Scene, result: RockingResult) -> list[Comparison]:
    """The scene's ``[report]`` values against one run."""
    from .units import parse

    report = scene.report
    tolerance = float(report.get("tolerance", 0.10))
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
            if result.overturned:
                lines.append(Comparison("max θ/α", float(value), "F (overturns)", "-", False))
                continue
            reproduced = round(result.max_theta_ratio, 3)
            lines.append(Comparison("max θ/α", float(value), reproduced, "-",
                                    _close(reproduced, float(value), tolerance)))
        elif key == "cycles":
            reproduced = _visible_cycles(result)
            lines.append(Comparison("cycles to rest", float(value), reproduced, "-",
                                    _close(reproduced, float(value), 0.3)))
        else:  # times
            expected = parse(value, "time", where=f"{scene.path}: report.{key}")
            reproduced = getattr(result, key)
            reproduced = None if reproduced is None or not math.isfinite(reproduced) else \
                round(float(reproduced), 3)
            lines.append(Comparison(key.replace("_", " "), expected, reproduced, "s",
                                    reproduced is not None and
                                    _close(reproduced, expected, tolerance)))
    return lines


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
