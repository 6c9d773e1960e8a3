"""The bundled scenes (``experiments/``): their names and where a name or path leads."""

from __future__ import annotations

from pathlib import Path

from shaketable.scenes.parse import SceneError


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
        names = ", ".join(sorted(p.stem for p in folder.glob("*.toml")))
        raise SceneError(f"no scene {name_or_path!r} (not a file, not in {folder}); "
                         f"available: {names}")
    return path


def sweep_names() -> list[str]:
    """Names of the bundled sweep specs (``experiments/sweeps/``)."""
    return sorted(path.stem for path in (experiments_folder() / "sweeps").glob("*.toml"))


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


def is_sweep_spec(name_or_path: str) -> bool:
    """Whether a name or path given to ``run`` is a sweep spec rather than a scene."""
    candidate = Path(name_or_path)
    if candidate.suffix == ".toml" and candidate.is_file():
        if candidate.resolve().parent == (experiments_folder() / "sweeps").resolve():
            return True
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
    from shaketable.core.tomlfile import tomllib

    path = resolve_scene_path(name_or_path)
    try:
        with open(path, "rb") as file:
            study = tomllib.load(file).get("study")
    except (OSError, tomllib.TOMLDecodeError) as error:
        raise SceneError(f"{path}: {error}") from error
    return str(study.get("kind")) if isinstance(study, dict) else None


#: Scenes whose section of the report runs the planar block beside the scene itself.
_PLANAR_SECTIONS = {"table-4-4"}


def uses_planar(name_or_path: str) -> bool:
    """Whether a scene runs the planar block, read from its TOML alone.

    True for ``block.static_friction`` (the planar run per COR), a ``mode-map`` study, and
    the scenes whose report section recomputes with the planar block (Table 4.4): the
    first-compile notice names the planar engine for them. An unreadable file is left to
    the scene parser to report (``False`` here).
    """
    from shaketable.core.tomlfile import tomllib

    try:
        path = resolve_scene_path(name_or_path)
        with open(path, "rb") as file:
            scene = tomllib.load(file)
    except (OSError, SceneError, tomllib.TOMLDecodeError):
        return False
    if path.stem in _PLANAR_SECTIONS:
        return True
    block, study = scene.get("block"), scene.get("study")
    return (isinstance(block, dict) and "static_friction" in block) or (
        isinstance(study, dict) and study.get("kind") == "mode-map")
