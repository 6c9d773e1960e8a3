"""What the classroom page computes: its fields -> a scene -> the runs -> what is drawn.

The page's inputs are :class:`Settings`, the text of its fields as a teacher types them
(``"30 in"``, ``"0.5 g"``, ``"2 Hz"``). :func:`scene_data` checks each field and turns
them into a scene (the dict a scene file holds, units written out), :func:`compute` runs
that scene with the scene pipeline (:func:`shaketable.scenes.run.run_scene`, which calls
:func:`shaketable.models.api.simulate`) and returns a :class:`Picture`: the block
outlines frame by frame, the table's displacement, the theta/alpha traces, the ground
acceleration, the mode band, the verdicts and the key numbers. :func:`scene_toml` writes
the scene as a file that ``shaketable run`` reproduces: what the page shows is a run of the
scene it saves, by construction.

Nothing here imports a web library: the page (:mod:`shaketable.classroom.page`) only draws
what these functions return, and the tests call them without a browser.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields, replace

import numpy as np

from shaketable.core.constants import LENGTH_UNITS, G
from shaketable.core.equality import fields_equal
from shaketable.core.units import parse

__all__ = ["COMPARE", "FIELD_LABELS", "FRAME_STEP", "LESSONS", "MOTIONS", "PULSE_SHAPES",
           "FieldError", "Lesson", "Picture", "Settings", "check", "compute", "key_numbers",
           "scene_data", "scene_toml"]

#: Table motions offered: none (the block released from theta0), a sine, one pulse, a
#: bundled record.
MOTIONS = ("free", "harmonic", "pulse", "record")

#: Pulse shapes offered: those a scene's ``[motion]`` holds (``kind = "half-sine"`` and
#: ``"constant-pulse"``), so that a saved scene reproduces the page.
PULSE_SHAPES = ("half-sine", "constant")

#: What the second block differs by: nothing (one block), its COR, its release angle, or
#: its size (a geometrically similar block: same H/B, the height given).
COMPARE = ("none", "cor", "theta0", "size")

#: Simulated time between two frames of the drawing [s]: 100 frames a simulated second,
#: enough for real time at 20 redraws a second and for playback slowed 5 times.
FRAME_STEP = 0.01

#: Longest run the page computes [s] (a slider move must redraw at once).
MAX_DURATION = 120.0

#: The 12 Hz pitch of the report's table (Section 3.7 (2)): frequency, angular
#: acceleration and seed, as the bundled scenes fig-3-5 and fig-3-7 write it.
PITCH = {"frequency": "12 Hz", "amplitude": "0.22 rad/s2", "seed": 1}

#: The label of each field (messages name it).
FIELD_LABELS = {
    "height": "height", "width": "width", "cor": "COR", "static_friction": "μs",
    "dynamic_friction": "μd", "frequency": "frequency", "amplitude": "amplitude",
    "vertical": "vertical amplitude", "pulse_amplitude": "pulse amplitude",
    "pulse_length": "pulse length", "record_scale": "scale", "target_pga": "target PGA",
    "duration": "duration", "theta0": "release angle θ0", "second": "second block",
}


@dataclass(frozen=True)
class Settings:
    """The page's inputs, as typed: dimensional values are text with their unit.

    Attributes
    ----------
    height, width : str
        Block height and width with a length unit (``"30 in"``, ``"0.5 m"``).
    cor : str
        Coefficient of restitution [-], a number in [0, 1], or ``"housner"`` for
        Housner's 1 - 1.5 sin^2 alpha.
    friction : bool
        False: the block rocks on a base that cannot slide (the report's model). True:
        the planar block (rest, slide, rock, slide-rock, flight) with Coulomb friction
        ``static_friction`` and ``dynamic_friction`` [-].
    motion : str
        One of :data:`MOTIONS`.
    frequency, amplitude, vertical : str
        Harmonic motion: frequency [Hz], horizontal and in-phase vertical amplitudes
        (``"0.3 g"``, ``"2 m/s2"``).
    pulse_shape, pulse_amplitude, pulse_length : str
        Pulse: one of :data:`PULSE_SHAPES`, its acceleration and length.
    record, record_scale, target_pga, record_vertical : str, str, str, bool
        Bundled record: its name, a factor on it [-], or (when not empty) the PGA it is
        scaled to; with or without its vertical component.
    pitch : bool
        The table pitches at 12 Hz, 0.22 rad/s^2 (:data:`PITCH`, Section 3.7 (2)).
    duration : str
        Length of the run (harmonic, pulse, free rocking; empty for a record: the whole
        record).
    theta0 : str
        Release angle: ``"0.5 alpha"``, ``"3 deg"`` or ``"0.05 rad"``.
    compare, second : str
        A second block differing by one of :data:`COMPARE`, and its value: a COR, a
        release angle, or a height (same H/B).
    """

    height: str = "30 in"
    width: str = "6 in"
    cor: str = "0.925"
    friction: bool = False
    static_friction: str = "0.5"
    dynamic_friction: str = "0.4"
    motion: str = "harmonic"
    frequency: str = "2 Hz"
    amplitude: str = "0.25 g"
    vertical: str = "0 g"
    pulse_shape: str = "half-sine"
    pulse_amplitude: str = "0.5 g"
    pulse_length: str = "0.2 s"
    record: str = "pacoima-dam-s74w"
    record_scale: str = "1"
    target_pga: str = ""
    record_vertical: bool = True
    pitch: bool = False
    duration: str = "10 s"
    theta0: str = "0 alpha"
    compare: str = "none"
    second: str = ""


class FieldError(ValueError):
    """A field's value cannot be used: ``field`` names it (a :class:`Settings` attribute)."""

    def __init__(self, name: str, message: str):
        super().__init__(message)
        self.field = name


@dataclass(frozen=True)
class Lesson:
    """One of the page's lessons: two blocks that differ by one thing.

    ``scene`` names the bundled scene whose parameters it uses (``shaketable run NAME``
    runs the same blocks), ``look_for`` says what the class should watch.
    """

    title: str
    scene: str
    look_for: str
    settings: Settings


#: The three lessons, with the parameters of the bundled teaching scenes.
LESSONS = {
    "period": Lesson(
        "The period grows with the amplitude", "teaching-period-grows",
        "Both blocks are the same 36 × 9 in block rocking freely without losses. Watch the "
        "trace: the one released from 0.8 α swings slower than the one from 0.2 α — a "
        "rocking block has no fixed period (Eq. 2-5).",
        Settings(height="36 in", width="9 in", cor="1", motion="free", duration="6 s",
                 theta0="0.2 alpha", compare="theta0", second="0.8 alpha")),
    "lower-cor": Lesson(
        "A lower COR can raise the response", "teaching-lower-cor",
        "The same 6 × 2 ft block under Pacoima Dam S74W, once with COR 1.0 and once with "
        "0.93. The block that loses more energy at each impact rocks to twice the angle: "
        "it meets the next strong pulse in a different phase (Section 4.3 (3)).",
        Settings(height="6 ft", width="2 ft", cor="1", motion="record",
                 record="pacoima-dam-s74w", duration="", compare="cor", second="0.93")),
    "small-falls": Lesson(
        "The small block falls first", "teaching-small-block-falls",
        "Two blocks of the same shape (H/B = 5), 4 ft and 12 ft tall, on the same record. "
        "The small one overturns near 4.3 s; the large one rocks and survives: a block "
        "three times larger needs a longer pulse to fall (Section 2.4 (1)).",
        Settings(height="4 ft", width="0.8 ft", cor="0.9", motion="record",
                 record="pacoima-dam-s74w", duration="", compare="size", second="12 ft")),
}


def _text(settings: Settings, name: str) -> str:
    return str(getattr(settings, name)).strip()


def _quantity(settings: Settings, name: str, kind: str, *, positive: bool = False,
              nonnegative: bool = False) -> float:
    """The SI value of field ``name``; a :class:`FieldError` naming it when unusable."""
    label = FIELD_LABELS[name]
    try:
        value = parse(_text(settings, name), kind, where=label)
    except ValueError as error:
        raise FieldError(name, str(error)) from None
    if not math.isfinite(value) or (positive and value <= 0) or (nonnegative and value < 0):
        need = "positive" if positive else "zero or more" if nonnegative else "finite"
        raise FieldError(name, f"{label} must be {need}, got {_text(settings, name)!r}")
    return value


def _number(settings: Settings, name: str, low: float, high: float, *,
            open_low: bool = False) -> float:
    label = FIELD_LABELS[name]
    text = _text(settings, name)
    try:
        value = float(text)
    except ValueError:
        raise FieldError(name, f"{label} must be a number (no unit), got {text!r}") from None
    if not (low < value if open_low else low <= value) or not value <= high:
        bracket = "(" if open_low else "["
        raise FieldError(name, f"{label} must be in {bracket}{low:g}, {high:g}], got {text!r}")
    return value


def _cor(settings: Settings, name: str, height: float, width: float) -> float:
    """A COR field: a number in [0, 1], or Housner's 1 - 1.5 sin^2 alpha [-]."""
    if _text(settings, name).lower() == "housner":
        return 1.0 - 1.5 * math.sin(math.atan2(width / 2, height / 2)) ** 2
    return _number(settings, name, 0.0, 1.0)


def _angle(settings: Settings, name: str, alpha: float) -> str:
    """A release angle field checked (``"0.5 alpha"``, ``"3 deg"``), as the scene writes it."""
    from shaketable.core.units import parse_angle_or_ratio

    label = FIELD_LABELS[name]
    text = _text(settings, name)
    try:
        value = parse_angle_or_ratio(text, alpha, where=label)
    except ValueError as error:
        raise FieldError(name, str(error)) from None
    if not abs(value) < math.pi / 2:
        raise FieldError(name, f"{label} must be below 90 deg in size, got {text!r}")
    return text


def _unit(text: str) -> str:
    """The unit of a length as typed (``"30 in"`` -> ``"in"``)."""
    return text.strip().lstrip("+-0123456789.eE ").strip().lower()


def _size(height: float, width: float, unit: str) -> str:
    """A block size in ``unit`` as a scene writes it (``"30x6in"``)."""
    factor = LENGTH_UNITS[unit]
    return f"{height / factor:.12g}x{width / factor:.12g}{unit}"


def scene_data(settings: Settings) -> dict:
    """The scene (the dict of a scene file, units written out) the page's settings describe.

    Raises
    ------
    FieldError
        A field that cannot be used; ``error.field`` names it, the message says why.
    """
    height = _quantity(settings, "height", "length", positive=True)
    width = _quantity(settings, "width", "length", positive=True)
    unit = _unit(_text(settings, "height"))
    alpha = math.atan2(width, height)
    cor: float | list = _cor(settings, "cor", height, width)
    theta0: str | list = _angle(settings, "theta0", alpha)
    size: str | list = _size(height, width, unit)
    if settings.compare not in COMPARE:
        raise FieldError("compare", f"compare must be one of {', '.join(COMPARE)}, got "
                                    f"{settings.compare!r}")
    if settings.compare == "cor":
        cor = [cor, _cor(settings, "second", height, width)]
    elif settings.compare == "theta0":
        theta0 = [theta0, _angle(settings, "second", alpha)]
    elif settings.compare == "size":
        second = _quantity(settings, "second", "length", positive=True)
        size = [size, _size(second, width * second / height, unit)]
    block: dict = {"size": size}
    if settings.friction:
        mu_s = _number(settings, "static_friction", 0.0, 10.0, open_low=True)
        mu_d = _number(settings, "dynamic_friction", 0.0, mu_s, open_low=True)
        block.update(static_friction=mu_s, dynamic_friction=mu_d)
    rocking: dict = {"cor": cor, "theta0": theta0}
    motion = _motion(settings, rocking)
    data = {"name": "classroom", "source": "shaketable classroom",
            "description": "A scene saved from the classroom page (shaketable classroom).",
            "block": block, "motion": motion, "rocking": rocking}
    if settings.pitch:
        data["table"] = {"pitch": dict(PITCH)}
    return data


def _duration(settings: Settings, required: bool) -> str | None:
    if not _text(settings, "duration"):
        if required:
            raise FieldError("duration", "duration: give the length of the run, e.g. '10 s'")
        return None
    value = _quantity(settings, "duration", "time", positive=True)
    if value > MAX_DURATION:
        raise FieldError("duration", f"duration must be at most {MAX_DURATION:g} s on this "
                                     f"page, got {_text(settings, 'duration')!r}")
    return _text(settings, "duration")


def _motion(settings: Settings, rocking: dict) -> dict:
    """The scene's ``[motion]`` (and ``rocking.duration`` where the motion has none)."""
    kind = settings.motion
    if kind not in MOTIONS:
        raise FieldError("motion", f"motion must be one of {', '.join(MOTIONS)}, got {kind!r}")
    if kind == "free":
        rocking["duration"] = _duration(settings, True)
        return {"kind": "free"}
    if kind == "harmonic":
        frequency = _quantity(settings, "frequency", "frequency", positive=True)
        if frequency > 50.0:
            raise FieldError("frequency", f"frequency must be at most 50 Hz here, got "
                                          f"{_text(settings, 'frequency')!r}")
        _quantity(settings, "amplitude", "acceleration")
        _quantity(settings, "vertical", "acceleration")
        return {"kind": "harmonic", "frequency": _text(settings, "frequency"),
                "horizontal": _text(settings, "amplitude"),
                "vertical": _text(settings, "vertical"),
                "duration": _duration(settings, True)}
    if kind == "pulse":
        amplitude = _quantity(settings, "pulse_amplitude", "acceleration")
        _quantity(settings, "pulse_length", "time", positive=True)
        duration = _duration(settings, True)
        if settings.pulse_shape == "half-sine":
            text = _text(settings, "pulse_amplitude").lstrip("+-").strip()
            return {"kind": "half-sine", "amplitude": text, "pulse_duration":
                    _text(settings, "pulse_length"), "duration": duration, "dt": "0.001 s",
                    "sign": -1 if amplitude < 0 else 1}
        if settings.pulse_shape == "constant":
            return {"kind": "constant-pulse", "acceleration": _text(settings, "pulse_amplitude"),
                    "pulse_duration": _text(settings, "pulse_length"), "duration": duration,
                    "dt": "0.001 s"}
        raise FieldError("pulse_shape", f"pulse shape must be one of {', '.join(PULSE_SHAPES)}, "
                                        f"got {settings.pulse_shape!r}")
    from shaketable.ground import records

    if settings.record not in records.available():
        raise FieldError("record", f"record must be one of {', '.join(records.available())}, "
                                   f"got {settings.record!r}")
    motion: dict = {"kind": "record", "name": settings.record,
                    "vertical": bool(settings.record_vertical)}
    if _text(settings, "target_pga"):
        target = _quantity(settings, "target_pga", "acceleration", positive=True)
        recorded = records.load(settings.record, vertical=settings.record_vertical)
        scale = target / float(np.max(np.abs(recorded.horizontal)))
    else:
        scale = _number(settings, "record_scale", 0.0, 10.0)
    if scale != 1.0:
        motion["scale"] = scale
    duration = _duration(settings, False)
    if duration is not None:
        rocking["duration"] = duration
    return motion


def check(settings: Settings) -> dict:
    """Every field that cannot be used, by name, with its message (empty: all good).

    Each field is tried on its own (the others at their defaults where they depend on
    each other), so that every bad field gets its message, not only the first.
    """
    messages: dict = {}
    try:
        scene_data(settings)
    except FieldError as error:
        messages[error.field] = str(error)
    else:
        return messages
    defaults = Settings()
    for item in fields(Settings):
        name = item.name
        if name in messages or getattr(settings, name) == getattr(defaults, name):
            continue
        values = {key: getattr(settings, key) for key in (
            "motion", "compare", "friction", "pulse_shape", "record")}
        values[name] = getattr(settings, name)
        trial = replace(defaults, **values)
        try:
            scene_data(trial)
        except FieldError as error:
            if error.field == name:
                messages[name] = str(error)
    return messages


@dataclass(frozen=True)
class Picture:
    """What the page draws for one set of inputs (SI units unless said).

    Attributes
    ----------
    data : dict
        The scene run (:func:`scene_data`).
    runs : tuple
        The results, one per block: :class:`~shaketable.models.rocking.result.RockingResult`, or
        :class:`~shaketable.models.planar.result.PlanarResult` with friction.
    labels : tuple of str
        What tells the blocks apart (``"COR 0.93"``, ``"12 x 2.4 ft"``).
    unit : str
        Length unit of the drawing (the unit the height was typed in).
    frames : ndarray
        Simulated times of the frames [s], every :data:`FRAME_STEP`.
    table : ndarray
        Table displacement at the frames [m].
    outlines : tuple of ndarray
        Per block, its corners at every frame [m], shape (frames, 5, 2), closed.
    traces : tuple of (ndarray, ndarray)
        Per block, output times [s] and theta/alpha [-].
    ground : (ndarray, ndarray)
        Times [s] and horizontal ground acceleration [g].
    bands : tuple of list
        Per block, (start [s], end [s], mode name) of each stretch of one mode.
    verdicts : tuple of str
        Per block, the run in words.
    numbers : tuple of dict
        Per block, :func:`key_numbers`.
    """

    __eq__ = fields_equal   # arrays compared by value

    data: dict
    runs: tuple
    labels: tuple
    unit: str
    frames: np.ndarray
    table: np.ndarray
    outlines: tuple
    traces: tuple
    ground: tuple
    bands: tuple
    verdicts: tuple
    numbers: tuple = field(default_factory=tuple)

    @property
    def end(self) -> float:
        """The last simulated time drawn [s]."""
        return float(self.frames[-1])


def key_numbers(result, unit: str = "in") -> dict:
    """The numbers under the picture for one run, as shown (text).

    ``max |θ|/α`` [-] (``F`` when it overturned, as the report writes it), the overturn
    time [s] (``—``: none), the impacts counted, and with friction the peak slip of the
    base in ``unit``.
    """
    overturned = bool(result.overturned() if callable(result.overturned) else result.overturned)
    numbers = {
        "max |θ|/α": "F" if overturned else f"{result.max_abs_theta / result.block.alpha:.3f}",
        "overturns at": f"{result.t_overturn:.2f} s" if overturned else "—",
        "impacts": f"{int(result.n_impacts)}",
    }
    if hasattr(result, "peak_slip"):
        numbers["peak slip"] = f"{result.peak_slip / LENGTH_UNITS[unit]:.3g} {unit}"
    return numbers


def _labels(data: dict) -> tuple:
    block, rocking = data["block"], data["rocking"]
    if isinstance(rocking["cor"], list):
        return tuple(f"COR {value:.3g}" for value in rocking["cor"])
    if isinstance(rocking["theta0"], list):
        return tuple(f"θ0 = {value}".replace("alpha", "α") for value in rocking["theta0"])
    if isinstance(block["size"], list):
        from shaketable.core.geometry import Block

        return tuple(Block.parse(size).describe() for size in block["size"])
    return ("",)


def _rocking_bands(result) -> list:
    """(start, end, mode) stretches of a rocking run: rest or rock, then overturned."""
    moving = (result.theta != 0.0) | (result.theta_dot != 0.0)
    return _stretches(result.t, np.where(moving, "rock", "rest"), result)


def _stretches(t: np.ndarray, names: np.ndarray, result) -> list:
    spans: list = []
    if t.size == 0:
        return spans
    changes = np.flatnonzero(names[1:] != names[:-1]) + 1
    starts = np.concatenate([[0], changes])
    stops = np.concatenate([changes, [t.size - 1]])
    for start, stop in zip(starts, stops):
        spans.append((float(t[start]), float(t[stop]), str(names[start])))
    overturned = result.overturned() if callable(result.overturned) else result.overturned
    if overturned and spans:
        spans.append((float(result.t_overturn), float(t[-1]) + 1e9, "overturned"))
    return spans


def _planar_bands(result) -> list:
    from shaketable.models.planar.shenton import MODE_NAMES
    from shaketable.plots.planar import mode_spans

    spans = [(start, stop, MODE_NAMES[code]) for start, stop, code in mode_spans(result)]
    if result.overturned:
        spans.append((float(result.t_overturn), float(result.t[-1]) + 1e9, "overturned"))
    return spans


def block_outlines(width: float, height: float, theta: np.ndarray, x: np.ndarray,
                   y: np.ndarray) -> np.ndarray:
    """Corners of a block whose centre of mass is at (x, y) turned by theta [m], (n, 5, 2).

    theta > 0 turns counterclockwise (the top toward -x, docs/conventions.md); the
    outline is closed (the first corner repeated).
    """
    b, h = width / 2.0, height / 2.0
    corners = np.array([[-b, -h], [b, -h], [b, h], [-b, h], [-b, -h]])
    cos, sin = np.cos(theta)[:, None], np.sin(theta)[:, None]
    return np.stack([corners[None, :, 0] * cos - corners[None, :, 1] * sin + x[:, None],
                     corners[None, :, 0] * sin + corners[None, :, 1] * cos + y[:, None]],
                    axis=-1)


def _centre(result, frames: np.ndarray) -> tuple:
    """Theta [rad] and the centre of mass (x, y) relative to the table [m] at the frames."""
    t = result.t
    clipped = np.minimum(frames, t[-1])   # held at the last state after the run ends
    theta = np.interp(clipped, t, result.theta)
    if hasattr(result, "x"):              # the planar block: its own centre of mass
        return theta, np.interp(clipped, t, result.x), np.interp(clipped, t, result.y)
    block = result.block
    pivot = np.where(theta >= 0.0, -block.b, block.b)   # theta > 0 pivots on the -x corner
    x = pivot - pivot * np.cos(theta) - block.h * np.sin(theta)
    y = -pivot * np.sin(theta) + block.h * np.cos(theta)
    return theta, x, y


def _offsets(runs) -> list:
    """Base centres of the blocks side by side on one table [m]: far enough apart that
    neither, fallen toward the other, reaches it."""
    if len(runs) == 1:
        return [0.0]
    gap = 1.1 * (runs[0].block.b + runs[1].block.b
                 + max(runs[0].block.height, runs[1].block.height))
    return [-gap / 2.0, gap / 2.0]


def compute(settings: Settings | dict) -> Picture:
    """Run the settings' scene and return what the page draws.

    Parameters
    ----------
    settings : Settings or dict
        The page's inputs, or a scene dict (:func:`scene_data`) already made.

    Raises
    ------
    FieldError
        A field that cannot be used (the page shows the message next to it).
    ValueError
        A run that cannot be made (e.g. pitch with friction); the message says why.
    """
    from shaketable.scenes.parse import Scene, scene_from_dict
    from shaketable.scenes.run import run_scene

    data = scene_data(settings) if isinstance(settings, Settings) else settings
    scene = scene_from_dict(data, "the classroom page")
    if not isinstance(scene, Scene):   # a [study]: never made by scene_data
        raise ValueError("the classroom page runs scenes, not studies")
    result = run_scene(scene)
    runs = result.planar if result.planar else result.runs
    unit = data["block"]["size"]
    unit = (unit[0] if isinstance(unit, list) else unit).rstrip().split("x")[-1]
    unit = unit.lstrip("0123456789.eE+- ")
    end = max(float(run.t[-1]) for run in runs)
    if result.motion is not None:   # an overturned block lies on the table to the end
        end = max(end, float(result.motion.t[-1]))
    frames = FRAME_STEP * np.arange(int(math.floor(end / FRAME_STEP + 1e-9)) + 1)
    motion = result.motion
    from shaketable.plots.animation import table_displacement

    table = table_displacement(motion, frames)
    outlines, traces, bands = [], [], []
    for run, offset in zip(runs, _offsets(runs)):
        theta, x, y = _centre(run, frames)
        outlines.append(block_outlines(run.block.width, run.block.height, theta,
                                       x + table + offset, y))
        traces.append((run.t, run.theta / run.block.alpha))
        bands.append(_planar_bands(run) if hasattr(run, "mode") else _rocking_bands(run))
    if motion is None:
        ground = (np.array([0.0, end]), np.zeros(2))
    else:
        ground = (motion.t, motion.horizontal / G)
    return Picture(data=data, runs=tuple(runs), labels=_labels(data), unit=unit, frames=frames,
                   table=table, outlines=tuple(outlines), traces=tuple(traces), ground=ground,
                   bands=tuple(bands), verdicts=tuple(run.verdict() for run in runs),
                   numbers=tuple(key_numbers(run, unit) for run in runs))


def _toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)   # the shortest text that reads back as the same float
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(item) for item in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{key} = {_toml_value(item)}" for key, item in value.items()) \
            + " }"
    text = str(value).replace("\\", "\\\\").replace('"', '\\"')
    return f'"{text}"'


def scene_toml(data: dict) -> str:
    """The scene file (TOML text) of a scene dict, for ``shaketable run FILE``."""
    lines = []
    for key, value in data.items():
        if not isinstance(value, dict):
            lines.append(f"{key} = {_toml_value(value)}")
    for key, value in data.items():
        if isinstance(value, dict):
            lines.append(f"\n[{key}]")
            lines.extend(f"{name} = {_toml_value(item)}" for name, item in value.items()
                         if item is not None)
    return "\n".join(lines) + "\n"
