"""Running a scene: motion -> (table) -> block -> outputs and the comparison with the report.

Only the stages a scene names are run. The core never reads TOML; the scene
is parsed by :mod:`shaketable.scenes.parse` first.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from shaketable.core.constants import G
from shaketable.core.equality import fields_equal
from shaketable.core.impulses import ImpulsiveMotion
from shaketable.core.motion import Motion
from shaketable.core.units import display_length_unit, parse
from shaketable.ground import generators
from shaketable.lab.stage import TableRun, run_table
from shaketable.models.api import simulate
from shaketable.models.rocking.result import RockingResult
from shaketable.scenes.compare import (
    compare_test_with_theory,
    compare_with_report,
    is_earthquake,
)
from shaketable.scenes.parse import Scene, SceneError

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure


def build_motion(scene: Scene) -> Motion | ImpulsiveMotion | None:
    """The table motion a scene names [m/s^2], or ``None`` for free rocking (an
    :class:`~shaketable.core.impulses.ImpulsiveMotion` for ``kind = "impulses"``); with
    ``[floor]``, the motion at that floor of the building (the ``[motion]`` is the ground's)."""
    motion = _ground_motion(scene)
    if scene.floor is None:
        return motion
    if not isinstance(motion, Motion):
        raise SceneError(f"{scene.path}: [floor] needs a ground motion (a [motion] of kind "
                         f"harmonic, record, artificial or a pulse), not {scene.motion['kind']!r}")
    from shaketable.ground.floor import floor_motion

    try:
        return floor_motion(motion, scene.floor.building, floor=scene.floor.floor)
    except ValueError as error:
        raise SceneError(f"{scene.path}: [floor]: {error}") from None


def _ground_motion(scene: Scene) -> Motion | ImpulsiveMotion | None:
    spec = dict(scene.motion)
    kind = spec.pop("kind")
    try:
        if kind == "free":
            return None
        if kind == "harmonic":
            return generators.harmonic(
                spec["frequency"], horizontal=spec["horizontal"],
                vertical=spec.get("vertical", 0.0), duration=spec["duration"],
                dt=spec.get("dt"), phase=spec.get("phase", 0.0),
                ramp=spec.get("ramp", 0.0), start=spec.get("start", 0.0))
        if kind == "half-sine":
            return generators.half_sine_pulse(
                amplitude=spec["amplitude"], pulse_duration=spec["pulse_duration"],
                duration=spec["duration"],
                dt=spec.get("dt", 0.001), sign=spec.get("sign", 1))
        if kind == "constant-pulse":
            return generators.constant_pulse(
                acceleration=spec["acceleration"], pulse_duration=spec["pulse_duration"],
                duration=spec["duration"],
                dt=spec.get("dt", 0.001))
        if kind == "impulses":     # times ["0.1 s", ...], velocity_steps ["0.2 m/s", ...]
            return generators.velocity_steps(
                [parse(x, "time", where=f"{scene.path}: motion.times") for x in spec["times"]],
                [parse(x, "velocity", where=f"{scene.path}: motion.velocity_steps")
                 for x in spec["velocity_steps"]],
                duration=spec["duration"], dt=spec.get("dt", 0.01))
        if kind == "artificial":
            options = {"seed": spec["seed"], "dt": spec.get("dt", 0.01)}
            if "duration" in spec:
                options["duration"] = spec["duration"]
            for key in ("pga", "vertical_pga"):
                if key in spec:
                    options[key] = spec[key]
            return generators.artificial(spec["preset"], **options)
        if kind == "record":
            return _record_motion(spec, scene)
    except SceneError:
        raise
    except (ValueError, KeyError) as error:
        raise SceneError(f"{scene.path}: [motion] ({kind}): {error}") from None
    raise SceneError(f"{scene.path}: motion.kind {kind!r} is not runnable")  # pragma: no cover


def _record_motion(spec: dict, scene: Scene) -> Motion:
    motion = _recorded(spec, scene)
    if "pga" in spec:
        return _scaled_to_pga(spec, scene, motion)[0]
    scale = spec.get("scale", 1.0)
    if scale != 1.0:
        motion = motion.scaled(float(scale))
    return motion


def _scaled_to_pga(spec: dict, scene: Scene, motion: Motion) -> tuple[Motion, str]:
    """The record of ``motion.pga`` scaled as ``simulate --pga`` scales it, and its note."""
    from shaketable.ground.records import scaled_to_pga

    name = spec["name"] if "name" in spec else Path(spec["file"]).stem
    return scaled_to_pga(motion, spec["pga"], name=name, where=f"{scene.path}: motion.pga")


def record_scaling_note(scene: Scene) -> str | None:
    """``"record NAME: own PGA 0.2808 g, scaled by 2.137 to PGA 0.6 g"`` for a record
    scene with ``motion.pga`` (the line ``simulate --pga`` prints); None otherwise."""
    spec = dict(scene.motion)
    if spec.get("kind") != "record" or "pga" not in spec:
        return None
    return _scaled_to_pga(spec, scene, _recorded(spec, scene))[1]


def _recorded(spec: dict, scene: Scene) -> Motion:
    """The record of a scene's ``[motion]`` as recorded (unscaled)."""
    from shaketable.ground import records

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
    return motion


@dataclass(frozen=True)
class SceneResult:
    """The runs of one scene (one per COR) and their comparison with the report.

    ``calibrated`` is the ensemble over a calibrated COR
    (:class:`~shaketable.calibration.uncertainty.CalibratedEnsemble`) when the scene's
    ``rocking.cor`` names a calibration.json and the block feels a motion.
    """

    __eq__ = fields_equal   # arrays compared by value; equal after a pickle round trip

    scene: Scene
    motion: Motion | None
    runs: tuple
    comparisons: tuple = field(default_factory=tuple)
    table: TableRun | None = None
    tests: tuple = ()
    slides: tuple = ()
    calibrated: Any = None
    planar: tuple = ()

    @property
    def main(self) -> RockingResult:
        """The first run (the scene's first COR)."""
        return self.runs[0]

    @property
    def slip_unit(self) -> str:
        """The one length unit of the scene's slips, in its figures and its lines: the unit
        the scene's block was given in, or the next smaller one (ft -> in, m -> mm) when a
        sliding or planar run's peak slip is under one of it
        (:func:`~shaketable.core.units.display_length_unit`; the smallest of the runs')."""
        from shaketable.core.constants import LENGTH_UNITS

        unit = self.scene.block.length_unit if self.scene.block is not None else "m"
        peaks = ([run.peak_slip for run in self.slides]
                 + [run.summary()["peak slip [m]"] for run in self.planar])
        units = {display_length_unit(float(peak), unit) for peak in peaks}
        return min(units, key=LENGTH_UNITS.__getitem__) if units else unit

    def to_frame(self) -> pd.DataFrame:
        """Time histories of every run, long format with a ``cor [-]`` column."""
        import pandas as pd

        frames = []
        several = bool(self.scene.blocks or self.scene.theta0s)  # lists of sizes or theta0
        for run in self.runs:
            frame = run.to_frame()
            frame.insert(0, "cor [-]", run.cor)
            if several:
                frame.insert(0, "theta0 [rad]", run.theta[0])
                frame.insert(0, "block", run.block.describe())
            frames.append(frame)
        return pd.concat(frames, ignore_index=True)

    def summary(self) -> dict:
        """JSON-ready scalars: scene identification, each run, each comparison."""
        from shaketable.models.stops import early_stop, stop_summary

        stopped = [run for run in (*self.runs, *self.planar) if early_stop(run) is not None]
        summary: dict[str, Any] = {
            "scene": self.scene.name, "source": self.scene.source,
            "description": self.scene.description,
            "stopped early": bool(stopped),
            "runs": [stop_summary(run) for run in self.runs],
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
        if self.slides:
            summary["sliding"] = [run.summary() for run in self.slides]
        if self.planar:
            summary["planar"] = [stop_summary(run) for run in self.planar]
        if self.calibrated is not None:
            from shaketable.core.files import json_ready_dict

            summary["calibrated COR ensemble"] = json_ready_dict(self.calibrated.summary)
        return summary

    def plot(self) -> Figure:
        """The Calcomp figure of the main run, captioned; other CORs overlaid on the rotation."""
        from shaketable.plots.calcomp import calcomp

        title = (f"{self.scene.source} (scene {self.scene.name})" if self.scene.source
                 else f"scene {self.scene.name}")
        return calcomp(self.main, title=title, others=self.runs[1:],
                       time_range=self.scene.outputs.get("time_range"),
                       details=self.caption_details())

    def caption_details(self) -> list[str]:
        """Caption lines beside the block and motion: record scale, substitute motion, table."""
        spec = self.scene.motion
        details = []
        if spec.get("kind") == "record" and float(spec.get("scale", 1.0)) != 1.0:
            details.append(f"record scaled by {float(spec['scale']):g}")
        if spec.get("kind") == "record" and "pga" in spec:
            details.append(f"record scaled to PGA {spec['pga'] / G:.4g} g")
        if spec.get("kind") == "artificial":
            details.append("SUBSTITUTE accelerogram (the report's artificial record is not "
                           "available): compare trends, not values")
        if self.table is not None:
            details.append("motion felt by the block on the virtual shaking table")
        return details

    def write(self, out: str | os.PathLike[str]) -> list[Path]:
        """Write the outputs the scene asks for into folder ``out``; return the paths."""
        from shaketable.core.files import prepare_output_folder, write_csv, write_parquet, write_text
        from shaketable.plots.base import save

        out = prepare_output_folder(out, "out")
        written = []
        outputs = self.scene.outputs
        if outputs.get("csv", True):
            written.append(out / "history.csv")
            write_csv(written[-1], self.to_frame())
        if outputs.get("parquet", False):
            written.append(out / "history.parquet")
            write_parquet(written[-1], self.to_frame())
        written.append(out / "summary.json")
        write_text(written[-1], json.dumps(self.summary(), indent=2))
        if outputs.get("figure", True):
            for suffix in ("png", "svg") if outputs.get("svg", False) else ("png",):
                written.append(out / f"calcomp.{suffix}")
                save(self.plot(), written[-1])
                for index, test in enumerate(self.tests):
                    label = "" if len(self.tests) == 1 else f"-{index + 1}"
                    written.append(out / f"test-vs-theory{label}.{suffix}")
                    title = (f"{self.scene.source or self.scene.name}: virtual test vs "
                             "theory, "  # the figure gives the block (B x H) below
                             + ("free rocking" if self.scene.motion.get("kind") == "free"
                                else f"{self.scene.motion.get('kind')} table motion"))
                    save(test.plot(title=title), written[-1])
        for index, test in enumerate(self.tests):
            label = "" if len(self.tests) == 1 else f"-{index + 1}"
            written.append(out / f"record{label}.csv")
            write_csv(written[-1], test.to_frame())
        for index, run in enumerate(self.planar):
            label = "" if len(self.planar) == 1 else f"-{index + 1}"
            written.append(out / f"planar{label}.csv")
            write_csv(written[-1], run.to_frame())
            if outputs.get("figure", True):
                written.append(out / f"planar{label}.png")
                title = (f"{self.scene.source or self.scene.name}: the planar block, "
                         f"μs {run.friction.static:g}, μd {run.friction.dynamic:g}, "
                         f"COR {run.cor:g}")
                save(run.plot(title=title), written[-1])
        for index, run in enumerate(self.slides):
            label = "" if len(self.slides) == 1 else f"-{index + 1}"
            written.append(out / f"sliding{label}.csv")
            write_csv(written[-1], run.to_frame())
            if outputs.get("figure", True):
                written.append(out / f"sliding{label}.png")
                title = (f"{self.scene.source or self.scene.name}: the same block sliding, "
                         f"μs {run.friction.static:g}, μd {run.friction.dynamic:g}")
                # lengths in the one unit of the scene's slips (the block's own, or the
                # next smaller one)
                save(run.plot(title=title, length_unit=self.slip_unit), written[-1])
        return written


def length_in(value: float, unit: str, *, signed: bool = False) -> str:
    """A length [m] in exactly ``unit`` (3 significant digits), with the unit: the lines of
    one scene keep one unit (:attr:`SceneResult.slip_unit`), where
    :func:`~shaketable.core.units.format_length` would pick one per value."""
    import math

    from shaketable.core.constants import LENGTH_UNITS

    if not math.isfinite(value):
        return "n/a"
    number = f"{value / LENGTH_UNITS[unit]:{'+' if signed else ''}#.3g}".replace(".e", "e")
    return f"{number[:-1] if number.endswith('.') else number} {unit}"


def run_scene(scene: Scene) -> SceneResult:
    """Run every stage a scene names and compare with the report's values."""
    motion = build_motion(scene)
    if isinstance(motion, ImpulsiveMotion):
        return _run_impulses(scene, motion)
    table = None
    felt = motion
    if scene.table is not None:
        try:
            table = run_table(motion, scene.table, duration=scene.duration)
        except ValueError as error:
            raise SceneError(f"{scene.path}: [table]: {error}") from None
        felt = table.felt
    if scene.sensors is not None:
        if scene.sliding:
            raise SceneError(f"{scene.path}: [sliding] and [sensors] cannot be combined: the "
                             "virtual instruments read a rocking block")
        return _run_virtual_tests(scene, motion, felt, table)
    runs = []
    for block, theta0, cor in scene.variants():
        try:
            runs.append(simulate(block, felt, cor=cor, theta0=theta0,
                                 theta_dot0=scene.theta_dot0, duration=scene.duration,
                                 method=scene.method, **scene.options))
        except ValueError as error:
            raise SceneError(f"{scene.path}: [rocking]: {error}") from None
    comparisons = compare_with_report(scene, runs[0])
    calibrated = None
    if scene.calibrated_cor is not None and felt is not None:
        from shaketable.calibration.uncertainty import calibrated_ensemble

        members = int(scene.ensemble.get("members", 200))
        calibrated = calibrated_ensemble(scene.block, felt, scene.calibrated_cor,
                                         members=members, seed=int(scene.ensemble.get("seed", 0)),
                                         duration=scene.duration, method=scene.method)
    return SceneResult(scene=scene, motion=felt, runs=tuple(runs),
                       comparisons=tuple(comparisons), table=table,
                       slides=_run_sliding(scene, felt), calibrated=calibrated,
                       planar=_run_planar(scene, felt))


def _run_impulses(scene: Scene, motion: ImpulsiveMotion) -> SceneResult:
    """A ``kind = "impulses"`` scene: the rocking runs only (steps of the table's velocity
    have no table, sensor or sliding stage)."""
    if scene.table is not None or scene.sensors is not None or scene.sliding:
        raise SceneError(f"{scene.path}: a motion of kind 'impulses' runs the rocking block "
                         "only ([table], [sensors] and [sliding] need a sampled motion)")
    runs = []
    for cor in scene.cors:
        try:
            runs.append(simulate(scene.block, motion, cor=cor, theta0=scene.theta0,
                                 theta_dot0=scene.theta_dot0, duration=scene.duration,
                                 method=scene.method, **scene.options))
        except ValueError as error:
            raise SceneError(f"{scene.path}: [rocking]: {error}") from None
    return SceneResult(scene=scene, motion=motion.motion, runs=tuple(runs),
                       comparisons=tuple(compare_with_report(scene, runs[0])), table=None,
                       slides=())


def _run_planar(scene: Scene, felt: Motion | None) -> tuple:
    """``block.static_friction`` (and ``dynamic_friction``) with a table motion: the planar
    block (rest, slide, rock, slide-rock, flight), one run per COR."""
    if scene.static_friction is None or felt is None:
        return ()
    from shaketable.models.sliding.result import Friction

    if scene.block.rods is not None:
        raise SceneError(f"{scene.path}: block.static_friction runs the planar block, which "
                         "cannot have prestress rods (a rod hinged to the ground ties the "
                         "block to the table); remove block.static_friction or the rods")
    friction = Friction(scene.static_friction, scene.dynamic_friction)
    runs = []
    for cor in scene.cors:
        try:
            runs.append(simulate(scene.block, felt, cor=cor, friction=friction,
                                 theta0=scene.theta0, theta_dot0=scene.theta_dot0,
                                 duration=scene.duration))
        except ValueError as error:
            raise SceneError(f"{scene.path}: [block] friction: {error}") from None
    return tuple(runs)


def _run_sliding(scene: Scene, felt: Motion | None) -> tuple:
    """``[sliding]``: the same block on the same table motion, sliding, per (mu_s, mu_d)."""
    if not scene.sliding or felt is None:
        return ()
    from shaketable.models.rocking.run import extended
    from shaketable.models.sliding.engine import slide
    from shaketable.models.sliding.result import Friction

    motion = extended(felt, scene.duration)
    try:
        return tuple(slide(motion, Friction(static, dynamic), block=scene.block)
                     for static, dynamic in scene.sliding)
    except ValueError as error:
        raise SceneError(f"{scene.path}: [sliding]: {error}") from None


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
    from shaketable.scenes.virtual_test import run_virtual_test

    sensors, theory = scene.sensors, scene.theory
    tests = []
    for block, theta0, cor in scene.variants():
        try:
            tests.append(run_virtual_test(block, felt, cor=cor, sensors=sensors,
                                          theory=theory, commanded=commanded,
                                          theta0=theta0,
                                          theta_dot0=scene.theta_dot0,
                                          duration=scene.duration,
                                          method=scene.method, **scene.options))
        except ValueError as error:
            raise SceneError(f"{scene.path}: virtual test: {error}") from None
    runs = tuple(test.test for test in tests)
    described = tests[0].test if is_earthquake(scene) else tests[0].theory
    comparisons = compare_with_report(scene, described) + compare_test_with_theory(scene,
                                                                                   tests[0])
    return SceneResult(scene=scene, motion=felt, runs=runs, comparisons=tuple(comparisons),
                       table=table, tests=tuple(tests))
