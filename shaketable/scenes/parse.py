"""Scenes: an experiment written as a TOML file, parsed and validated.

A scene names only what it needs; the pipeline (:mod:`shaketable.scenes.run`) runs
only the stages a scene names. Every dimensional value carries its unit
(``"30 in"``, ``"0.5 g"``, ``"2 Hz"``); errors name the file, the key and what is
expected.

Sections (``experiments/*.toml`` are the examples)::

    name, source, description       # top level: text (name is one folder name: the
                                    # default output folder shaketable-out/<name>, so no
                                    # '/', '\\', '..' -- refused, never sanitised)
    [block]      size = "30x6in" (or a list to compare, ["30x6in", "60x12in"])
                 or  height = "30 in", width = "6 in"
    [block.rods] stiffness = "0.4 W/in", force = "0.4 W", edge_distance = "12 in"
                 (and block.static_friction = 0.6: the sliding/rocking check of Section 2.1)
    [motion]     kind = "free" | "harmonic" | "record" | "artificial" | "half-sine"
                 | "constant-pulse", and the keys of that kind
    [rocking]    cor = 0.925 (or a list to compare), theta0 = "0.5 alpha" (or a list),
                 duration = "8 s", method = "fast", subdivisions, rtol
    [report]     the report's values to compare with (see REPORT_KEYS)
    [outputs]    figure = true, csv = true, parquet = false, svg = false,
                 time_range = ["0 s", "42 s"] (the figures' time axis)
    [table]      command, highpass, actuator, pitch, limits (shaketable.lab.stage)
    [sensors]    potentiometers, accelerometers, rate, noise... (shaketable.scenes.virtual_test)
    [theory]     cor = "calibrated" or a number: the test-vs-theory comparison of Section 3.7
    [sliding]    static_friction = 0.3, dynamic_friction = 0.2 (or a list to compare): the
                 same block and table motion also run sliding (Coulomb stick-slip,
                 Section 4.5), beside the rocking runs, with Section 2.1's choice
    [floor]      floor = 3, period = "0.6 s", height = "17.5 m", storeys = 5 (damping,
                 shape, modes): the block stands on that floor; [motion] is the ground's
                 (shaketable.ground.floor, parsed by shaketable.scenes.assess)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from shaketable.core import sections
from shaketable.core.geometry import Block
from shaketable.core.tomlfile import read_toml
from shaketable.core.tomlfile import with_line as _with_line
from shaketable.core.units import parse, parse_angle_or_ratio
from shaketable.core.validation import check_keys, count, flag

if TYPE_CHECKING:
    from shaketable.lab.stage import TableSetup
    from shaketable.scenes.mode_map import ModeMapSettings
    from shaketable.scenes.spectrum import SpectrumSettings

MOTION_KEYS = {
    "free": set(),
    "harmonic": {"frequency", "horizontal", "vertical", "phase", "duration", "dt", "ramp",
                 "start"},
    "record": {"name", "file", "units", "dt", "column", "vertical", "scale", "pga",
               "pacoima_vertical_sign", "duration"},
    "artificial": {"preset", "seed", "pga", "duration", "dt", "vertical_pga"},
    "half-sine": {"amplitude", "pulse_duration", "duration", "dt", "sign"},
    "constant-pulse": {"acceleration", "pulse_duration", "duration", "dt"},
    # steps of the table's velocity, applied exactly (shaketable.core.impulses)
    "impulses": {"times", "velocity_steps", "duration", "dt"},
}

ROCKING_KEYS = {"cor", "theta0", "theta_dot0", "duration", "method", "subdivisions", "rtol"}

#: The report's values a scene may state, and how each is compared.
REPORT_KEYS = {
    "t_rest": "time", "cycles": "number", "overturned": "bool", "overturn_direction": "number",
    "t_unstable": "time", "t_overturn": "time", "max_theta_ratio": "number",
    "tolerance": "number", "note": "text", "by_construction": "keys",
}

#: ``time_range = ["0 s", "42 s"]``: the time axis of the scene's figures, shared by
#: figures meant to be compared (Figs. 4.1/4.2, 4.13/4.14, 4.16/4.17).
OUTPUT_KEYS = {"figure", "csv", "parquet", "svg", "time_range"}

#: Figures recomputed by a ``"report-figure"`` study: Figs. 2.3-2.6 and the
#: single-pulse check of Section 4.3 (4).
REPORT_FIGURES = ("2.3", "2.4", "2.5", "2.6", "4.3.4")

TOP_KEYS = {"name", "source", "description", "block", "motion", "rocking", "report", "outputs",
            "table", "sensors", "theory", "sliding", "ensemble", "floor"}

#: Keys of a scene's ``[sliding]`` section (friction coefficients, dimensionless).
SLIDING_KEYS = {"static_friction", "dynamic_friction"}

#: Studies that recompute one of the report's tables (a ``[study]`` section).
STUDY_KINDS = {"report-table": {"table", "columns", "seed"}, "report-figure": {"figure"},
               "pitch-repeatability": {"phases"}, "teaching": {"item"},
               # the keys are read by shaketable.scenes.spectrum
               "overturning-spectrum": {"pulse", "block", "alpha", "p", "cor", "omega_over_p",
                                        "ceiling", "scan_step", "tolerance", "reference",
                                        "method"},
               # the keys are read by shaketable.scenes.mode_map
               "mode-map": {"record", "pga", "aspect_ratios", "frictions", "height", "cor"},
               "stacks": set()}   # stacks beside single blocks (scenes.stack)


class SceneError(ValueError):
    """A scene file that cannot be used; the message names the file and the key."""


@dataclass(frozen=True)
class Scene:
    """A validated experiment.

    Attributes
    ----------
    name, source, description : str
        Identification; ``source`` names the report's figure or table.
    block : Block
    motion : dict
        The ``[motion]`` table with ``kind`` checked and values converted to SI.
    cors : tuple of float
        Coefficients of restitution to run (one run each) [-]; with
        ``cor = "calibration.json"`` the calibrated mean COR.
    theta0 : float
        Initial rotation [rad] (the first of ``theta0s``).
    blocks : tuple of Block
        ``size = [...]``: every block to run (one run each); ``(block,)`` for one size.
    theta0s : tuple of tuple of float
        ``theta0 = [...]``: for each block of ``blocks``, every initial rotation to run
        [rad] (``"0.5 alpha"`` is a multiple of that block's own alpha); ``()`` when
        the scene gives one block and one theta0.
    theta_dot0 : float
        Initial angular velocity [rad/s].
    duration : float or None
        Run length [s].
    method : str
    options : dict
        Further keyword arguments for :func:`shaketable.models.api`.
    report : dict
        The report's values to compare with.
    outputs : dict
    table : TableSetup or None
        ``[table]``, parsed (:func:`shaketable.lab.stage.table_setup_from_dict`);
        ``None`` when the scene has no (or an empty) ``[table]``: the block feels
        the commanded motion.
    sensors : shaketable.lab.sensors.Sensors or None
        ``[sensors]``, parsed by the parser registered for it
        (:func:`shaketable.scenes.virtual_test.sensors_from_dict`); ``None`` when
        the scene has none (an empty section means the default instruments).
    theory : shaketable.scenes.virtual_test.TheorySetup or None
        ``[theory]``, parsed the same way; set (defaults included) whenever the
        scene has ``[sensors]``, ``None`` otherwise.
    static_friction : float or None
        ``block.static_friction``: mu_s for Section 2.1's sliding-or-rocking check; with a
        table motion the scene also runs the planar block (rest, slide, rock, slide-rock,
        flight) with this friction.
    dynamic_friction : float or None
        ``block.dynamic_friction``: mu_d of that planar run (default mu_s).
    sliding : tuple of (float, float)
        ``[sliding]``: the (mu_s, mu_d) pairs of the sliding runs (empty: none).
    path : str
        Where the scene was read from.
    calibrated_cor : CalibratedCor or None
        ``rocking.cor = "calibration.json"``: the calibrated COR, whose
        distribution :mod:`shaketable.scenes.run` runs as an ensemble.
    floor : shaketable.scenes.assess.FloorSetup or None
        ``[floor]``: the block stands on a floor of a building; the table motion is the
        ground motion and the block feels :func:`shaketable.ground.floor.floor_motion`.
    """

    name: str
    source: str
    description: str
    block: Block
    motion: dict
    cors: tuple
    theta0: float = 0.0
    theta_dot0: float = 0.0
    duration: float | None = None
    method: str = "fast"
    options: dict = field(default_factory=dict)
    report: dict = field(default_factory=dict)
    outputs: dict = field(default_factory=dict)
    table: TableSetup | None = None
    sensors: Any = None
    theory: Any = None
    static_friction: float | None = None
    dynamic_friction: float | None = None
    sliding: tuple = ()
    path: str = ""
    ensemble: dict = field(default_factory=dict)
    calibrated_cor: Any = None
    blocks: tuple = ()
    theta0s: tuple = ()
    floor: Any = None

    def variants(self) -> list:
        """The runs a scene asks for: ``(block, theta0 [rad], cor)`` for every block, then
        every initial rotation, then every COR (a single block and theta0: one per COR)."""
        blocks = self.blocks or (self.block,)
        starts = self.theta0s or ((self.theta0,),)
        return [(block, theta0, cor) for index, block in enumerate(blocks)
                for theta0 in starts[index] for cor in self.cors]

    def mode(self) -> str | None:
        """Sliding or rocking by Section 2.1 (mu_s against B/H), when ``static_friction`` is given."""
        if self.static_friction is None:
            return None
        ratio = self.block.width / self.block.height
        if self.static_friction > ratio:
            return (f"rocking: static friction {self.static_friction:g} > B/H = {ratio:.3f} "
                    "(Section 2.1): the block rocks before it can slide")
        return (f"SLIDING: static friction {self.static_friction:g} <= B/H = {ratio:.3f} "
                "(Section 2.1, Eq. 2-2): the block slides before it rocks; the rocking "
                "runs assume a base that cannot slide")


@dataclass(frozen=True)
class Study:
    """A scene that runs a study of the report or of the teaching gallery (``[study]``).

    Each kind reads its own keys (the others keep their defaults):

    Attributes
    ----------
    name, source, description : str
    kind : str
        One of :data:`STUDY_KINDS`: ``"report-table"``, ``"report-figure"``,
        ``"pitch-repeatability"``, ``"teaching"`` or ``"overturning-spectrum"``.
    table : str
        ``"report-table"``: which printed table, ``"table_3_1"``, ``"table_4_1"``,
        ``"table_4_2"`` or ``"table_4_3"``.
    columns : tuple of str
        ``"report-table"``: the columns to recompute (default all).
    seed : int
        ``"report-table"``: seed of the substitute artificial accelerograms.
    figure : str
        ``"report-figure"``: one of :data:`REPORT_FIGURES`.
    phases : int
        ``"pitch-repeatability"``: the number of pitch phases run per case.
    item : str
        ``"teaching"``: a gallery item registered with :func:`register_study_items`.
    path : str
        The scene file.
    spectrum : SpectrumSettings or None
        ``"overturning-spectrum"``: its validated inputs
        (:class:`shaketable.scenes.spectrum.SpectrumSettings`).
    mode_map : ModeMapSettings or None
        ``"mode-map"``: its validated inputs
        (:class:`shaketable.scenes.mode_map.ModeMapSettings`).
    """

    name: str
    source: str
    description: str
    kind: str
    table: str = ""
    columns: tuple = ()
    seed: int = 1
    figure: str = ""
    phases: int = 24
    item: str = ""
    path: str = ""
    spectrum: SpectrumSettings | None = None
    mode_map: ModeMapSettings | None = None


#: Names a study kind accepts for its ``item`` key, registered by the studies
#: themselves through the loader (:mod:`shaketable.scenes`), so that this parser
#: imports no study module: a function giving the names, called when a scene
#: of that kind is read.
STUDY_ITEMS: dict[str, Callable[[], Any]] = {}


def register_study_items(kind: str, items: Callable[[], Any]) -> None:
    """Declare the items a ``[study]`` of ``kind`` may name: a function returning them."""
    STUDY_ITEMS[kind] = items


#: Parsers of the stage sections that a pipeline module runs (``"sensors"``,
#: ``"theory"``), registered by the loader (:mod:`shaketable.scenes`), so that this
#: parser imports no pipeline module: ``parser(section: dict, where: str)`` returns
#: the section's frozen object or raises ValueError naming the key.
SECTION_PARSERS: dict[str, Callable[[dict, str], Any]] = {}


def register_section_parser(section: str, parser: Callable[[dict, str], Any]) -> None:
    """Declare the function that parses a scene's ``[section]`` into its object."""
    SECTION_PARSERS[section] = parser


def load_scene(path: str | Path, *, read: tuple[dict, str] | None = None) -> Scene | Study:
    """Read and validate a scene file.

    ``read``: the file's TOML data and text when the caller has read it already
    (:func:`shaketable.scenes.catalog.read_scene`): the file is then not read again.

    Raises
    ------
    SceneError
        With the file name, the key and what was expected.
    """
    path = Path(path)
    data, text = read_toml(path, "scene", SceneError) if read is None else read
    try:
        return scene_from_dict(data, where=str(path))
    except SceneError as error:
        raise SceneError(with_line(str(error), str(path), text)) from None


def with_line(message: str, where: str, text: str) -> str:
    """``message`` (``"WHERE: rocking.cor ..."``) with the line of the key it names in ``text``
    (:func:`shaketable.core.tomlfile.with_line` over the scene's sections): ``"scene.toml:
    rocking.cor must be ..., got 1.5 (line 9)"``."""
    return _with_line(message, where, text, (TOP_KEYS - {"name", "source", "description"})
                      | {"study", "stack"})


def scene_from_dict(data: dict, where: str = "<scene>") -> Scene | Study:
    """Validate a scene given as a dict (the parsed TOML); a ``[study]`` gives a :class:`Study`."""
    if "study" in data:
        return _study(data, where)
    if "stack" in data:   # a column of blocks: the parser registered for it (scenes.stack)
        return SECTION_PARSERS["stack"](data, where)
    _only(data, TOP_KEYS, where, "top level")
    for key in ("name", "block", "motion", "rocking"):
        if key not in data:
            raise SceneError(f"{where}: missing [{key}]" if key != "name"
                             else f"{where}: missing 'name' at the top level")
    blocks = _blocks(data["block"], where)
    block = blocks[0]
    static_friction = data["block"].get("static_friction")
    if static_friction is not None and (isinstance(static_friction, bool) or not isinstance(
            static_friction, (int, float)) or not 0 < static_friction < math.inf):
        raise SceneError(f"{where}: block.static_friction must be a positive number (the "
                         f"static coefficient of friction mu_s), got {static_friction!r}")
    dynamic_friction = data["block"].get("dynamic_friction")
    if dynamic_friction is not None:   # with static_friction, the planar block runs
        if static_friction is None:
            raise SceneError(f"{where}: block.dynamic_friction needs block.static_friction "
                             "(mu_s)")
        if isinstance(dynamic_friction, bool) or not isinstance(dynamic_friction, (int, float)) \
                or not 0 <= dynamic_friction <= static_friction:
            raise SceneError(f"{where}: block.dynamic_friction must be a number in [0, "
                             f"static_friction = {static_friction!r}] (mu_d), got "
                             f"{dynamic_friction!r}")
    motion = _motion(data["motion"], where)
    if data.get("theory") and "sensors" not in data:
        raise SceneError(f"{where}: [theory] compares a virtual test with theory; it needs "
                         "a [sensors] section")
    rocking = _table(data["rocking"], where, "rocking")
    _only(rocking, ROCKING_KEYS, where, "rocking")
    if "cor" not in rocking:
        raise SceneError(f"{where}: rocking.cor is missing (coefficient of restitution, 0-1)")
    calibrated = _calibrated_cor(rocking["cor"], where)     # cor = "calibration.json"
    cors = ([calibrated.mean] if calibrated is not None else
            rocking["cor"] if isinstance(rocking["cor"], list) else [rocking["cor"]])
    if not cors:
        raise SceneError(f"{where}: rocking.cor is an empty list; give a number in [0, 1] or a "
                         f"list of them")
    for cor in cors:
        if isinstance(cor, bool) or not isinstance(cor, (int, float)) or not 0 <= cor <= 1:
            raise SceneError(f"{where}: rocking.cor must be a number in [0, 1] or a list of "
                             f"them, got {rocking['cor']!r}")
    starts = rocking.get("theta0", "0 rad")
    starts = starts if isinstance(starts, list) else [starts]
    if not starts:
        raise SceneError(f"{where}: rocking.theta0 is an empty list; give an angle such as "
                         f"'0.5 alpha' or a list of them")
    try:
        theta0s = tuple(tuple(parse_angle_or_ratio(start, each.alpha,
                                                   where=f"{where}: rocking.theta0")
                              for start in starts) for each in blocks)
        theta0 = theta0s[0][0]
        theta_dot0 = 0.0
        if "theta_dot0" in rocking:
            theta_dot0 = parse(str(rocking["theta_dot0"]).replace("rad/s", "rad"), "angle",
                               where=f"{where}: rocking.theta_dot0")
        duration = (parse(rocking["duration"], "time", where=f"{where}: rocking.duration")
                    if "duration" in rocking else None)
    except ValueError as error:
        raise SceneError(str(error)) from None
    if motion["kind"] == "free" and duration is None:
        raise SceneError(f"{where}: rocking.duration is needed for free rocking, e.g. '8 s'")
    options = {}
    for key in ("subdivisions", "rtol"):
        if key in rocking:
            options[key] = rocking[key]
    report = _table(data.get("report", {}), where, "report")
    _only(report, set(REPORT_KEYS), where, "report")
    chosen = report.get("by_construction", [])
    if not isinstance(chosen, list) or not set(chosen) <= set(report) - {"by_construction"}:
        raise SceneError(f"{where}: report.by_construction must list keys of [report] that "
                         f"match by construction (e.g. [\"t_unstable\"]), got {chosen!r}")
    outputs = {"figure": True, "csv": True, "parquet": False, "svg": False}
    given = _table(data.get("outputs", {}), where, "outputs")
    _only(given, OUTPUT_KEYS, where, "outputs")
    for key, value in given.items():
        if key == "time_range":
            given = dict(given, time_range=_time_range(value, where))
        else:
            _checked(flag, f"{where}: outputs.{key}", value)
    outputs.update(given)
    name = data["name"]
    if not isinstance(name, str) or not name:
        raise SceneError(f"{where}: 'name' must be a non-empty string")
    _check_folder_name(name, where)
    return Scene(name=name, source=str(data.get("source", "")),
                 description=str(data.get("description", "")), block=block, motion=motion,
                 cors=tuple(float(c) for c in cors), theta0=theta0, theta_dot0=theta_dot0,
                 duration=duration, method=str(rocking.get("method", "fast")), options=options,
                 report=report, outputs=outputs,
                 table=_table_section(data.get("table", {}), where),
                 sensors=_stage_section(data, "sensors", where) if "sensors" in data else None,
                 theory=_stage_section(data, "theory", where) if "sensors" in data else None,
                 static_friction=None if static_friction is None else float(static_friction),
                 dynamic_friction=None if dynamic_friction is None else float(dynamic_friction),
                 sliding=_sliding(data, motion, where),
                 path=where, ensemble=_ensemble_section(data, where),
                 calibrated_cor=calibrated,
                 floor=_stage_section(data, "floor", where) if "floor" in data else None,
                 **_variants(blocks, theta0s, data, where))


def _calibrated_cor(value: object, where: str):
    """``rocking.cor = "path/calibration.json"`` (relative to the scene file): the
    :class:`~shaketable.calibration.uncertainty.CalibratedCor`, else None."""
    if not isinstance(value, str):
        return None
    from pathlib import Path

    from shaketable.calibration.uncertainty import CalibratedCor

    path = Path(value)
    if not path.is_absolute() and Path(where).parent.is_dir():
        path = Path(where).parent / path
    try:
        return CalibratedCor.from_json(path)
    except (OSError, ValueError) as error:
        raise SceneError(f"{where}: rocking.cor {value!r}: a number in [0, 1], a list of them, "
                         f"or a calibration.json of `shaketable calibrate` ({error})") from None


def _variants(blocks: tuple, theta0s: tuple, data: dict, where: str) -> dict:
    """``blocks`` and ``theta0s`` of a scene that lists several (empty for one of each)."""
    if len(blocks) == 1 and len(theta0s[0]) == 1:
        return {}
    for section in ("ensemble", "sliding"):
        if section in data:
            raise SceneError(f"{where}: [{section}] runs one block from one theta0; a list "
                             f"of block sizes or of theta0 cannot be combined with it")
    return {"blocks": blocks, "theta0s": theta0s}


def _sliding(data: dict, motion: dict, where: str) -> tuple:
    """``[sliding]``: the (mu_s, mu_d) pairs to run, one per dynamic_friction given."""
    if "sliding" not in data:
        return ()
    section = _table(data["sliding"], where, "sliding")
    _only(section, SLIDING_KEYS, where, "sliding")
    if motion["kind"] == "free":
        raise SceneError(f"{where}: [sliding] needs a table motion; free rocking has none")
    if "static_friction" not in section:
        raise SceneError(f"{where}: sliding.static_friction is missing (mu_s, e.g. 0.3)")
    static = section["static_friction"]
    dynamic = section.get("dynamic_friction", static)
    dynamics = dynamic if isinstance(dynamic, list) else [dynamic]
    if not dynamics:
        raise SceneError(f"{where}: sliding.dynamic_friction is an empty list")
    for name, value in [("static_friction", static)] + [("dynamic_friction", d)
                                                        for d in dynamics]:
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not 0 <= value < math.inf:
            raise SceneError(f"{where}: sliding.{name} must be a number >= 0 (a coefficient "
                             f"of friction), got {value!r}")
        if name == "dynamic_friction" and value > static:
            raise SceneError(f"{where}: sliding.dynamic_friction {value!r} must not exceed "
                             f"static_friction {static!r}")
    return tuple((float(static), float(d)) for d in dynamics)


def _check_folder_name(name: str, where: str) -> None:
    """The scene's name names its output folder: a path there could write anywhere."""
    from shaketable.core.files import folder_name_problem

    problem = folder_name_problem(name) if name else None
    if problem:
        raise SceneError(f"{where}: 'name' {name!r} {problem} (the name is the default output "
                         f"folder shaketable-out/<name>; use letters, digits, '-', '_', '.')")


def _study(data: dict, where: str) -> Study:
    _only(data, {"name", "source", "description", "study"}, where, "top level of a study")
    spec = _table(data["study"], where, "study")
    kind = spec.get("kind")
    if kind not in STUDY_KINDS:
        raise SceneError(f"{where}: study.kind must be one of {', '.join(STUDY_KINDS)}, "
                         f"got {kind!r}")
    _only({k: v for k, v in spec.items() if k != "kind"}, STUDY_KINDS[kind], where, "study")
    _check_folder_name(str(data.get("name", "")), where)
    common = dict(name=str(data.get("name", "")), source=str(data.get("source", "")),
                  description=str(data.get("description", "")), kind=kind, path=where)
    if kind == "overturning-spectrum":
        from shaketable.scenes.spectrum import spectrum_settings

        try:
            return Study(**common, spectrum=spectrum_settings(spec, where))
        except ValueError as error:
            raise SceneError(str(error)) from None
    if kind == "mode-map":
        from shaketable.scenes.mode_map import mode_map_settings

        try:
            return Study(**common, mode_map=mode_map_settings(spec, where))
        except ValueError as error:
            raise SceneError(str(error)) from None
    if kind == "stacks":
        return Study(**common)
    if kind == "pitch-repeatability":
        phases = _checked(count, f"{where}: study.phases", spec.get("phases", 24), 2)
        return Study(**common, phases=phases)
    if kind == "teaching":
        items = STUDY_ITEMS[kind]() if kind in STUDY_ITEMS else ()
        if spec.get("item") not in items:
            raise SceneError(f"{where}: study.item must be one of {', '.join(items)}, got "
                             f"{spec.get('item')!r}")
        return Study(**common, item=spec["item"])
    if kind == "report-figure":
        if spec.get("figure") not in REPORT_FIGURES:
            raise SceneError(f"{where}: study.figure must be one of "
                             f"{', '.join(repr(name) for name in REPORT_FIGURES)}, got "
                             f"{spec.get('figure')!r}")
        return Study(**common, figure=spec["figure"])
    table = spec.get("table")
    if table not in ("table_3_1", "table_4_1", "table_4_2", "table_4_3", "table_4_4"):
        raise SceneError(f"{where}: study.table must be table_3_1, table_4_1, table_4_2 or "
                         f"table_4_3, got {table!r}")
    seed = _checked(count, f"{where}: study.seed", spec.get("seed", 1))
    columns = spec.get("columns", ())
    if not isinstance(columns, list) or not all(isinstance(c, str) for c in columns):
        if columns != ():
            raise SceneError(f"{where}: study.columns must be a list of column names, got "
                             f"{columns!r}")
    return Study(**common, table=table, columns=tuple(columns), seed=seed)


# --------------------------------------------------------------------------- helpers
def _ensemble_section(data: dict, where: str) -> dict:
    """The raw ``[ensemble]`` section, validated now (scenes.ensemble)."""
    from shaketable.scenes.ensemble import ensemble_options

    section = _table(data.get("ensemble", {}), where, "ensemble")
    if section or "ensemble" in data:
        try:
            ensemble_options(section, where)
        except ValueError as error:
            raise SceneError(str(error)) from None
        return dict(section) or {"members": 200}
    return {}


def _stage_section(data: dict, section: str, where: str) -> Any:
    """``[sensors]`` or ``[theory]``, parsed once by its registered parser (errors at load)."""
    value = _table(data.get(section, {}), where, section)
    if section not in SECTION_PARSERS:
        raise SceneError(f"{where}: [{section}] cannot be read: no parser is registered "
                         "for it (import shaketable.scenes, which registers them)")
    try:
        return SECTION_PARSERS[section](value, where)
    except ValueError as error:
        raise SceneError(str(error)) from None


def _table_section(value, where) -> TableSetup | None:
    """``[table]`` parsed into a :class:`~shaketable.lab.stage.TableSetup` (``None``: none)."""
    from shaketable.lab.stage import table_setup_from_dict

    value = _table(value, where, "table")
    if not value:
        return None
    try:
        return table_setup_from_dict(value, where)
    except ValueError as error:
        raise SceneError(str(error)) from None


def _time_range(value, where) -> tuple:
    """``outputs.time_range``: two times with units, start before stop -> (start, stop) [s]."""
    if not isinstance(value, list) or len(value) != 2:
        raise SceneError(f"{where}: outputs.time_range must be two times such as "
                         f"[\"0 s\", \"42 s\"], got {value!r}")
    try:
        start, stop = (parse(item, "time", where=f"{where}: outputs.time_range")
                       for item in value)
    except ValueError as error:
        raise SceneError(str(error)) from None
    if not stop > start:
        raise SceneError(f"{where}: outputs.time_range must end after it starts, got {value!r}")
    return (start, stop)


def _table(value, where, section):
    if not isinstance(value, dict):
        raise SceneError(f"{where}: [{section}] must be a table, got {value!r}")
    return value


def _only(table: dict, allowed: set, where: str, section: str) -> None:
    check_keys(table, allowed, where, f"[{section}]", SceneError)


def _checked(check: Callable[..., Any], name: str, *args: Any) -> Any:
    """``check(name, *args)`` of :mod:`shaketable.core.validation`, its error a SceneError."""
    try:
        return check(name, *args)
    except ValueError as error:
        raise SceneError(str(error)) from None


def _blocks(table, where) -> tuple:
    """``[block]``: one block, or one per size of ``size = ["30x6in", "60x12in"]``."""
    table = _table(table, where, "block")
    sizes = table.get("size")
    if not isinstance(sizes, list):
        return (_block(table, where),)
    if not sizes:
        raise SceneError(f"{where}: block.size is an empty list; give a size such as "
                         f"'30x6in' or a list of them")
    return tuple(_block(dict(table, size=size), where) for size in sizes)


def _block(table, where) -> Block:
    table = _table(table, where, "block")
    _only(table, {"size", "height", "width", "rods", "static_friction", "dynamic_friction"},
          where, "block")
    rods = sections.rods(table["rods"], where, "block.rods", SceneError) \
        if "rods" in table else None
    if "size" in table:
        if "height" in table or "width" in table:
            raise SceneError(f"{where}: [block] gives 'size' and height/width; give one")
        return sections.sized_block(table["size"], where, "block.size", rods, SceneError)
    if "height" not in table or "width" not in table:
        raise SceneError(f"{where}: [block] needs size = '30x6in' or height and width")
    height, width = (sections.quantity(table[key], "length", where, f"block.{key}", SceneError)
                     for key in ("height", "width"))
    try:
        return Block(height, width, rods)
    except ValueError as error:
        raise SceneError(f"{where}: block: {error}") from None


_MOTION_UNITS = {
    "frequency": "frequency", "horizontal": "acceleration", "vertical": "acceleration",
    "phase": "angle", "duration": "time", "dt": "time", "ramp": "time", "start": "time",
    "pga": "acceleration", "vertical_pga": "acceleration", "amplitude": "acceleration",
    "acceleration": "acceleration", "pulse_duration": "time",
}


def _motion(table, where) -> dict:
    table = dict(_table(table, where, "motion"))
    kind = table.pop("kind", None)
    if kind not in MOTION_KEYS:
        raise SceneError(f"{where}: motion.kind must be one of {', '.join(MOTION_KEYS)}, "
                         f"got {kind!r}")
    _only(table, MOTION_KEYS[kind], where, f"motion ({kind})")
    converted = {"kind": kind}
    for key, value in table.items():
        unit_kind = _MOTION_UNITS.get(key)
        if unit_kind is not None and not (kind == "record" and key == "vertical"):
            try:
                value = parse(value, unit_kind, where=f"{where}: motion.{key}")
            except ValueError as error:
                raise SceneError(str(error)) from None
        converted[key] = value
    if kind == "record" and "pga" in converted:   # as simulate --pga: scaled to it
        if "scale" in converted:
            raise SceneError(f"{where}: motion.pga and motion.scale both scale the record: "
                             "give one")
        if not (converted["pga"] > 0 and math.isfinite(converted["pga"])):
            raise SceneError(f"{where}: motion.pga must be above 0, got {table['pga']!r}")
    if kind == "record" and ("name" in converted) == ("file" in converted):
        raise SceneError(f"{where}: a record motion needs exactly one of motion.name "
                         "(a bundled record) or motion.file")
    if kind == "harmonic" and not {"frequency", "horizontal", "duration"} <= set(converted):
        raise SceneError(f"{where}: a harmonic motion needs frequency, horizontal and duration")
    if kind == "impulses" and not {"times", "velocity_steps", "duration"} <= set(converted):
        raise SceneError(f"{where}: an impulses motion needs times, velocity_steps (lists, "
                         "e.g. ['0.1 s', '0.5 s'] and ['0.2 m/s', '-0.2 m/s']) and duration")
    for key in ("times", "velocity_steps") if kind == "impulses" else ():
        if not isinstance(converted[key], list) or not converted[key]:
            raise SceneError(f"{where}: motion.{key} must be a list of values with units, "
                             f"got {converted[key]!r}")
    if kind == "artificial" and not {"preset", "seed"} <= set(converted):
        raise SceneError(f"{where}: an artificial motion needs preset and seed")
    return converted
