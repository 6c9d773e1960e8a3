"""The bundled scenes (``experiments/``): their names and where a name or path leads."""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from shaketable.core.tomlfile import read_toml
from shaketable.scenes.parse import SceneError


@dataclass(frozen=True)
class SceneSource:
    """A scene file read once: where it is, its TOML data and its text (for the lines of
    error messages). What a command needs to know of a scene before parsing it (is it a
    sweep spec, does it run the planar engine, its study kind) is read from ``data``, and
    :func:`shaketable.scenes.parse.load_scene` parses the same reading (``read=``)."""

    path: Path
    data: dict
    text: str


#: The last files read, by (resolved path, modification time, size): the scheduling of
#: ``reproduce`` asks several questions of one file without reading it again.
_READ: dict = {}


def read_scene(name_or_path: str) -> SceneSource:
    """The scene file of a name or path (:func:`resolve_scene_path`), read and decoded once.

    Raises
    ------
    SceneError
        No such scene, or a file that is not UTF-8 TOML (naming the file).
    """
    path = resolve_scene_path(name_or_path)
    try:
        status = path.stat()
        key = (str(path.resolve()), status.st_mtime_ns, status.st_size)
    except OSError:
        key = None
    if key is not None and key in _READ:
        return _READ[key]
    data, text = read_toml(path, "scene", SceneError)
    source = SceneSource(path, data, text)
    if key is not None:
        if len(_READ) >= 256:
            _READ.clear()
        _READ[key] = source
    return source


def resolve_scene_path(name_or_path: str, directory=None) -> Path:
    """A scene file from a path or a name in the experiments folder."""
    candidate = Path(name_or_path)
    if candidate.suffix == ".toml" and candidate.is_file():
        return candidate
    folder = Path(directory) if directory is not None else experiments_folder()
    path = folder / f"{name_or_path}.toml"
    if path.is_file():  # a bundled name wins over a folder of that name (e.g. an earlier --out)
        return path
    if candidate.is_dir():
        raise SceneError(f"{name_or_path!r} is a folder; give a scene .toml file or the name "
                         f"of a bundled scene (`shaketable reproduce --list`)")
    if not path.exists():
        names = sorted(p.stem for p in folder.glob("*.toml"))
        raise SceneError(f"no scene {name_or_path!r}{did_you_mean(str(name_or_path), names)} "
                         f"(not a file, not in {folder}); available: {', '.join(names)}")
    return path


def did_you_mean(name: str, names) -> str:
    """``": did you mean fig-3-7?"``: the name of ``names`` closest to a misspelt ``name``
    (``fig-3-77``), to lead a refusal before any list; ``""`` when none is close."""
    import difflib

    close = difflib.get_close_matches(name, list(names), n=1, cutoff=0.75)
    return f": did you mean {close[0]}?" if close else ""


def sweep_names() -> list[str]:
    """Names of the bundled sweep specs (``experiments/sweeps/``)."""
    return sorted(path.stem for path in (experiments_folder() / "sweeps").glob("*.toml"))


def object_names() -> list[str]:
    """Names of the bundled objects of ``shaketable assess`` (``experiments/assess/``)."""
    return sorted(path.stem for path in (experiments_folder() / "assess").glob("*.toml"))


def resolve_object_path(name_or_path: str | os.PathLike) -> Path:
    """An object file of ``assess``, or the name of a bundled object (``experiments/assess``).

    Raises
    ------
    FileNotFoundError
        Neither a file nor a bundled name; the message lists the bundled names.
    """
    path = Path(name_or_path)
    if path.is_file():
        return path  # a folder of the same name (an earlier --out) is not an object file
    bundled = experiments_folder() / "assess" / f"{name_or_path}.toml"
    if path.suffix != ".toml" and bundled.is_file():
        return bundled
    raise FileNotFoundError(f"{str(name_or_path)!r}: no such object file, nor a bundled "
                            f"example{did_you_mean(path.stem, object_names())} (bundled: "
                            f"{', '.join(object_names())})")


def resolve_sweep_path(name_or_path: str) -> Path:
    """A sweep spec from a path or the name of a bundled spec (``experiments/sweeps``)."""
    candidate = Path(name_or_path)
    if candidate.suffix == ".toml" and candidate.exists():
        return candidate
    path = experiments_folder() / "sweeps" / f"{name_or_path}.toml"
    if path.exists():
        return path
    if candidate.suffix == ".toml":
        raise SceneError(f"no sweep spec {name_or_path!r}: no such file")
    raise SceneError(f"no sweep spec {name_or_path!r} (not a .toml file, not bundled); "
                     f"bundled: {', '.join(sweep_names())}")


