"""Running a sweep: the runs table, chunks through the batch engine, locally or on a Dask
cluster, with progress and resume.
"""

from __future__ import annotations

import json
import math
import os
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from shaketable.core.constants import G
from shaketable.core.equality import fields_equal
from shaketable.core.files import folder_lock, prepare_output_folder, subfolder, temporary_files
from shaketable.core.motion import Motion
from shaketable.sweeps.spec import (
    RecordSpec,
    SweepError,
    SweepSpec,
    load_spec,
    pitch_of,
)
from shaketable.sweeps.store import (
    FORMAT_VERSION,
    MIGRATED_VERSIONS,
    SweepStoreWarning,
    finished_chunks,
    migrate_parts,
    parquet_available,
    part_path,
    read_results,
    stray_parts_message,
    write_atomic,
    write_text_atomic,
)

if TYPE_CHECKING:
    import pandas as pd
    from distributed import Client


@lru_cache(maxsize=16)
def _record_motion(record: RecordSpec, seed) -> Motion:
    """The unscaled ground motion of one record realisation [m/s^2] (cached per process)."""
    from shaketable.ground import generators as motions
    from shaketable.ground import records

    options = dict(record.options)
    if record.kind == "bundled":
        return records.load(record.name, vertical=record.vertical)
    if record.kind == "file":
        return records.combine(records.read(record.file, **options), name=record.label)
    return motions.artificial(record.preset, seed=seed, **options)


@lru_cache(maxsize=64)
def record_measures(record: RecordSpec, seed, measures) -> dict:
    """Every intensity measure of the unscaled record (cached per process), SI.

    :func:`shaketable.ground.intensity.intensity_measures` of the whole record, with the
    Sa periods, range and damping of ``measures`` (an
    :class:`~shaketable.sweeps.targets.IntensitySettings`). A record without horizontal
    motion (a vertical-only record) has NaN measures (and cannot be scaled to one).
    """
    from shaketable.ground.intensity import (
        intensity_measures,
        sa_avg_column,
        sa_column,
    )

    base = _record_motion(record, seed)
    if base.pga == 0.0:
        columns = (["pga [m/s^2]", "pgv [m/s]", "pgd [m]", "pgv/pga [s]"]
                   + [sa_column(period) for period in measures.periods]
                   + [sa_avg_column(*measures.period_range), "arias [m/s]", "cav [m/s]",
                      "d5-95 [s]"])
        return dict.fromkeys(columns, math.nan) | {"pga [m/s^2]": 0.0}
    return intensity_measures(base, periods=measures.periods,
                              period_range=measures.period_range, damping=measures.damping)


@lru_cache(maxsize=64)
def spectrum_factor(record: RecordSpec, seed, measures) -> float:
    """Factor that scales a record to the target spectrum of ``measures`` [-].

    The least-squares fit in logs over ``SA_AVG_POINTS`` log-spaced periods of
    ``period_range``: ``ln f = mean_i ln(Sa_target(T_i) / Sa_record(T_i))``, the target
    interpolated linearly in log-log between its rows (amplitude scaling of a suite
    to a target spectrum, one factor per record).
    """
    from shaketable.ground.intensity import SA_AVG_POINTS, spectral_acceleration

    low, high = measures.period_range
    periods = np.geomspace(low, high, SA_AVG_POINTS)
    target_t, target_sa = np.array(measures.spectrum).T
    target = np.exp(np.interp(np.log(periods), np.log(target_t), np.log(target_sa)))
    values = spectral_acceleration(_record_motion(record, seed), periods, measures.damping)
    if np.any(values <= 0.0):
        raise SweepError(f"record {record.label!r} has no horizontal motion; it cannot be "
                         "scaled to a spectrum")
    return float(np.exp(np.mean(np.log(target / values))))


