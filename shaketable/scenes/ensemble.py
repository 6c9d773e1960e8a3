"""The ``[ensemble]`` section of a scene: perturbed copies of each run.

Keys (all optional): ``members`` (default 200), ``perturb`` (relative spread of every
input, default 1e-9), ``perturb_amplitude``, ``perturb_cor``, ``perturb_size``,
``perturb_start`` (override it per input), ``seed`` (0), ``horizon_threshold`` (1e-3,
in units of alpha). See :mod:`shaketable.studies.predictability`; the keys are read by
:func:`shaketable.core.ensemble.ensemble_options` (shared with a sweep's ``[ensemble]``).
"""

from __future__ import annotations

import json

# one parser of [ensemble] for scenes and sweep specs, in the core layer (the sweeps
# sit below the scenes); re-exported here, where the scene parser imports it from
from shaketable.core.ensemble import ENSEMBLE_KEYS, ensemble_options

__all__ = ["ENSEMBLE_KEYS", "ensemble_options", "run_ensembles"]


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