def is_sweep_spec(name_or_path: str, data: dict | None = None) -> bool:
    """Whether a name or path given to ``run`` is a sweep spec rather than a scene
    (``data``: the file's TOML, already read, is looked at instead of reading it)."""
    candidate = Path(name_or_path)
    if candidate.suffix == ".toml" and candidate.is_file():
        if candidate.resolve().parent == (experiments_folder() / "sweeps").resolve():
            return True
        if data is not None:   # the sections only a sweep spec has
            return bool({"blocks", "stacks", "records", "intensity", "run"} & set(data))
        try:
            head = candidate.read_text(encoding="utf-8", errors="replace")
        except OSError:
            return False
        # the sections only a sweep spec has (shaketable.sweeps.spec.TOP_KEYS)
        return any(line.strip() in ("[blocks]", "[[records]]", "[intensity]", "[run]")
                   for line in head.splitlines())
    return name_or_path in sweep_names() and not (experiments_folder()
                                                  / f"{name_or_path}.toml").exists()


def scene_names(directory=None) -> list[str]:
    """Names of the scenes in a folder (default: the bundled experiments), in figure order."""
    import re

    folder = Path(directory) if directory is not None else experiments_folder()

    def natural(name):
        return [int(part) if part.isdigit() else part for part in re.split(r"(\d+)", name)]

    return sorted((path.stem for path in folder.glob("*.toml")), key=natural)


def experiments_folder() -> Path:
    """The scenes shipped with the package (the repository's ``experiments/``)."""
    from importlib.resources import files

    return Path(str(files("shaketable.experiments")))


def study_kind(name_or_path: str) -> str | None:
    """The ``[study] kind`` of a scene file (``None`` for a single scene), read without
    parsing the scene: no pipeline module is imported (the table stage's SciPy).

    Raises
    ------
    SceneError
        No such scene, or a file that is not TOML (:func:`resolve_scene_path`).
    """
    study = read_scene(name_or_path).data.get("study")
    return str(study.get("kind")) if isinstance(study, dict) else None


#: Scenes whose section of the report runs the planar block beside the scene itself.
_PLANAR_SECTIONS = {"table-4-4"}


def _readable(name_or_path: str | SceneSource) -> SceneSource | None:
    """The scene's source, or None when it cannot be read (left to the parser to say)."""
    if isinstance(name_or_path, SceneSource):
        return name_or_path
    try:
        return read_scene(name_or_path)
    except (OSError, SceneError):
        return None


def uses_planar(name_or_path: str | SceneSource) -> bool:
    """Whether a scene runs the planar block, read from its TOML alone.

    True for ``block.static_friction`` (the planar run per COR), a ``mode-map`` study, and
    the scenes whose report section recomputes with the planar block (Table 4.4): the
    first-compile notice names the planar engine for them. An unreadable file is left to
    the scene parser to report (``False`` here).
    """
    source = _readable(name_or_path)
    if source is None:
        return False
    path, scene = source.path, source.data
    if path.stem in _PLANAR_SECTIONS:
        return True
    block, study = scene.get("block"), scene.get("study")
    return (isinstance(block, dict) and "static_friction" in block) or (
        isinstance(study, dict) and study.get("kind") == "mode-map")


def uses_stack(name_or_path: str | SceneSource) -> bool:
    """Whether a scene runs the stack model, read from its TOML alone: a ``[stack]`` scene
    or a ``stacks`` study (the first-compile notice names the stack engine for them). An
    unreadable file is left to the scene parser to report (``False`` here)."""
    source = _readable(name_or_path)
    if source is None:
        return False
    study = source.data.get("study")
    return "stack" in source.data or (isinstance(study, dict)
                                      and study.get("kind") == "stacks")


#: CPU seconds of the slowest scenes in one worker (warm numba cache; measured with
#: ``benchmarks/reproduce_time.py --per-scene``): the pool starts the longest first
#: (longest processing time first), so that the two processes end together.
SCENE_CPU = {"table-4-3": 11.3, "table-4-2": 9.7, "table-4-1": 8.6,
             "teaching-slide-or-rock": 4.4, "fig-2-6": 4.0, "mode-map-pacoima": 3.5,
             "spectrum-one-sine": 3.1, "stacks": 7.0, "section-3-7-pitch": 2.1, "fig-3-8": 1.9,
             "fig-2-3": 1.9, "fig-3-9": 1.8, "fig-3-5": 1.7, "fig-3-7": 1.5,
             "section-4-3-4": 1.5, "fig-2-4": 1.4, "teaching-lower-cor": 1.3,
             "table-3-1": 0.3, "table-4-4": 0.2}

#: The estimate for any other scene, by kind: a report-table study, another study, a
#: single scene (a name that does not load: 0, last).
KIND_CPU = {"report-table": 8.0, "study": 1.0, "scene": 0.9}


def expected_cost(name: str) -> float:
    """The CPU seconds a scene is expected to take (:data:`SCENE_CPU`, else :data:`KIND_CPU`)."""
    if name in SCENE_CPU:
        return SCENE_CPU[name]
    try:   # the scene file's [study] kind only: parsing the scene would import its
        kind = study_kind(name)   # pipeline (SciPy) in the process that only schedules
    except (ValueError, OSError):
        return 0.0
    if kind is not None:
        return KIND_CPU["report-table" if kind == "report-table" else "study"]
    return KIND_CPU["scene"]