def check_inputs(spec: SweepSpec) -> None:
    """Read every record the sweep will use and check that it can be scaled as asked,
    before the first chunk runs (and before anything is written).

    Each distinct base motion (record and seed) is read (a bad file of a suite, a file
    that is not a record, an unreadable one: refused now, naming the file), and with
    a target PGA, measure or spectrum its value is computed and checked (a record
    without horizontal motion cannot be scaled). The motions and measures are cached
    per process, so the chunks reuse them. A spec refused here leaves nothing behind:
    the corrected spec starts (or resumes) as if the bad one had never run.

    Raises
    ------
    SweepError
        Naming the spec, the record and (for a file) its path.
    """
    seen = set()
    for record_index, seed, _ in spec.motion_variants:
        if (record_index, seed) in seen:
            continue
        seen.add((record_index, seed))
        record = spec.records[record_index]
        what = f"record {record.label!r}" + (f" ({record.file})" if record.file else "") \
            + ("" if seed is None else f", seed {seed}")
        try:
            base = _record_motion(record, seed)
        except (ValueError, OSError) as error:
            message = getattr(error, "strerror", None) or str(error)
            raise SweepError(f"{spec.path}: {what}: cannot be used ({message}); nothing was "
                             "run") from None
        if spec.intensity == "pga" and not base.pga > 0.0:
            raise SweepError(f"{spec.path}: {what} has no horizontal motion; it cannot be "
                             "scaled to a PGA; nothing was run")
        try:   # every row records the measures: an unusable one is refused now
            measures = record_measures(record, seed, spec.measures)
            if spec.measures.spectrum:
                spectrum_factor(record, seed, spec.measures)
        except ValueError as error:   # SweepError included
            raise SweepError(f"{spec.path}: {what}: its intensity measures cannot be "
                             f"computed ({error}); nothing was run") from None
        if spec.intensity == "measure":
            value = measures[spec.measures.column]
            if not (value > 0.0 and math.isfinite(value)):
                raise SweepError(f"{spec.path}: {what} has {spec.measures.column} = {value!r}; "
                                 "it cannot be scaled to it; nothing was run")


def build_motion(spec: SweepSpec, record_index: int, seed: int | None = None,
                 level_index: int = 0, phase_index: int | None = None) -> tuple[Motion, float]:
    """The motion of one run and its earthquake scale factor.

    Parameters
    ----------
    spec : SweepSpec
    record_index : int
        Index into ``spec.records``.
    seed : int, optional
        Seed of the artificial realisation (``None`` for a recorded motion).
    level_index : int
        Index into ``spec.levels``.
    phase_index : int, optional
        Index into ``spec.pitch.phases`` (``None`` without pitch).

    Returns
    -------
    motion : Motion
        Without pitch: the *unscaled* record (the batch scales it by
        ``factor``); with pitch: the record scaled by ``factor`` (as
        :meth:`Motion.scaled`) and then put on the pitching table by
        :func:`shaketable.lab.pitch.motion_at_block`.
    factor : float
        Scale factor of the earthquake [-]: the level itself (times the record's
        spectrum factor with a target spectrum), target PGA / record PGA (as
        :func:`shaketable.ground.signals.scale_to_pga`), or ``(level / IM) ** (1 / n)``
        for a target measure with scale exponent ``n``.
    """
    base = _record_motion(spec.records[record_index], seed)
    level = spec.levels[level_index]
    if spec.intensity == "pga":
        if base.pga == 0.0:
            raise SweepError(f"{spec.path}: record {spec.records[record_index].label!r} has "
                             "no horizontal motion; it cannot be scaled to a PGA")
        factor = level / base.pga
    elif spec.intensity == "measure":
        from shaketable.ground.intensity import scale_exponent

        settings = spec.measures
        value = record_measures(spec.records[record_index], seed, settings)[settings.column]
        if not value > 0.0:
            raise SweepError(f"{spec.path}: record {spec.records[record_index].label!r} has "
                             f"{settings.column} = {value!r}; it cannot be scaled to it")
        factor = (level / value) ** (1.0 / scale_exponent(settings.column))
    elif spec.measures.spectrum:
        factor = level * spectrum_factor(spec.records[record_index], seed, spec.measures)
    else:
        factor = level
    if spec.pitch is None:
        return base, factor
    from shaketable.lab.pitch import motion_at_block

    assert phase_index is not None   # a pitching sweep's runs each have a phase
    scaled = base if factor == 1.0 else base.scaled(factor)
    pitched = motion_at_block(scaled, pitch=pitch_of(spec.pitch, phase_index, spec.seed),
                              block_position=spec.pitch.block_position,
                              axis_depth=spec.pitch.axis_depth)
    return pitched, factor


