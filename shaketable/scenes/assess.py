"""An object to assess, written as a TOML file (``shaketable assess OBJECT.toml``).

::

    name = "lab-cabinet"                 # one folder name
    description = "..."
    [object]     size = "2x0.5m" (height x width; the width in the direction of shaking)
                 mass = "400 kg"  or  density = "2400 kg/m3" with depth = "0.6 m"
                 friction = [0.3, 0.5]   (low, high; mu_s = mu_d; or one number)
                 cor = 0.9  or  cor = "calibration.json" (of `shaketable calibrate`, for this
                 block: its height and width must match)
    [location]   floor = 3               (0 or no [location]: at grade)
    [building]   period = "0.5 s", height = "17.5 m", storeys = 5, damping = 0.05,
                 shape = "linear" | "shear-beam", modes = 1
    [demand]     records = ["pacoima-dam-s16e", ...] (bundled names), pga = ["0.2 g", "0.4 g"],
                 names = ["design", "MCE"], S_DS = 1.0,
                 artificial = {preset = "B-1", count = 4}
                 (or S_DS alone: the levels 0.4 S_DS "design" and 0.6 S_DS "MCE")
    [criteria]   clearance = "100 mm", acceptable = 0.05, slide_friction = 0.15,
                 hazard = "hazard.csv" (PGA), years = 50
    [codes]      a_p = 1.0, R_p = 2.5, I_p = 1.0, FC = 1.0

Errors name the file, the key and its line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from shaketable.core.constants import MAX_FRICTION, G
from shaketable.core.geometry import Block
from shaketable.core.tomlfile import key_line, read_toml
from shaketable.core.units import parse
from shaketable.core.validation import check_keys, integer, unknown_keys
from shaketable.ground import records
from shaketable.ground.artificial import PRESETS
from shaketable.ground.floor import SHAPES, Building
from shaketable.scenes.parse import SceneError
from shaketable.studies.assess import (
    DEFAULT_RECORDS,
    AssessedObject,
    Assessment,
    Criteria,
    Demand,
)

SECTIONS = {
    "object": {"size", "height", "width", "mass", "density", "depth", "friction", "cor"},
    "location": {"floor"},
    "building": {"period", "height", "storeys", "damping", "shape", "modes"},
    "demand": {"records", "pga", "names", "S_DS", "artificial"},
    "criteria": {"clearance", "acceptable", "slide_friction", "hazard", "years"},
    "codes": {"a_p", "R_p", "I_p", "FC"},
}
TOP = {"name", "description"} | set(SECTIONS)


class _Error(SceneError):
    """A bad value, with the dotted key it came from (for the line number)."""

    def __init__(self, key: str, message: str):
        super().__init__(message)
        self.key = key


def load_assessment(path: str | Path) -> Assessment:
    """Read an object file into an :class:`~shaketable.studies.assess.Assessment`.

    Raises
    ------
    SceneError
        Naming the file, the key and its line.
    FileNotFoundError
        A missing file (the object file, a calibration or hazard file).
    """
    path = Path(path)
    data, text = read_toml(path, "object file", SceneError)
    try:
        return assessment_from_dict(data, path.parent)
    except _Error as error:
        line = key_line(text, error.key.split("."))
        suffix = "" if line is None else f" (line {line})"
        raise SceneError(f"{path}: {error.key}: {error}{suffix}") from None


def _checked(check, key: str, value, *bounds, name: str = ""):
    """``check(name, value, *bounds)`` of :mod:`shaketable.core.validation`, its ValueError
    raised with the dotted ``key`` (for the line number): ``key: [name ]must be ...``."""
    try:
        return check(name, value, *bounds)
    except ValueError as error:
        raise _Error(key, str(error).lstrip()) from None


def _number(value, key: str, low: float, high: float, *, low_open=False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not math.isfinite(value):
        raise _Error(key, f"must be a number, got {value!r}")
    if value < low or value > high or (low_open and value == low):
        raise _Error(key, f"must be in {'(' if low_open else '['}{low:g}, {high:g}], "
                          f"got {value!r}")
    return float(value)


def _quantity(value, kind: str, key: str) -> float:
    try:
        return parse(value, kind, where="")
    except ValueError as error:
        raise _Error(key, str(error).removeprefix(": ")) from None


def _section(data: dict, name: str) -> dict:
    table = data.get(name, {})
    if not isinstance(table, dict):
        raise _Error(name, f"[{name}] must be a table")
    unknown = unknown_keys(table, SECTIONS[name])
    if unknown:
        raise _Error(f"{name}.{unknown[0]}", f"unknown key; [{name}] takes "
                                              f"{', '.join(sorted(SECTIONS[name]))}")
    return table


def assessment_from_dict(data: dict, folder: Path | None = None) -> Assessment:
    """Validate the parsed TOML (``folder``: where relative file names are read from)."""
    folder = Path(".") if folder is None else folder
    if "stack" in data or "stacks" in data:   # a column of blocks is the stack model's
        key = "stack" if "stack" in data else "stacks"
        raise _Error(key, "assess takes one object, not a stack of blocks: for a column "
                          "use `shaketable simulate --stack` (one motion) or a sweep with "
                          "[stacks] and `shaketable risk` (fragility and risk; docs/stack.md, "
                          "docs/sweeps.md)")
    unknown = unknown_keys(data, TOP)
    if unknown:
        raise _Error(unknown[0], f"unknown key at the top level; expected "
                                 f"{', '.join(sorted(TOP))}")
    name = data.get("name")
    if not isinstance(name, str) or not name or any(c in name for c in "/\\") or ".." in name:
        raise _Error("name", f"must be one folder name (no '/', '\\\\' or '..'), got {name!r}")
    if "object" not in data:
        raise _Error("object", "missing [object]")
    obj = _object(_section(data, "object"), folder)
    building, floor = _building(data)
    demand = _demand(_section(data, "demand"))
    criteria = _criteria(_section(data, "criteria"), _section(data, "codes"), folder)
    return Assessment(name, obj, demand, criteria, building, floor,
                      str(data.get("description", "")))


def _object(table: dict, folder: Path) -> AssessedObject:
    if "size" in table:
        try:
            block = Block.parse(table["size"])
        except ValueError as error:
            raise _Error("object.size", str(error)) from None
    elif "height" in table and "width" in table:
        block = Block(_quantity(table["height"], "length", "object.height"),
                      _quantity(table["width"], "length", "object.width"))
    else:
        raise _Error("object", "needs size = '2x0.5m' (height x width) or height and width")
    if "mass" in table:
        mass = _quantity(table["mass"], "mass", "object.mass")
    elif "density" in table:
        density = _quantity(table["density"], "density", "object.density")
        if "depth" not in table:
            raise _Error("object.density", "needs depth (the size across the shaking)")
        mass = density * block.height * block.width * _quantity(table["depth"], "length",
                                                                "object.depth")
    else:
        raise _Error("object", "needs mass = '400 kg' or density with depth")
    if not mass > 0:
        raise _Error("object.mass", f"must be positive, got {mass!r} kg")
    friction = table.get("friction")
    if friction is None:
        raise _Error("object", "needs friction = [low, high] (mu_s = mu_d)")
    values = friction if isinstance(friction, list) else [friction, friction]
    if len(values) != 2:
        raise _Error("object.friction", f"must be one number or [low, high], got {friction!r}")
    low, high = (_number(v, "object.friction", 0.0, MAX_FRICTION, low_open=True) for v in values)
    if low > high:
        raise _Error("object.friction", f"low ({low}) must not exceed high ({high})")
    cor, source = _cor(table.get("cor"), block, folder)
    return AssessedObject(block, mass, (low, high), cor, source)


def _cor(value, block: Block, folder: Path) -> tuple[float, str]:
    if value is None:
        raise _Error("object", "needs cor = 0.9 (a number in (0, 1]) or a calibration file")
    if not isinstance(value, str):
        return _number(value, "object.cor", 0.0, 1.0, low_open=True), "given"
    import json

    from shaketable.calibration.uncertainty import CalibratedCor

    path = Path(value) if Path(value).is_absolute() else folder / value
    try:
        calibrated = CalibratedCor.from_json(path)
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise _Error("object.cor", f"no such calibration file {str(path)!r}") from None
    except ValueError as error:
        raise _Error("object.cor", str(error)) from None
    for key, size in (("block_height [m]", block.height), ("block_width [m]", block.width)):
        other = data.get(key)
        if isinstance(other, (int, float)) and not math.isclose(other, size, rel_tol=1e-6):
            raise _Error("object.cor", f"the calibration {str(path)!r} is of another block "
                                       f"({key} {other:g}, this object {size:g} m)")
    return calibrated.mean, f"calibration {path.name} (mean COR)"


def _building(data: dict) -> tuple[Building | None, int]:
    location = _section(data, "location")
    floor = location.get("floor", 0)
    if isinstance(floor, bool) or not isinstance(floor, int) or floor < 0:
        raise _Error("location.floor", f"must be an integer >= 0 (0: at grade), got {floor!r}")
    if "building" not in data:
        if floor:
            raise _Error("location.floor", "a floor needs a [building]")
        return None, 0
    table = _section(data, "building")
    for key in ("period", "height", "storeys"):
        if key not in table:
            raise _Error("building", f"needs {key}")
    period = _quantity(table["period"], "time", "building.period")
    if not period > 0:
        raise _Error("building.period", f"must be positive, got {table['period']!r}")
    height = _quantity(table["height"], "length", "building.height")
    if not height > 0:
        raise _Error("building.height", f"must be positive, got {table['height']!r}")
    storeys = _checked(integer, "building.storeys", table["storeys"], 1, 200)
    if floor > storeys:
        raise _Error("location.floor", f"floor {floor} is above the roof (floor {storeys} of "
                                       f"a {storeys}-storey building)")
    damping = _number(table.get("damping", 0.05), "building.damping", 0.0, 0.99)
    shape = table.get("shape", "linear")
    if shape not in SHAPES:
        raise _Error("building.shape", f"must be one of {', '.join(SHAPES)}, got {shape!r}")
    modes = table.get("modes", 1)
    if isinstance(modes, bool) or not isinstance(modes, int) or not 1 <= modes <= storeys \
            or (shape == "linear" and modes != 1):
        raise _Error("building.modes", f"must be 1 for the linear shape, 1..{storeys} for the "
                                       f"shear beam, got {modes!r}")
    return Building(period, height, storeys, damping, shape, modes), floor


def _demand(table: dict) -> Demand:
    names = table.get("records", list(DEFAULT_RECORDS))
    if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
        raise _Error("demand.records", f"must be a list of record names, got {names!r}")
    known = records.available()
    for name in names:
        if name not in known:
            raise _Error("demand.records", f"unknown record {name!r}; bundled: "
                                           f"{', '.join(known)}")
    s_ds = table.get("S_DS")
    if s_ds is not None:
        s_ds = _number(s_ds, "demand.S_DS", 0.0, 5.0, low_open=True)
    if "pga" in table:
        levels_in = table["pga"] if isinstance(table["pga"], list) else [table["pga"]]
        levels = tuple(_quantity(v, "acceleration", "demand.pga") for v in levels_in)
        if not levels or any(not v > 0 for v in levels) or list(levels) != sorted(levels):
            raise _Error("demand.pga", "must be positive accelerations, increasing")
        default_names = tuple(f"{v / G:.3g} g" for v in levels)
    elif s_ds is not None:  # ASCE 7-16 Eq. 11.4-5 at T = 0; MCE_R = 1.5 x design (11.4.7)
        levels = (0.4 * s_ds * G, 0.6 * s_ds * G)
        default_names = ("design", "MCE")
    else:
        raise _Error("demand", "needs pga = ['0.2 g', ...] or S_DS")
    level_names = table.get("names", list(default_names))
    if not isinstance(level_names, list) or len(level_names) != len(levels) \
            or not all(isinstance(n, str) and n for n in level_names):
        raise _Error("demand.names", f"must be one name per level ({len(levels)}), got "
                                     f"{level_names!r}")
    preset, count = None, 0
    if "artificial" in table:
        spec = table["artificial"]
        if not isinstance(spec, dict) or set(spec) - {"preset", "count"}:
            raise _Error("demand.artificial", "must be {preset = 'B-1', count = 4}")
        preset = spec.get("preset", "B-1")
        if preset not in PRESETS:
            raise _Error("demand.artificial", f"unknown preset {preset!r}; expected "
                                              f"{', '.join(PRESETS)}")
        count = _checked(integer, "demand.artificial", spec.get("count", 4), 1, 100,
                         name="count")
    if not names and not count:
        raise _Error("demand.records", "the suite is empty: give records or artificial")
    return Demand(tuple(names), levels, tuple(level_names), s_ds, preset, count)


def _criteria(table: dict, code: dict, folder: Path) -> Criteria:
    clearance = None
    if "clearance" in table:
        clearance = _quantity(table["clearance"], "length", "criteria.clearance")
        if not clearance > 0:
            raise _Error("criteria.clearance", f"must be positive, got {table['clearance']!r}")
    acceptable = _number(table.get("acceptable", 0.05), "criteria.acceptable", 0.0, 1.0)
    slide = table.get("slide_friction")
    if slide is not None:
        slide = _number(slide, "criteria.slide_friction", 0.0, MAX_FRICTION, low_open=True)
    hazard = None
    if "hazard" in table:
        from shaketable.sweeps.risk import read_hazard_curve

        path = Path(str(table["hazard"]))
        path = path if path.is_absolute() else folder / path
        try:
            hazard = read_hazard_curve(path)
        except (OSError, ValueError) as error:
            raise _Error("criteria.hazard", str(error)) from None
        if hazard.measure != "pga":
            raise _Error("criteria.hazard", f"the hazard curve must be in pga, got "
                                            f"{hazard.measure!r}")
    years = _number(table.get("years", 50.0), "criteria.years", 0.0, 1e4, low_open=True)
    return Criteria(clearance, acceptable, slide, hazard, years,
                    a_p=_number(code.get("a_p", 1.0), "codes.a_p", 0.0, 10.0, low_open=True),
                    r_p=_number(code.get("R_p", 2.5), "codes.R_p", 0.0, 20.0, low_open=True),
                    i_p=_number(code.get("I_p", 1.0), "codes.I_p", 0.0, 5.0, low_open=True),
                    fc=_number(code.get("FC", 1.0), "codes.FC", 1.0, 5.0))


@dataclass(frozen=True)
class FloorSetup:
    """A scene's ``[floor]``: the block stands on ``floor`` of ``building``."""

    building: Building
    floor: int


#: Keys of a scene's ``[floor]`` section: the floor and the building's keys.
FLOOR_KEYS = {"floor"} | SECTIONS["building"]


def floor_from_dict(section: dict, where: str) -> FloorSetup:
    """A scene's ``[floor]`` (``floor = 3``, ``period = "0.6 s"``, ``height = "17.5 m"``,
    ``storeys = 5``, ``damping``, ``shape``, ``modes``): errors name ``floor.KEY``."""
    check_keys(section, FLOOR_KEYS, where, "[floor]", SceneError)
    if "floor" not in section:
        raise SceneError(f"{where}: floor.floor is missing (the floor the block stands on, "
                         f"1..storeys)")
    data = {"location": {"floor": section["floor"]},
            "building": {k: v for k, v in section.items() if k != "floor"}}
    try:
        building, floor = _building(data)
    except _Error as error:
        key = "floor." + error.key.split(".")[-1] if "." in error.key else "floor"
        raise SceneError(f"{where}: {key}: {error}") from None
    assert building is not None
    return FloorSetup(building, floor)
