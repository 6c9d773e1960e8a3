"""The ``[ensemble]`` section of a scene: perturbed copies of each run (issue 16).

Keys (all optional): ``members`` (default 200), ``perturb`` (relative spread of every
input, default 1e-9), ``perturb_amplitude``, ``perturb_cor``, ``perturb_size``,
``perturb_start`` (override it per input), ``seed`` (0), ``horizon_threshold`` (1e-3,
in units of alpha). See :mod:`shaketable.studies.predictability`.
"""

from __future__ import annotations

import json
import math

ENSEMBLE_KEYS = {"members", "perturb", "perturb_amplitude", "perturb_cor", "perturb_size",
                 "perturb_start", "seed", "horizon_threshold"}


def ensemble_options(section: dict, where: str) -> dict:
    """Validated ``[ensemble]`` options (raises ValueError naming the key).

    Loads no study and no solver (the scene parser stays light): the spreads are
    checked here and become a :class:`~shaketable.studies.predictability.Perturbation`
    when the ensemble runs.
    """
    unknown = sorted(set(section) - ENSEMBLE_KEYS)
    if unknown:
        raise ValueError(f"{where}: unknown key ensemble.{unknown[0]}; expected one of "
                         f"{', '.join(sorted(ENSEMBLE_KEYS))}")
    members = section.get("members", 200)
    if isinstance(members, bool) or not isinstance(members, int) or members < 2:
        raise ValueError(f"{where}: ensemble.members must be an integer >= 2, got {members!r}")
    seed = section.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ValueError(f"{where}: ensemble.seed must be a non-negative integer, got {seed!r}")
    spread = section.get("perturb", 1e-9)
    spreads = {}
    for name in ("amplitude", "cor", "size", "start"):
        value = section.get(f"perturb_{name}", spread)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                0 <= value < 1):
            raise ValueError(f"{where}: ensemble.perturb_{name} (or perturb) must be a "
                             f"relative spread in [0, 1), got {value!r}")
        spreads[name] = float(value)
    threshold = section.get("horizon_threshold", 1e-3)
    if isinstance(threshold, bool) or not isinstance(threshold, (int, float)) or not (
            0 < threshold < math.inf):
        raise ValueError(f"{where}: ensemble.horizon_threshold must be positive, got "
                         f"{threshold!r}")
    return {"members": members, "seed": seed, "spreads": spreads,
            "threshold": float(threshold)}


def run_ensembles(scene, felt, out) -> tuple[list, list[str]]:
    """One ensemble per COR of ``scene`` on the motion the block feels; write its files.

    Returns ``(written paths, lines to print)``.
    """
    from shaketable.plots.base import save
    from shaketable.studies.predictability import Perturbation, ensemble

    options = ensemble_options(scene.ensemble, scene.path)
    from shaketable.core.files import (
        json_ready_dict,
        prepare_output_folder,
        write_csv,
        write_text,
    )

    out = prepare_output_folder(out, "out")
    written, lines = [], []
    for index, cor in enumerate(scene.cors):
        label = "" if len(scene.cors) == 1 else f"-cor{cor:g}"
        result = ensemble(scene.block, felt, cor=cor, members=options["members"],
                          perturbation=Perturbation(**options["spreads"]), seed=options["seed"],
                          threshold=options["threshold"], duration=scene.duration,
                          method=scene.method)
        written.append(out / f"ensemble{label}.csv")
        write_csv(written[-1], result.to_frame())
        summary = json_ready_dict(result.summary)
        written.append(out / f"ensemble{label}.json")
        write_text(written[-1], json.dumps(summary, indent=2, default=float))
        written.append(out / f"ensemble{label}.png")
        save(result.plot().figure, written[-1])
        lines.append(f"{scene.name}: COR {cor:g}, {options['members']} members: "
                     f"{result.describe()}")
    return written, lines
