"""Parameter sweeps: a TOML spec, a grid of runs, a tidy table; parallel, resumable, Dask.

A sweep spec names grids; every combination is one run of
:func:`shaketable.models.rocking.batch.simulate_cases` and one row of the result table. Every
dimensional value carries its unit, as in the scenes (``"30 in"``, ``"0.5 g"``)::

    name = "pacoima-map"
    description = "..."
    seed = 1                      # artificial records and drawn pitch phases

    [blocks]                      # one of these groups of keys:
    height = ["2 ft", "4 ft"]     #   height + width | height + aspect | width + aspect
    width = ["1 ft"]              #   (aspect = H/B [-], plain numbers)
    # R = ["0.5 m"]               #   R + alpha | R + aspect  (R: the size, sqrt(b^2 + h^2))
    # alpha = ["0.1 rad"]
    # sizes = ["30x6in", "16x4ft"] #   an explicit list
    [blocks.rods]                 # optional, on every block (as in a scene)
    stiffness = "0.4 W/in"
    force = "0.4 W"
    edge_distance = "12 in"

    [rocking]
    cor = [0.9, 1.0]              # [-], a number or a list
    duration = "30 s"             # optional: cut (or pad) every motion
    method = "fast"               # optional; rtol, theta0 ("0.1 alpha"), subdivisions

    [[records]]                   # one table per record; any number of them
    name = "pacoima-dam-s16e"     # a bundled record (vertical = false drops its vertical)
    [[records]]
    file = "my-record.AT2"        # a file, relative to the spec (units, dt, column as in a scene)
    [[records]]
    preset = "A-1"                # an artificial SUBSTITUTE preset (shaketable.ground.generators.PRESETS)
    seeds = 5                     # 5 realisations, seeds seed .. seed + 4; or a list [3, 7]
    # seed = 10                   # base seed of this entry (default: the top-level seed)
    # duration = "30 s", dt = "0.01 s", pga = "0.5 g", vertical_pga = "0.2 g"

    [[records]]
    folder = "my-suite"           # a suite: every file of a folder (NGA-West2 *.AT2 by default)
    # pattern = "*.AT2"           #   one record per file, labelled by the file's stem
    # suite = "far-field"         #   the suite's name (``suite`` column; default the folder's)

    [intensity]                   # optional; one of
    scale = [0.5, 1.0, 1.5]       #   factors [-] on every component of the record
    # pga = ["0.1 g", "0.2 g"]    #   target peak horizontal acceleration (both components scaled)
    # measure = "pgv"             #   or any intensity measure as the target (below):
    # levels = ["0.25 m/s", "0.5 m/s"]  pga, pgv, pgd, sa, sa_avg, arias, cav (with units)
    # period = "1 s"              #   T of measure = "sa" (Sa(T, damping))
    # period_range = ["0.2 s", "2 s"]   range of sa_avg and of spectrum matching
    # damping = 0.05              #   of the spectra [-]
    # spectrum = "target.csv"     #   scale each record to a target spectrum first (CSV:
    #                             #   period [s], sa [g]) over period_range (with scale only)

    [pitch]                       # optional: the table pitches (shaketable.lab.pitch.Pitch)
    phases = 8                    # 8 phases evenly in [0, 2 pi); or a list ["0 deg", "90 deg"]
    # random_phases = 16          # or 16 phases drawn uniformly from the top-level seed
    frequency = "12 Hz"           # defaults: Section 3.7 (2) of the report, 12 Hz, 0.22 rad/s2
    amplitude = "0.22 rad/s2"
    # block_position = "0 in", axis_depth = "0 in"

    [ensemble]                    # optional: every cell run as an ensemble
    members = 200                 # copies per cell, the first the nominal run
    perturb = 1e-9                # relative spread of every input; or per input:
    # perturb_amplitude, perturb_cor, perturb_size, perturb_start (sample intervals)
    # seed = 0                    # of the draws (member k is the same in every cell)

    # model = "rocking"           # optional: "rocking" (default), "planar" ([friction]) or
    #                             # "stack" ([stacks] in place of [blocks]: shaketable.sweeps.stacks)
    [friction]                    # optional: the coupled planar model (shaketable.sweeps.friction)
    static = [0.2, 0.3]           # mu_s [-], plain numbers; dynamic = [...] or dynamic_ratio

    [run]
    chunk_size = 500              # runs (cells) per chunk (a part file each)

Intensity measures: every row records every measure of
:func:`shaketable.ground.intensity.intensity_measures` of the scaled record (before the
pitch, over the whole record): ``pgv [m/s]``, ``pgd [m]``, ``pgv/pga [s]``, ``sa(T s)
[m/s^2]`` at 0.2, 0.5, 1 and 2 s (and ``period``), ``sa_avg(T1-T2 s) [m/s^2]`` over
``period_range``, ``arias [m/s]``, ``cav [m/s]``, ``d5-95 [s]``, and the block-normalised
``pga/(g tan a) [-]`` and ``pgv p/(g tan a) [-]``; with ``measure`` also
``target_measure`` and ``target [SI]``; with ``spectrum`` the per-record
``spectrum_scale [-]``. A measure scales as a power of the factor (Arias 2, the others
1), so the factor to a target level is ``(level / IM) ** (1 / exponent)``.

Order of the runs (the ``run`` column): record realisation, pitch phase,
intensity, block, friction (with ``[friction]``), COR, the last varying fastest. A record is scaled first and
then put on the pitching table (:func:`shaketable.lab.pitch.motion_at_block`): the
pitch is the table's, not the earthquake's, and is not scaled.

Execution (:func:`run_sweep`): the runs are cut into chunks of ``chunk_size``;
each finished chunk is written atomically (a temporary file renamed) to its own
part file under ``OUT/parts/``, so a sweep that is killed loses nothing already
written; run again with ``resume=True`` it skips the chunks on disk and repeats
none. When every chunk is on disk the parts are joined into ``OUT/results.parquet``
(``results.csv`` when pyarrow is missing, with a note). Locally the chunks run
one after the other, each spread over ``workers`` threads by the compiled batch
loop; with ``scheduler`` they are Dask tasks on a ``distributed`` cluster (the
workers must have shaketable installed and see record files at the same path).

With ``[ensemble]`` (the keys of a scene's ``[ensemble]``, read by
:func:`shaketable.core.ensemble.ensemble_options`, except ``horizon_threshold``:
a sweep computes no horizon) each cell is run ``members`` times: member 0 is
the cell's own run (its row is the row the sweep writes without
``[ensemble]``), member k has the amplitude, COR, block height and width and
the record's start perturbed by the k-th draw of
:func:`shaketable.core.ensemble.perturbed_members` (the same draw in every
cell). The row gains the ensemble's verdict: ``members``, ``overturned
members``, ``P(overturn) [-]`` with its Wilson 95 % interval (``P low [-]``,
``P high [-]``), ``robust`` (every member agrees) and ``mark``
(``robust`` / ``fragile``), and the median and 5-95 % range of max
theta/alpha over the members that stand. ``chunk_size`` still counts cells
(a chunk runs ``chunk_size * members`` simulations).

The same spec (and seed) always gives the same table, whatever the number of
workers, the chunking or the interruptions.

The intensity settings and the target-spectrum reader are in
:mod:`shaketable.sweeps.targets`, record suites in :mod:`shaketable.sweeps.suites`, the
friction axis (``[friction]``, the coupled planar model) in :mod:`shaketable.sweeps.friction`,
:class:`SweepError` and :class:`RecordSpec` in :mod:`shaketable.sweeps.base`.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from dataclasses import dataclass, field
from itertools import product
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from shaketable.core import sections
from shaketable.core.equality import fields_equal
from shaketable.core.geometry import Block
from shaketable.core.tomlfile import read_toml, with_line
from shaketable.core.units import parse_angle_or_ratio
from shaketable.core.validation import check_keys, count, flag
from shaketable.sweeps.base import RecordSpec, SweepError
from shaketable.sweeps.limits import MAX_CHUNK_SIZE, check_grid_size
from shaketable.sweeps.models import PlanarSweep, RockingSweep, chosen_model
from shaketable.sweeps.targets import (
    IntensitySettings,
    check_levels,
    check_periods,
    check_spectrum_covers,
    read_spectrum,
)

if TYPE_CHECKING:
    from shaketable.lab.pitch import Pitch

TOP_KEYS = {"name", "description", "seed", "blocks", "rocking", "records", "intensity",
            "pitch", "run", "ensemble", "friction", "model", "stacks"}

BLOCK_KEYS = {"height", "width", "aspect", "R", "alpha", "sizes", "rods"}

#: The groups of block keys a spec may give (one of them).
BLOCK_GRIDS = (("height", "width"), ("height", "aspect"), ("width", "aspect"), ("R", "alpha"),
               ("R", "aspect"), ("sizes",))

ROCKING_KEYS = {"cor", "duration", "method", "rtol", "theta0", "subdivisions"}

RECORD_KEYS = {
    "bundled": {"name", "vertical", "label"},
    "file": {"file", "units", "dt", "column", "label"},
    "artificial": {"preset", "seed", "seeds", "duration", "dt", "pga", "vertical_pga", "label"},
    "folder": {"folder", "pattern", "suite", "units"},
}

INTENSITY_KEYS = {"scale", "pga", "measure", "levels", "period", "period_range", "damping",
                  "spectrum"}

PITCH_KEYS = {"phases", "random_phases", "frequency", "amplitude", "block_position",
              "axis_depth", "frequency_drift", "amplitude_drift"}

RUN_KEYS = {"chunk_size"}

#: Sections whose keys an error message gets the line of (``(line N)``).
LINE_SECTIONS = ("friction", "stacks")


@dataclass(frozen=True)
class PitchGrid:
    """The ``[pitch]`` section: phases [rad] and the :class:`shaketable.lab.pitch.Pitch` settings.

    Attributes
    ----------
    phases : tuple of float
        Pitch phases psi [rad] (one run each).
    frequency : float
        Pitch frequency [Hz].
    amplitude : float
        Angular-acceleration amplitude [rad/s^2].
    block_position : float
        Distance of the block from the pitch axis along +x [m].
    axis_depth : float
        Height of the table surface above the pitch axis [m].
    frequency_drift, amplitude_drift : float
        Relative drifts [-] (seeded with the spec's seed).
    """

    phases: tuple
    frequency: float = 12.0
    amplitude: float = 0.22
    block_position: float = 0.0
    axis_depth: float = 0.0
    frequency_drift: float = 0.0
    amplitude_drift: float = 0.0


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep (see the module docstring for the TOML).

    Attributes
    ----------
    name, description : str
    seed : int
        Seed of the artificial records (default base) and of drawn pitch phases.
    blocks : tuple of Block
    block_inputs : tuple of dict
        For each block the grid values that made it (SI units), for the table.
    cors : tuple of float
        Coefficients of restitution [-].
    records : tuple of RecordSpec
    intensity : str
        ``"scale"`` (factors), ``"pga"`` (target peak horizontal acceleration) or
        ``"measure"`` (target of ``measures.measure``).
    levels : tuple of float
        Scale factors [-], target PGAs [m/s^2] or target measures [SI].
    measures : IntensitySettings
        Periods, damping, target measure and target spectrum.
    pitch : PitchGrid or None
    duration : float or None
        Length of every run [s].
    method : str
    options : dict
        ``rtol``, ``theta0`` [rad or "k alpha"], ``subdivisions`` for the batch.
    chunk_size : int
        Runs (cells) per chunk.
    ensemble : dict or None
        ``[ensemble]``: :func:`shaketable.core.ensemble.ensemble_options`
        (``members``, ``seed``, ``spreads``); None runs each cell once.
    model : RockingSweep
        The model the sweep runs (:mod:`shaketable.sweeps.models`): the rocking block,
        :class:`~shaketable.sweeps.models.PlanarSweep` (``[friction]``) or
        :class:`~shaketable.sweeps.stacks.StackSweep` (``[stacks]``: ``blocks`` then holds
        :class:`~shaketable.models.stack.Stack` objects).
    friction : shaketable.sweeps.friction.FrictionGrid or None
        ``[friction]``: the (mu_s, mu_d) axis of the planar model (its parameters); None
        for the other models.
    path : str
        Where the spec was read from (for messages and relative record files).
    raw : dict
        The parsed TOML, for the manifest's fingerprint.
    """

    # by value, NaN equal to NaN in the same place: the plastic law's COR is NaN by design
    # (a stack sweep's ``cors``, its ``block_inputs`` "mass ratio" for one density), and a
    # spec equals its pickled copy
    __eq__ = fields_equal

    name: str
    description: str
    seed: int
    blocks: tuple
    block_inputs: tuple
    cors: tuple
    records: tuple
    intensity: str = "scale"
    levels: tuple = (1.0,)
    pitch: PitchGrid | None = None
    duration: float | None = None
    method: str = "fast"
    options: dict = field(default_factory=dict)
    chunk_size: int = 500
    ensemble: dict | None = None
    path: str = "<spec>"
    measures: IntensitySettings = IntensitySettings()
    model: Any = RockingSweep()
    raw: dict = field(default_factory=dict, compare=False, repr=False)

    # ------------------------------------------------------------ the grid
    @property
    def motion_variants(self) -> tuple:
        """(record index, seed, phase index) of every distinct base motion, in run order."""
        phases = range(len(self.pitch.phases)) if self.pitch is not None else [None]
        return tuple((r, seed, k) for r, record in enumerate(self.records)
                     for seed in record.seeds for k in phases)

    @property
    def n_runs(self) -> int:
        """Number of runs (rows of the table)."""
        return (len(self.motion_variants) * len(self.levels) * len(self.blocks)
                * len(self.cors) * max(1, len(self.model.axis)))

    @property
    def friction(self) -> Any:
        """The planar model's (mu_s, mu_d) grid (``[friction]``); None for another model."""
        return getattr(self.model, "friction", None)

    @property
    def n_chunks(self) -> int:
        """Number of chunks."""
        return math.ceil(self.n_runs / self.chunk_size)

    def fingerprint(self) -> str:
        """SHA-256 of the spec's content (and of the record files it reads)."""
        digest = hashlib.sha256(json.dumps(self.raw, sort_keys=True, default=str).encode())
        for record in self.records:
            if record.kind == "file":
                digest.update(Path(record.file).read_bytes())
        if self.measures.spectrum:   # the target spectrum file's values (not only its name)
            digest.update(json.dumps(self.measures.spectrum).encode())
        return digest.hexdigest()


# --------------------------------------------------------------------------- parsing
def load_spec(path: str | os.PathLike[str]) -> SweepSpec:
    """Read and validate a sweep spec (TOML).

    Raises
    ------
    SweepError
        With the file name, the key and what was expected.
    """
    path = Path(path)
    data, text = read_toml(path, "sweep spec", SweepError)
    try:
        return spec_from_dict(data, where=str(path), directory=path.parent)
    except SweepError as error:   # a [friction] or [stacks] key: its line, as the scenes give it
        raise SweepError(with_line(str(error), str(path), text, LINE_SECTIONS,
                                   at_start=True)) from None


def spec_from_dict(data: dict, where: str = "<spec>",
                   directory: str | os.PathLike[str] | None = None) -> SweepSpec:
    """Validate a sweep spec given as a dict (the parsed TOML).

    Parameters
    ----------
    data : dict
    where : str
        Name used in error messages (the file).
    directory : path, optional
        Folder that relative record files are resolved against (default the
        current directory).
    """
    directory = Path(directory) if directory is not None else Path.cwd()
    _only(data, TOP_KEYS, where, "the top level")
    model_name = chosen_model(data, where)
    required = ("name", "stacks", "records") if model_name == "stack" else (
        "name", "blocks", "rocking", "records")
    for key in required:
        if key not in data:
            raise SweepError(f"{where}: missing " + (f"[{key}]" if key != "name" else
                                                     "'name' at the top level"))
    name = data["name"]
    if not isinstance(name, str) or not name.strip():
        raise SweepError(f"{where}: 'name' must be a non-empty string, got {name!r}")
    from shaketable.core.files import folder_name_problem

    if problem := folder_name_problem(name.strip()):
        raise SweepError(f"{where}: 'name' {name!r} {problem} (the name is the default output "
                         f"folder shaketable-out/<name>; use letters, digits, '-', '_', '.')")
    seed = _checked(count, f"{where}: 'seed'", data.get("seed", 1))

    rocking = _section(data, "rocking", where) if "rocking" in data else {}
    _only(rocking, ROCKING_KEYS, where, "[rocking]")
    if model_name == "stack":
        from shaketable.sweeps.stacks import stack_cors, stacks_grid

        blocks, block_inputs = stacks_grid(data["stacks"], where)
        cors = stack_cors(rocking, where)
    else:
        blocks, block_inputs = _blocks(_section(data, "blocks", where), where)
        if "cor" not in rocking:
            raise SweepError(f"{where}: rocking.cor is missing (coefficient of restitution, "
                             "a number in [0, 1] or a list)")
        cors = tuple(_number_list(rocking["cor"], where, "rocking.cor", 0.0, 1.0))
    duration = None
    if "duration" in rocking:
        duration = _quantity(rocking["duration"], "time", where, "rocking.duration",
                             positive=True)
    method = rocking.get("method", "fast")
    from shaketable.models.rocking.batch import METHODS
    if method not in METHODS:
        raise SweepError(f"{where}: rocking.method must be one of {', '.join(METHODS)}, "
                         f"got {method!r}")
    options: dict[str, Any] = {}
    if "rtol" in rocking:
        rtol = rocking["rtol"]
        from shaketable.models.rocking.run import MIN_RTOL

        if isinstance(rtol, bool) or not isinstance(rtol, (int, float)) \
                or not MIN_RTOL <= rtol < 1:
            raise SweepError(f"{where}: rocking.rtol must be a number in [{MIN_RTOL:g}, 1), "
                             f"got {rtol!r}")
        options["rtol"] = float(rtol)
    if "subdivisions" in rocking:
        options["subdivisions"] = _checked(count, f"{where}: rocking.subdivisions",
                                           rocking["subdivisions"], 1)
    if "theta0" in rocking:
        value = rocking["theta0"]
        if not isinstance(value, str):
            raise SweepError(f"{where}: rocking.theta0 must be text such as '0.1 alpha' or "
                             f"'0.01 rad', got {value!r}")
        try:
            parse_angle_or_ratio(value, 1.0, where=f"{where}: rocking.theta0")
        except ValueError as error:
            raise SweepError(str(error)) from None
        options["theta0"] = value

    records = _records(data["records"], where, directory, seed)
    intensity, levels, measures = _intensity(data.get("intensity", {}), where, directory)
    pitch = _pitch(data.get("pitch"), where, seed)
    run = data.get("run", {})
    if not isinstance(run, dict):
        raise SweepError(f"{where}: [run] must be a table, got {run!r}")
    _only(run, RUN_KEYS, where, "[run]")
    chunk_size = _checked(count, f"{where}: run.chunk_size", run.get("chunk_size", 500), 1)
    if chunk_size > MAX_CHUNK_SIZE:
        raise SweepError(f"{where}: run.chunk_size must be at most {MAX_CHUNK_SIZE:,} (a "
                         f"chunk's rows are held in memory), got {chunk_size!r}")
    model = _model(model_name, data, where)
    spec = SweepSpec(name=name.strip(), description=str(data.get("description", "")),
                     seed=seed, blocks=tuple(blocks), block_inputs=tuple(block_inputs),
                     cors=cors, records=tuple(records), intensity=intensity,
                     levels=tuple(levels), pitch=pitch, duration=duration, method=method,
                     options=options, chunk_size=chunk_size,
                     ensemble=_ensemble(data.get("ensemble"), where), path=where,
                     measures=measures, model=model,
                     raw=data)
    model.check(spec, rocking)   # what the model refuses, by key
    check_grid_size(spec, where)
    return spec


def _model(name: str, data: dict, where: str):
    """The sweep's model with its parameters (:mod:`shaketable.sweeps.models`)."""
    if name == "stack":
        from shaketable.sweeps.stacks import StackSweep

        return StackSweep()
    if name == "planar":
        from shaketable.sweeps.friction import friction_grid

        return PlanarSweep(friction=friction_grid(data.get("friction"), where))
    return RockingSweep()


def _ensemble(table, where):
    """``[ensemble]``: the scene's option parser (no horizon in a sweep); None if absent."""
    from shaketable.core.ensemble import ensemble_options

    if table is None:
        return None
    if not isinstance(table, dict):
        raise SweepError(f"{where}: [ensemble] must be a table, got {table!r}")
    try:
        options = ensemble_options(table, where, horizon=False)
    except ValueError as error:
        raise SweepError(str(error)) from None
    del options["threshold"]
    return options


def _only(table: dict, allowed: set, where: str, section: str) -> None:
    check_keys(table, allowed, where, section, SweepError)


def _checked(check, name: str, *args):
    """``check(name, *args)`` of :mod:`shaketable.core.validation`, its error a SweepError."""
    try:
        return check(name, *args)
    except ValueError as error:
        raise SweepError(str(error)) from None


def _section(data, key, where) -> dict:
    value = data[key]
    if not isinstance(value, dict):
        raise SweepError(f"{where}: [{key}] must be a table, got {value!r}")
    return value


def _as_list(value):
    return value if isinstance(value, list) else [value]


def _number_list(value, where, key, low=-math.inf, high=math.inf, low_open=False):
    values = _as_list(value)
    if not values:
        raise SweepError(f"{where}: {key} must not be an empty list")
    result = []
    for item in values:
        ok = not isinstance(item, bool) and isinstance(item, (int, float)) and \
            math.isfinite(item) and low <= item <= high and not (low_open and item == low)
        if not ok:
            bracket = "(" if low_open else "["
            raise SweepError(f"{where}: {key} must be a number in {bracket}{low:g}, {high:g}] "
                             f"or a list of them, got {item!r}")
        result.append(float(item))
    return result


def _quantity(value, kind, where, key, positive=False):
    return sections.quantity(value, kind, where, key, SweepError, positive)


def _quantity_list(value, kind, where, key, positive=True):
    values = _as_list(value)
    if not values:
        raise SweepError(f"{where}: {key} must not be an empty list")
    return [_quantity(item, kind, where, key, positive=positive) for item in values]


def _blocks(table, where):
    _only(table, BLOCK_KEYS, where, "[blocks]")
    rods = sections.rods(table["rods"], where, "blocks.rods", SweepError) \
        if "rods" in table else None
    given = tuple(sorted(set(table) - {"rods"}))
    grid = next((g for g in BLOCK_GRIDS if set(g) == set(given)), None)
    if grid is None:
        raise SweepError(f"{where}: [blocks] gives {', '.join(given) or 'nothing'}; give one "
                         "of: " + "; ".join(" + ".join(g) for g in BLOCK_GRIDS))
    blocks, inputs = [], []

    def add(make, key, values):
        try:
            block = make()
        except ValueError as error:
            raise SweepError(f"{where}: blocks.{key}: {error}") from None
        blocks.append(block)
        inputs.append(values)

    if grid == ("sizes",):
        for text in _as_list(table["sizes"]):
            if not isinstance(text, str):
                raise SweepError(f"{where}: blocks.sizes must be texts such as '30x6in', got "
                                 f"{text!r}")
            blocks.append(sections.sized_block(text, where, "blocks.sizes", rods, SweepError))
            inputs.append({"size": text})
        return blocks, inputs
    lengths = {key: _quantity_list(table[key], "length", where, f"blocks.{key}")
               for key in ("height", "width", "R") if key in table}
    if "aspect" in table:
        aspects = _number_list(table["aspect"], where, "blocks.aspect (H/B)", 0.0,
                               low_open=True)
    if "alpha" in table:
        alphas = []
        for item in _as_list(table["alpha"]):
            value = _quantity(item, "angle", where, "blocks.alpha", positive=True)
            if value >= math.pi / 2:
                raise SweepError(f"{where}: blocks.alpha must be below 90 deg, got {item!r}")
            alphas.append(value)
    # the blocks of a grid are labelled in the unit of the grid's first length
    unit = sections.length_unit(table[next(key for key in grid if key in lengths)])
    if grid == ("height", "width"):
        for height, width in product(lengths["height"], lengths["width"]):
            add(lambda: sections.labelled(Block(height, width, rods), unit), "height", {})
    elif grid == ("height", "aspect"):
        for height, aspect in product(lengths["height"], aspects):
            add(lambda: sections.labelled(Block(height, height / aspect, rods), unit), "aspect",
                {"aspect": aspect})
    elif grid == ("width", "aspect"):
        for width, aspect in product(lengths["width"], aspects):
            add(lambda: sections.labelled(Block(width * aspect, width, rods), unit), "aspect",
                {"aspect": aspect})
    elif grid == ("R", "alpha"):
        for radius, alpha in product(lengths["R"], alphas):
            add(lambda: sections.labelled(Block.from_slenderness(radius, alpha, rods), unit), "alpha",
                {})
    else:  # R + aspect
        for radius, aspect in product(lengths["R"], aspects):
            add(lambda: sections.labelled(Block.from_slenderness(radius, math.atan(1.0 / aspect), rods),
                                  unit), "aspect", {"aspect": aspect})
    return blocks, inputs


def _records(value, where, directory: Path, seed: int):
    from shaketable.ground import generators as motions
    from shaketable.ground import records as bundled

    if isinstance(value, dict):
        value = [value]
    if not isinstance(value, list) or not value:
        raise SweepError(f"{where}: [[records]] must be one or more tables, got {value!r}")
    result = []
    for k, entry in enumerate(value):
        key = f"records[{k}]"
        if not isinstance(entry, dict):
            raise SweepError(f"{where}: {key} must be a table, got {entry!r}")
        kinds = [kind for kind, marker in (("bundled", "name"), ("file", "file"),
                                            ("artificial", "preset"), ("folder", "folder"))
                 if marker in entry]
        if len(kinds) != 1:
            raise SweepError(f"{where}: {key} needs exactly one of 'name' (a bundled record), "
                             "'file' (a record file), 'preset' (an artificial record) or "
                             "'folder' (a suite of record files)")
        kind = kinds[0]
        _only(entry, RECORD_KEYS[kind], where, f"{key} ({kind})")
        if kind == "folder":
            from shaketable.sweeps.suites import suite_records
            result.extend(suite_records(entry, where, key, directory))
            continue
        label = entry.get("label")
        if label is not None and (not isinstance(label, str) or not label):
            raise SweepError(f"{where}: {key}.label must be a non-empty string")
        if kind == "bundled":
            if entry["name"] not in bundled.available():
                raise SweepError(f"{where}: {key}.name {entry['name']!r} is not a bundled "
                                 f"record; available: {', '.join(bundled.available())}")
            vertical = _checked(flag, f"{where}: {key}.vertical", entry.get("vertical", True))
            result.append(RecordSpec("bundled", label or entry["name"], name=entry["name"],
                                     vertical=vertical))
        elif kind == "file":
            path = Path(entry["file"])
            path = path if path.is_absolute() else (directory / path)
            if not path.is_file():
                raise SweepError(f"{where}: {key}.file: no such file {str(path)!r}")
            options = []
            if "units" in entry:
                options.append(("units", str(entry["units"])))
            if "dt" in entry:
                options.append(("dt", _quantity(entry["dt"], "time", where, f"{key}.dt",
                                                positive=True)))
            if "column" in entry:
                options.append(("value_column", entry["column"]))
            result.append(RecordSpec("file", label or path.stem, file=str(path.resolve()),
                                     options=tuple(options)))
        else:
            if entry["preset"] not in motions.PRESETS:
                raise SweepError(f"{where}: {key}.preset must be one of "
                                 f"{', '.join(sorted(motions.PRESETS))}, got {entry['preset']!r}")
            base = _checked(count, f"{where}: {key}.seed", entry.get("seed", seed))
            seeds = entry.get("seeds", 1)
            if isinstance(seeds, list):
                if not seeds or any(isinstance(s, bool) or not isinstance(s, int) or s < 0
                                    for s in seeds) or len(set(seeds)) != len(seeds):
                    raise SweepError(f"{where}: {key}.seeds must be a count or a list of "
                                     f"distinct non-negative integers, got {seeds!r}")
                seeds = tuple(seeds)
            elif isinstance(seeds, bool) or not isinstance(seeds, int) or seeds < 1:
                raise SweepError(f"{where}: {key}.seeds must be a positive count or a list of "
                                 f"seeds, got {seeds!r}")
            else:
                seeds = tuple(range(base, base + seeds))
            options = []
            for name, unit_kind in (("duration", "time"), ("dt", "time"),
                                    ("pga", "acceleration"), ("vertical_pga", "acceleration")):
                if name in entry:
                    options.append((name, _quantity(entry[name], unit_kind, where,
                                                    f"{key}.{name}", positive=True)))
            result.append(RecordSpec("artificial", label or entry["preset"],
                                     preset=entry["preset"], seeds=seeds,
                                     options=tuple(options)))
    labels = [record.label for record in result]
    duplicated = sorted({label for label in labels if labels.count(label) > 1})
    if duplicated:
        raise SweepError(f"{where}: two [[records]] are both labelled {duplicated[0]!r}; give "
                         "one of them a 'label'")
    return result


#: Intensity keys that go with ``measure`` (and ``spectrum``), not with ``pga``.
_MEASURE_KEYS = {"measure", "levels", "period", "period_range", "damping", "spectrum"}


def _intensity(table, where, directory: Path | None = None):
    from shaketable.ground.intensity import MEASURES

    if not isinstance(table, dict):
        raise SweepError(f"{where}: [intensity] must be a table, got {table!r}")
    _only(table, INTENSITY_KEYS, where, "[intensity]")
    targets = [key for key in ("scale", "pga", "measure") if key in table]
    if len(targets) > 1:
        raise SweepError(f"{where}: [intensity] gives both {' and '.join(targets)}; give one")
    settings: dict[str, Any] = {}
    if "damping" in table:
        settings["damping"] = _number_list(table["damping"], where, "intensity.damping",
                                           0.0, 0.99)[0]
    if "period_range" in table:
        ends = _quantity_list(table["period_range"], "time", where, "intensity.period_range")
        if len(ends) != 2 or not ends[0] < ends[1]:
            raise SweepError(f"{where}: intensity.period_range must be two periods, the "
                             f"shorter first, such as [\"0.2 s\", \"2 s\"], got "
                             f"{table['period_range']!r}")
        settings["period_range"] = tuple(ends)
    if "period" in table:
        settings["period"] = _quantity(table["period"], "time", where, "intensity.period",
                                       positive=True)
    check_periods(settings, table, where)
    if "spectrum" in table:
        if "measure" in table or "pga" in table:
            raise SweepError(f"{where}: intensity.spectrum goes with scale factors (or none), "
                             "not with a target pga or measure")
        settings["spectrum"] = read_spectrum(table["spectrum"], where, directory)
        check_spectrum_covers(settings["spectrum"], settings.get("period_range", (0.2, 2.0)),
                              where)
    if "measure" in table:
        measure = table["measure"]
        if measure not in MEASURES:
            raise SweepError(f"{where}: intensity.measure must be one of "
                             f"{', '.join(MEASURES)}, got {measure!r}")
        if "levels" not in table:
            raise SweepError(f"{where}: intensity.measure = {measure!r} needs intensity.levels "
                             "(the target values, with units)")
        if measure == "sa" and "period" not in table:
            raise SweepError(f"{where}: intensity.measure = 'sa' needs intensity.period "
                             "(such as \"1 s\")")
        kind = MEASURES[measure][1]
        levels = _quantity_list(table["levels"], kind, where, "intensity.levels")
        check_levels(levels, "arias" if measure in ("arias", "cav") else kind, where,
                     "intensity.levels")
        return "measure", levels, IntensitySettings(measure=measure, **settings)
    if "levels" in table:
        raise SweepError(f"{where}: intensity.levels needs intensity.measure (which measure "
                         "the levels are of)")
    if "pga" in table:
        extra = sorted(set(table) & _MEASURE_KEYS)
        if extra:
            raise SweepError(f"{where}: intensity.{extra[0]} does not go with intensity.pga; "
                             "use measure = \"pga\" with levels")
        levels = _quantity_list(table["pga"], "acceleration", where, "intensity.pga")
        check_levels(levels, "acceleration", where, "intensity.pga")
        return "pga", levels, IntensitySettings()
    if "scale" in table:
        levels = _number_list(table["scale"], where, "intensity.scale", 0.0, low_open=True)
        check_levels(levels, "scale", where, "intensity.scale")
        return "scale", levels, IntensitySettings(**settings)
    return "scale", [1.0], IntensitySettings(**settings)


def _pitch(table, where, seed):
    if table is None:
        return None
    if not isinstance(table, dict):
        raise SweepError(f"{where}: [pitch] must be a table, got {table!r}")
    _only(table, PITCH_KEYS, where, "[pitch]")
    if ("phases" in table) == ("random_phases" in table):
        raise SweepError(f"{where}: [pitch] needs exactly one of pitch.phases (a count, evenly "
                         "spaced, or a list of angles) or pitch.random_phases (a count)")
    if "phases" in table:
        value = table["phases"]
        if isinstance(value, int) and not isinstance(value, bool):
            value = _checked(count, f"{where}: pitch.phases", value, 1)
            phases = [2.0 * math.pi * k / value for k in range(value)]
        else:
            phases = [_quantity(item, "angle", where, "pitch.phases") for item in
                      _as_list(value)]
    else:
        drawn = _checked(count, f"{where}: pitch.random_phases", table["random_phases"], 1)
        phases = list(np.random.default_rng(seed).uniform(0.0, 2.0 * math.pi, drawn))
    values = {}
    for key, kind in (("frequency", "frequency"), ("amplitude", "angular acceleration"),
                      ("block_position", "length"), ("axis_depth", "length")):
        if key in table:
            values[key] = _quantity(table[key], kind, where, f"pitch.{key}",
                                    positive=key == "frequency")
    for key in ("frequency_drift", "amplitude_drift"):
        if key in table:
            values[key] = _number_list(table[key], where, f"pitch.{key}", 0.0, 0.25)[0]
    grid = PitchGrid(phases=tuple(float(p) for p in phases), **values)
    try:
        pitch_of(grid, 0, seed)
    except ValueError as error:
        raise SweepError(f"{where}: [pitch]: {error}") from None
    return grid


def pitch_of(grid: PitchGrid, index: int, seed: int) -> Pitch:
    from shaketable.lab.pitch import Pitch

    drift = grid.frequency_drift > 0 or grid.amplitude_drift > 0
    return Pitch(frequency=grid.frequency, amplitude=grid.amplitude,
                 phase=grid.phases[index], seed=seed if drift else None,
                 frequency_drift=grid.frequency_drift, amplitude_drift=grid.amplitude_drift)
