"""``shaketable simulate --friction MU --ensemble N``: the planar model's ensemble."""

from __future__ import annotations

import dataclasses
import json


def friction_ensemble(args, block, motion, friction, out) -> int:
    """Run the perturbed copies of one planar run, print the answer, write CSV, JSON, figure.

    The perturbation is the one ``--ensemble`` gives the rocking model (``--perturb`` and
    ``--perturb-amplitude/-cor/-size/-start``); see
    :func:`shaketable.studies.planar_ensemble.planar_ensemble`.
    """
    from shaketable.core.files import json_ready_dict, write_csv, write_text
    from shaketable.plots import base as plots
    from shaketable.studies.planar_ensemble import planar_ensemble

    perturbation = ensemble_perturbation(args, motion)
    result = planar_ensemble(block, motion, args.cor, friction, members=args.ensemble,
                             perturbation=perturbation, seed=args.seed, duration=args.duration)
    write_csv(out / "ensemble.csv", result.to_frame())
    summary = json_ready_dict(result.summary)
    summary["perturbation [-]"] = dataclasses.asdict(perturbation)
    write_text(out / "ensemble.json", json.dumps(summary, indent=2, default=float))
    plots.save(result.plot().figure, out / f"ensemble.{args.format}")
    print(f"{block.describe()} block, COR {args.cor}, mu_s {friction.static:g}, mu_d "
          f"{friction.dynamic:g}, {args.ensemble} members (planar model): "
          f"{result.describe()}")
    print(perturbation_line(perturbation))
    print(f"wrote {out / 'ensemble.csv'}, {out / 'ensemble.json'}, "
          f"{out / ('ensemble.' + args.format)}")
    return 0


def perturbation_line(perturbation) -> str:
    """What the members differ by, said with the answer: the default spread (1e-9) probes
    chaos (nearly equal runs that part), it is not an uncertainty of the inputs."""
    sizes = ", ".join(f"{name} {value:g}" for name, value in
                      dataclasses.asdict(perturbation).items())
    line = f"  members differ by a relative spread of: {sizes}"
    if max(dataclasses.asdict(perturbation).values()) < 1e-3:
        line += (" (a probe of chaos, not an uncertainty of the inputs: --perturb 0.05 "
                 "spreads them by 5 %)")
    return line


def ensemble_perturbation(args, motion):
    """The members' :class:`~shaketable.core.ensemble.Perturbation` from ``--perturb`` and
    ``--perturb-amplitude/-cor/-size/-start`` (each defaulting to ``--perturb``), after
    checking that ``--ensemble`` has a motion and at least two members."""
    from shaketable.core.ensemble import Perturbation

    if motion is None:
        raise ValueError("--ensemble needs a --record (free rocking from --theta0 is not chaotic)")
    if args.ensemble < 2:
        raise ValueError(f"--ensemble must be 2 or more members (the nominal run and its "
                         f"perturbed copies), got {args.ensemble}")
    spread = args.perturb
    return Perturbation(
        amplitude=spread if args.perturb_amplitude is None else args.perturb_amplitude,
        cor=spread if args.perturb_cor is None else args.perturb_cor,
        size=spread if args.perturb_size is None else args.perturb_size,
        start=spread if args.perturb_start is None else args.perturb_start)