def runs_table(spec: SweepSpec, start: int = 0, stop: int | None = None) -> pd.DataFrame:
    """The inputs of runs ``start`` to ``stop`` (the grid, before running), one row each.

    Columns: ``run``, ``record_index``, ``seed``, ``phase_index``,
    ``level_index``, ``block_index``, ``cor [-]``; with ``[friction]`` (the planar
    model's axis) also ``friction_index`` (into ``spec.friction.pairs``; between block and
    COR in run order).
    """
    import pandas as pd

    stop = spec.n_runs if stop is None else min(stop, spec.n_runs)
    runs = np.arange(start, stop, dtype=np.int64)
    n_cor, n_block, n_level = len(spec.cors), len(spec.blocks), len(spec.levels)
    n_friction = max(1, len(spec.model.axis))   # the model's own axis (friction pairs)
    cor_index = runs % n_cor
    friction_index = (runs // n_cor) % n_friction
    n_cor = n_cor * n_friction   # the runs of one block (frictions x CORs)
    block_index = (runs // n_cor) % n_block
    level_index = (runs // (n_cor * n_block)) % n_level
    variant_index = runs // (n_cor * n_block * n_level)
    variants = spec.motion_variants
    frictions = {"friction_index": friction_index} if spec.model.axis else {}
    return pd.DataFrame({
        "run": runs,
        "variant": variant_index,
        "record_index": np.array([variants[v][0] for v in variant_index], dtype=np.int64),
        "seed": pd.array([variants[v][1] for v in variant_index], dtype="Int64"),
        "phase_index": pd.array([variants[v][2] for v in variant_index], dtype="Int64"),
        "level_index": level_index,
        "block_index": block_index,
        **frictions,
        "cor [-]": np.array(spec.cors)[cor_index],
    })


def compute_chunk(spec: SweepSpec, chunk: int, threads: int | None = None) -> pd.DataFrame:
    """Run one chunk; the rows of the result table for runs ``chunk * chunk_size`` on.

    A plain function of picklable arguments: this is what a Dask worker runs. The
    spec's model (:mod:`shaketable.sweeps.models`) runs the chunk's cases. With
    ``spec.ensemble`` each run is an ensemble of perturbed copies (its row gains
    :data:`~shaketable.sweeps.models.ENSEMBLE_COLUMNS` and ``mark``).
    """
    import pandas as pd

    model = spec.model
    start = chunk * spec.chunk_size
    inputs = runs_table(spec, start, start + spec.chunk_size)
    cases: list = []
    factor_list: list[float] = []
    pga_list: list[float] = []
    motions: dict[tuple, tuple[Motion, float]] = {}
    cors = inputs["cor [-]"].to_numpy()
    for k, row in enumerate(inputs.drop(columns="cor [-]").itertuples(index=False)):
        seed = None if pd.isna(row.seed) else int(row.seed)
        phase = None if pd.isna(row.phase_index) else int(row.phase_index)
        key = (row.record_index, seed, row.level_index, phase)
        if key not in motions:
            motions[key] = build_motion(spec, row.record_index, seed, row.level_index, phase)
        motion, factor = motions[key]
        record = spec.records[row.record_index]
        label = record.label if seed is None else f"{record.label} (seed {seed})"
        block = spec.blocks[row.block_index]
        cases.append(model.case(block, motion, cors[k], 1.0 if spec.pitch is not None else factor,
                                model.label(block), label))
        factor_list.append(factor)
        pga_list.append(_record_motion(record, seed).pga)
    frame, statistics = model.simulate(spec, inputs, cases, threads)
    frame = frame.drop(columns=["block_index", "motion_index", "scale [-]", "pga [m/s^2]"])
    record_pgas = np.array(pga_list)
    factors = np.array(factor_list)
    level = np.array(spec.levels)[inputs["level_index"].to_numpy()]
    records = [spec.records[i] for i in inputs["record_index"]]
    # a run has a phase index only when the sweep pitches
    pitch_phases = () if spec.pitch is None else spec.pitch.phases
    phases = np.array([math.nan if pd.isna(k) else pitch_phases[int(k)]
                       for k in inputs["phase_index"]])
    extra = pd.DataFrame({
        "sweep": spec.name,
        "run": inputs["run"].to_numpy(),
        "chunk": chunk,
        "record": [record.label for record in records],
        "record_kind": [record.kind for record in records],
        "seed": inputs["seed"].array,
        "record_pga [m/s^2]": record_pgas,
        "scale [-]": factors,
        "target_pga [m/s^2]": level if spec.intensity == "pga" else np.full(len(level), np.nan),
        "pga [m/s^2]": record_pgas * factors,
        "pga [g]": record_pgas * factors / G,
        "pitch": spec.pitch is not None,
        "pitch_phase [rad]": phases,
        "R [m]": [model.lead_block(spec.blocks[i]).R for i in inputs["block_index"]],
        "block_index": inputs["block_index"].to_numpy(),
    })
    frame = frame.reset_index(drop=True)
    measures = _measure_columns(spec, inputs, records, factors, level)
    return pd.concat([extra, frame, measures] + ([] if statistics is None else [statistics]),
                     axis=1)


def _measure_columns(spec: SweepSpec, inputs, records, factors, level):
    """The intensity measures of each row's scaled record, appended after the batch's
    columns (the earlier columns keep their places; the ensemble's come after)."""
    import pandas as pd

    from shaketable.ground.intensity import normalised_pga, normalised_pgv, scale_exponent

    rows = []
    for k, (record, seed) in enumerate(zip(records, inputs["seed"])):
        seed = None if pd.isna(seed) else int(seed)
        base = record_measures(record, seed, spec.measures)
        row = {column: value * factors[k] ** scale_exponent(column)
               for column, value in base.items() if column != "pga [m/s^2]"}
        block = spec.model.lead_block(spec.blocks[inputs["block_index"].iloc[k]])
        row["pga/(g tan a) [-]"] = normalised_pga(base["pga [m/s^2]"] * factors[k], block.alpha)
        row["pgv p/(g tan a) [-]"] = normalised_pgv(row["pgv [m/s]"], block.p, block.alpha)
        rows.append(row)
    table = pd.DataFrame(rows)
    table["suite"] = [record.suite for record in records]
    if spec.intensity == "measure":
        table["target_measure"] = spec.measures.measure
        table["target [SI]"] = level
    if spec.measures.spectrum:
        table["spectrum_scale [-]"] = [
            spectrum_factor(record, None if pd.isna(seed) else int(seed), spec.measures)
            for record, seed in zip(records, inputs["seed"])]
    return table


def solver_identity() -> dict:
    """What a resumed sweep must share with the parts already written: the package
    version, the solvers and their default tolerances (rows computed by another engine
    must not be mixed into one table)."""
    from shaketable.models.rocking.layout import METHODS
    from shaketable.models.rocking.run import DEFAULT_RTOL
    from shaketable.version import __version__

    return {"shaketable": __version__, "methods": dict(METHODS),
            "default rtol": dict(DEFAULT_RTOL)}


def refuse_a_second_sweep(out: Path) -> None:
    """Raise SweepError if folder ``out`` already holds a sweep (its manifest): a sweep
    goes on there only with ``resume``."""
    manifest_path = Path(out) / "manifest.json"
    if manifest_path.exists():
        raise SweepError(f"{out}: already holds a sweep ({manifest_path}); pass --resume "
                         "(resume=True from Python) to continue it, or choose another "
                         "output folder")


def _prepare(spec, out: Path, resume: bool, fmt: str) -> set:
    manifest_path = out / "manifest.json"
    manifest = {"sweep": spec.name, "spec": spec.path, "fingerprint": spec.fingerprint(),
                "n_runs": spec.n_runs, "chunk_size": spec.chunk_size,
                "n_chunks": spec.n_chunks, "format": fmt, "format_version": FORMAT_VERSION,
                "solver": solver_identity()}
    if spec.ensemble is not None:
        manifest["ensemble"] = spec.ensemble
    # the model's entries ("friction": the planar model's grid; "model": the stack model);
    # a folder without them ran the rocking block
    manifest.update(spec.model.manifest())
    if manifest_path.exists():
        if not resume:
            refuse_a_second_sweep(out)
        try:
            old = json.loads(manifest_path.read_text())
        except (OSError, ValueError) as error:
            raise SweepError(f"{manifest_path}: unreadable manifest ({error})") from None
        if not isinstance(old, dict):
            raise SweepError(f"{manifest_path}: not a sweep manifest (a JSON "
                             f"{type(old).__name__}, not an object); use another output folder")
        if old.get("model") != manifest.get("model"):
            def model(entry):
                return entry["model"] if isinstance(entry, dict) and "model" in entry \
                    else "the rocking or planar model"
            raise SweepError(f"{out}: cannot resume: the sweep there runs "
                             f"{model(old.get('model'))} and {spec.path} "
                             f"{model(manifest.get('model'))}; use another output folder")
        if old.get("friction") != manifest.get("friction"):
            def friction(entry):
                if not isinstance(entry, dict):
                    return "no [friction] (the rocking model)"
                pairs = entry.get("pairs (mu_s, mu_d)") or []
                return "[friction] (mu_s, mu_d) = " + ", ".join(
                    f"({mu_s:.6g}, {mu_d:.6g})" for mu_s, mu_d in pairs)
            raise SweepError(f"{out}: cannot resume: the sweep there has "
                             f"{friction(old.get('friction'))} and {spec.path} has "
                             f"{friction(manifest.get('friction'))}; use another output folder")
        if old.get("format_version") in MIGRATED_VERSIONS and all(
                old.get(key) == manifest[key] for key in ("fingerprint", "n_runs",
                                                          "chunk_size", "format", "solver")):
            # a folder of an earlier layout: its parts brought to this one, then resumed
            migrate_parts(spec, out, fmt, old["format_version"], spec.model.label)
            old["format_version"] = FORMAT_VERSION
            write_text_atomic(manifest_path, json.dumps(old, indent=2))
        for key in ("fingerprint", "n_runs", "chunk_size", "format", "format_version",
                    "solver"):
            if old.get(key) != manifest[key]:
                raise SweepError(
                    f"{out}: cannot resume: the sweep there differs from {spec.path} in "
                    f"{key} ({old.get(key)!r} there, {manifest[key]!r} now); use another "
                    "output folder")
        # temporary files of a killed writer (atomic_write's .<stem>.tmp-<random><suffix>);
        # the folder lock is held, so none belongs to a live process
        for stray in temporary_files(out) + _part_leftovers(out):
            stray.unlink(missing_ok=True)
        return finished_chunks(spec, out, fmt)
    subfolder(out, "parts")
    existing = [p for p in (out / "parts").iterdir() if not p.name.startswith(".")]
    if existing:
        raise SweepError(f"{out}: holds part files but no manifest; choose another output "
                         "folder")
    write_text_atomic(manifest_path, json.dumps(manifest, indent=2))
    return set()


def _part_leftovers(out: Path) -> list:
    """Half-written parts a killed writer left in ``out/parts``: every hidden file named
    after a part (``.part-NNNNNN.tmp-<random>.parquet`` of the atomic writer, and any
    other ``.part-NNNNNN.<...>`` a writer may leave), never a finished part."""
    parts = out / "parts"
    if not parts.is_dir():
        return []
    return sorted(path for path in parts.iterdir()
                  if path.name.startswith(".part-") and not path.is_dir())


@dataclass(frozen=True)
class SweepOutcome:
    """What :func:`run_sweep` did.

    Attributes
    ----------
    table : pandas.DataFrame or None
        The whole result table (None when the sweep stopped before the end).
    path : Path or None
        The joined table's file.
    out : Path
        Output folder.
    computed_runs, skipped_runs : int
        Runs computed now, and runs found finished on disk (resume).
    seconds : float
        Wall-clock time of this call [s].
    complete : bool
        Every chunk is on disk.
    format : str
        ``"parquet"`` or ``"csv"``.
    """

    __eq__ = fields_equal   # the table compared by value; equal after a pickle round trip

    table: pd.DataFrame | None
    path: Path | None
    out: Path
    computed_runs: int
    skipped_runs: int
    seconds: float
    complete: bool
    format: str


def run_sweep(spec: SweepSpec | str | os.PathLike[str], out: str | os.PathLike[str], *,
              workers: int | None = None, scheduler: str | Client | None = None,
              resume: bool = False, progress: bool = True, max_chunks: int | None = None,
              on_chunk: Callable[[int, pd.DataFrame], object] | None = None,
              fmt: str | None = None) -> SweepOutcome:
    """Run a sweep into the folder ``out``, chunk by chunk, resumable.

    Parameters
    ----------
    spec : SweepSpec or path
        The sweep (a path is read with :func:`load_spec`).
    out : path
        Output folder: ``manifest.json``, ``parts/part-NNNNNN.parquet`` and,
        at the end, ``results.parquet``.
    workers : int, optional
        Local: threads of the compiled batch loop (default all cores); for a model whose
        runs are not a compiled batch (the stack model, ``model.processes``), processes,
        each computing whole chunks (default one: the chunks one after the other, in this
        process; the table is the same either way). With ``scheduler``: threads inside
        each Dask task (default 1; the cluster's own workers give the parallelism).
    scheduler : str or distributed.Client, optional
        Address of a ``dask.distributed`` scheduler (``tcp://host:8786``), or
        a connected ``distributed.Client`` (used as is and not closed at the
        end; a client made from an address is closed); the chunks become Dask
        tasks. Default: run locally.
    resume : bool
        Continue a sweep already in ``out`` (finished chunks are kept, not
        recomputed). Without it an existing sweep in ``out`` is an error.
    progress : bool
        Show a progress bar with the time left (tqdm, on stderr).
    max_chunks : int, optional
        Compute at most this many chunks now, then stop (the rest on resume).
    on_chunk : callable, optional
        Called as ``on_chunk(chunk_index, frame)`` after each chunk is on disk.
    fmt : {"parquet", "csv"}, optional
        Part and result format; default Parquet when pyarrow is installed,
        else CSV (with a note in the manifest and on stderr).

    Returns
    -------
    SweepOutcome
    """

    if not isinstance(spec, SweepSpec):
        spec = load_spec(spec)
    out = Path(out)
    if fmt is None:
        fmt = "parquet" if parquet_available() else "csv"
        if fmt == "csv":
            import sys
            print("shaketable sweep: note: pyarrow is not installed, writing CSV instead of "
                  "Parquet (pip install pyarrow: the 'parquet' extra)", file=sys.stderr)
    if fmt not in ("parquet", "csv"):
        raise ValueError(f"fmt must be 'parquet' or 'csv', got {fmt!r}")
    if fmt == "parquet" and not parquet_available():
        raise ValueError("fmt='parquet' needs pyarrow (pip install pyarrow: the 'parquet' extra)")
    if max_chunks is not None and (isinstance(max_chunks, bool) or int(max_chunks) < 0):
        raise ValueError(f"max_chunks must be a non-negative integer, got {max_chunks!r}")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise ValueError(f"workers (--workers) must be a positive integer ("
                         f"{'processes' if spec.model.processes else 'threads'}), "
                         f"got {workers!r}")
    check_inputs(spec)   # every record and measure, before any file or chunk
    began = time.perf_counter()
    client: Any      # a distributed.Client, or None
    own_client: bool
    client, own_client = (None, False) if scheduler is None else _connect(scheduler)
    try:
        prepare_output_folder(out, "out")
        with folder_lock(out, "sweep folder"):  # a second process on `out` refuses
            return _run(spec, out, fmt, resume, max_chunks, workers, client, progress,
                        on_chunk, began)
    finally:
        if own_client:
            client.close()


def _run(spec, out, fmt, resume, max_chunks, workers, client, progress, on_chunk, began):
    done = _prepare(spec, out, resume, fmt)
    todo = [chunk for chunk in range(spec.n_chunks) if chunk not in done]
    if max_chunks is not None:
        todo = todo[:int(max_chunks)]
    skipped = sum(_chunk_length(spec, chunk) for chunk in done)
    bar = None
    if progress:
        from tqdm.auto import tqdm
        bar = tqdm(total=spec.n_runs, initial=skipped, unit="run", desc=spec.name,
                   smoothing=0.1)
    computed = 0

    def finished(chunk, frame):
        nonlocal computed
        _write_or_stop(frame, part_path(out, chunk, fmt), fmt, f"chunk {chunk}")
        computed += len(frame)
        if bar is not None:
            bar.update(len(frame))
        if on_chunk is not None:
            on_chunk(chunk, frame)

    try:
        if client is None and spec.model.processes and (workers or 1) > 1 and len(todo) > 1:
            _run_in_processes(spec, todo, min(workers or 1, len(todo)), finished)
        elif client is None:
            for chunk in todo:
                finished(chunk, compute_chunk(spec, chunk, threads=workers))
        else:
            _run_on_dask(spec, todo, client, workers or 1, finished)
    finally:
        if bar is not None:
            bar.close()

    complete = len(finished_chunks(spec, out, fmt)) == spec.n_chunks
    table = path = None
    if complete:
        stray = stray_parts_message(out, fmt, spec.n_chunks)
        if stray:   # said once, as the CSV note above, not as a Python warning
            import sys
            print(f"shaketable sweep: warning: {stray}", file=sys.stderr)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SweepStoreWarning)
            table = read_results(out, fmt=fmt, parts_only=True, n_chunks=spec.n_chunks)
        path = out / f"results.{'parquet' if fmt == 'parquet' else 'csv'}"
        _write_or_stop(table, path, fmt, "the joined table")
    return SweepOutcome(table=table, path=path, out=out, computed_runs=computed,
                        skipped_runs=skipped, seconds=time.perf_counter() - began,
                        complete=complete, format=fmt)


def _write_or_stop(frame, path: Path, fmt: str, what: str) -> None:
    """Write a part or the joined table; a write that fails (a folder made read-only
    during the run, a full disk) stops the sweep with a RuntimeError (exit status 1)
    naming the file, never silently."""
    try:
        write_atomic(frame, path, fmt)
        if not path.is_file():
            raise OSError(f"{path} is not on disk after writing it")
    except OSError as error:
        raise RuntimeError(f"{path}: cannot write {what} ({error.strerror or error}); the sweep "
                           "stopped here; the chunks already finished are on disk: make the "
                           "folder writable and run again with --resume") from error


def _chunk_length(spec, chunk: int) -> int:
    return min(spec.chunk_size, spec.n_runs - chunk * spec.chunk_size)


#: Seconds to wait for a Dask scheduler before saying it cannot be reached.
SCHEDULER_TIMEOUT = 10.0


def _connect(scheduler):
    """A ``distributed.Client`` for an address (connected here, before anything is
    written), or the client given; and whether it is ours to close."""
    try:
        from distributed import Client
    except ImportError:
        raise ValueError("--scheduler needs dask.distributed: pip install "
                         "'shaketable[cluster]'") from None
    if isinstance(scheduler, Client):
        return scheduler, False
    if not isinstance(scheduler, str) or not scheduler.strip():
        raise ValueError(f"scheduler (--scheduler) must be an address such as "
                         f"tcp://host:8786, got {scheduler!r}")
    try:
        return Client(scheduler, timeout=SCHEDULER_TIMEOUT), True
    except (OSError, TimeoutError, ValueError) as error:
        raise ValueError(f"--scheduler {scheduler!r}: cannot reach a Dask scheduler there "
                         f"within {SCHEDULER_TIMEOUT:g} s ({type(error).__name__}: "
                         f"{error}); nothing was written") from None


def _run_in_processes(spec, chunks, workers: int, finished) -> None:
    """Compute the chunks in ``workers`` processes of their own; write each as it completes.

    Each process runs :func:`compute_chunk` as a Dask task does (a chunk's rows do not
    depend on where or in which order it is computed), its batches on one thread.
    The processes ignore Ctrl-C: it stops this process, which then ends them at once
    (:func:`shaketable.core.workers.end_workers`) and writes the chunks that had already
    come back; a chunk's error does the same. The chunks finished are on disk, the others
    run on resume.
    """
    from concurrent.futures import as_completed

    from shaketable.core.workers import (
        end_workers_after,
        ignore_interrupts,
        interrupts_ignored,
        process_pool,
    )

    pool = process_pool(workers, ignore_interrupts)
    futures: dict = {}
    written = set()
    try:
        with interrupts_ignored():   # the processes start (at submit) ignoring Ctrl-C
            futures = {pool.submit(compute_chunk, spec, chunk, 1): chunk for chunk in chunks}
        for future in as_completed(futures):
            finished(futures[future], future.result())
            written.add(future)
    except BaseException:
        end_workers_after(pool)   # a second Ctrl-C meanwhile: this error is still raised
        # the chunks computed but not yet written are kept (an atomic write each); a write
        # that fails stops this, the error that stopped the sweep is the one raised
        try:
            for future, chunk in futures.items():
                if future not in written and future.done() and not future.cancelled() \
                        and future.exception() is None:
                    finished(chunk, future.result())
        except Exception:
            pass
        raise
    pool.shutdown(wait=True)


def _run_on_dask(spec, chunks, client, threads, finished) -> None:
    """Submit every chunk to a Dask cluster; write each as it completes."""
    from distributed import as_completed

    futures = {client.submit(compute_chunk, spec, chunk, threads, pure=False,
                             key=f"shaketable-sweep-{spec.name}-{chunk}-{time.time_ns()}"):
               chunk for chunk in chunks}
    failures = []
    for future in as_completed(futures):
        chunk = futures[future]
        try:
            frame = future.result()
        except Exception as error:  # keep writing the others; report at the end
            failures.append((chunk, error))
            continue
        finished(chunk, frame)
    if failures:
        first_chunk, first_error = failures[0]
        raise RuntimeError(f"{len(failures)} chunk(s) failed on the cluster, first chunk "
                           f"{first_chunk}: {first_error!r}; the finished chunks are on disk, "
                           "run again with --resume") from first_error

