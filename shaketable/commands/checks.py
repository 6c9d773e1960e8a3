"""Checks the commands share, run before any work, and the early-stop report after it.

Kept apart from the commands' own modules so that each command calls one function per
check: options that one model would ignore (:func:`refuse_ignored_options`), and a run
that ended before its motion did (:func:`report_early_stops`: said on stderr, exit 1).
"""

from __future__ import annotations

import sys
from collections.abc import Iterable


def report_early_stops(results: Iterable, command: str, label: str = "") -> int:
    """Say on stderr which runs stopped before their motion ended; the exit status.

    Parameters
    ----------
    results : iterable of results
        Runs of any model (:func:`shaketable.models.stops.early_stop` decides).
    command : str
        The subcommand, for the message prefix.
    label : str
        What the runs are (a block, a scene), for the message.

    Returns
    -------
    int
        1 when any run stopped early (the command's exit status), else 0.
    """
    from shaketable.models.stops import early_stop

    reasons = [reason for reason in (early_stop(result) for result in results) if reason]
    for reason in reasons:
        print(f"shaketable {command}: warning: {label + ': ' if label else ''}the run "
              f"{reason}; exit status 1", file=sys.stderr)
    return 1 if reasons else 0


def report_stopped_rows(table, name: str, command: str = "sweep") -> int:
    """Say on stderr how many runs of a sweep table stopped before their motion ended
    (a ``status`` other than completed or overturned); the exit status (1 if any).

    The rows keep what the run computed up to its stop (the ``status`` column says
    which stopped); the sweep's table is complete, but a fragility or risk read from
    it counts such runs as not overturned, which the user must know.
    """
    from shaketable.models.stops import FINISHED_STATUSES

    if "status" not in table:
        return 0
    stopped = table[~table["status"].isin(FINISHED_STATUSES)]
    if not len(stopped):
        return 0
    run_column = "run" if "run" in table else "member"
    print(f"shaketable {command}: warning: {name}: {len(stopped)} of {len(table)} run(s) stopped "
          f"before their motion ended (status "
          f"{', '.join(sorted(map(str, stopped['status'].unique())))}; runs "
          f"{', '.join(str(run) for run in stopped[run_column].head(5))}"
          f"{' ...' if len(stopped) > 5 else ''}; see the 'status' column and "
          "docs/planar.md); their results cover the run up to the stop only"
          + ("; a stack run that stalled has none and is left out of the fits (docs/stack.md)"
             if (stopped["status"] == "stalled").any() else "") + "; exit status 1",
          file=sys.stderr)
    return 1


def refuse_ignored_options(args, model: str, ignored: dict) -> None:
    """Refuse options the chosen model would ignore, naming them and the option that
    chose the model.

    Parameters
    ----------
    args : argparse.Namespace
    model : str
        The option (or options) that chose the model, e.g. ``"--friction"``.
    ignored : dict
        ``{"--option": default}``: each option whose value differs from its default
        is refused.

    Raises
    ------
    ValueError
        Naming the first option given and ``model``.
    """
    for option, default in ignored.items():
        value = getattr(args, option.lstrip("-").replace("-", "_"), default)
        if value != default and value is not None:
            raise ValueError(f"{option} {value!r} cannot be used with {model}: that model "
                             f"does not take {option} (it would be ignored); leave out "
                             f"{option}, or {model}")


#: ``simulate``'s options that belong to one model or mode, with their defaults.
_ENSEMBLE_OPTIONS = {"--perturb": 1e-9, "--perturb-amplitude": None, "--perturb-cor": None,
                     "--perturb-size": None, "--perturb-start": None,
                     "--horizon-threshold": 1e-3}


def check_simulate_options(args, refuse=lambda args: None) -> None:
    """Refuse the ``simulate`` options the chosen model or mode would ignore.

    ``refuse(args)`` refuses those the chosen model does not take (the planar model's
    :meth:`~shaketable.commands.simulate_models.PlanarCommand.refuse`: no ``--method``,
    ``--subdivisions`` or calibration file as ``--cor``); ``--subdivisions`` belongs to
    ``--method predictor-corrector``; the perturbation options and ``--seed`` belong to
    ``--ensemble`` (or to a calibration file as ``--cor``, which draws its CORs with
    ``--seed``); an ensemble writes no ``history.csv`` (no ``--history``).

    Raises
    ------
    ValueError
        Naming both options.
    """
    calibrated = isinstance(args.cor, str)
    from shaketable.core.ensemble import MAX_MEMBERS

    if args.ensemble and not 2 <= args.ensemble <= MAX_MEMBERS:
        raise ValueError(f"--ensemble {args.ensemble}: must be from 2 to {MAX_MEMBERS:,} "
                         "members (each is a run)")
    refuse(args)   # the options the chosen model does not take
    if args.method != "predictor-corrector":
        refuse_ignored_options(args, f"--method {args.method}", {"--subdivisions": 4})
    moving = any(getattr(args, name, None) for name in ("record", "harmonic", "pulse"))
    if args.ensemble and not moving:
        raise ValueError("--ensemble needs a --record (or --harmonic, --pulse): free rocking "
                         "from --theta0 is not chaotic, every member would be the same run")
    ensemble = bool(args.ensemble) or (calibrated and moving)
    if not ensemble:
        refuse_ignored_options(args, "a single run (no --ensemble)",
                               {**_ENSEMBLE_OPTIONS, "--seed": 0})
    else:
        refuse_ignored_options(args, "--ensemble" if args.ensemble else
                               f"--cor {args.cor} (an ensemble over the calibrated COR)",
                               {"--history": "auto"})
        if calibrated:
            refuse_ignored_options(args, f"--cor {args.cor} (an ensemble over the calibrated "
                                   "COR)", _ENSEMBLE_OPTIONS)


def check_animate_options(args) -> None:
    """``animate``'s --dpi, --fps and --speed, bounded before the scene runs (a dpi or a
    frame rate beyond :data:`~shaketable.plots.animation.DPI_RANGE` and
    :data:`~shaketable.plots.animation.FPS_RANGE` would exhaust memory or fail inside the
    writers)."""
    import math

    from shaketable.plots.animation import DPI_RANGE, FPS_RANGE

    for option, value, (low, high), unit in (("--dpi", args.dpi, DPI_RANGE, "dots per inch"),
                                             ("--fps", args.fps, FPS_RANGE,
                                              "frames per second")):
        if not (math.isfinite(value) and low <= value <= high):
            raise ValueError(f"{option} {value:g}: must be from {low:g} to {high:g} {unit}")
    if args.speed is not None and not (math.isfinite(args.speed) and args.speed > 0):
        raise ValueError(f"--speed {args.speed:g}: must be a positive number of simulated "
                         "seconds per second")


def with_option_names(error: ValueError, options: dict) -> ValueError:
    """``error`` with the library's parameter name at the start of its message replaced by
    the command's option (``scan_step must be ...`` -> ``--scan-step must be ...``), so a
    refusal names what the user typed."""
    message = str(error)
    for parameter, option in options.items():
        if message.startswith(parameter + " ") or message.startswith(parameter + ":"):
            return ValueError(option + message[len(parameter):])
    return ValueError(message)


def check_slide_options(args) -> None:
    """Refuse the ``slide`` options the chosen mode would ignore: ``--table-4-4`` takes
    only ``--seed`` (and ``--out``); ``--sweep`` gives the dynamic frictions itself (no
    ``--static-friction``, ``--dynamic-friction`` or ``--block``); ``--seed`` belongs to
    ``--table-4-4``."""
    if args.table_4_4:
        refuse_ignored_options(args, "--table-4-4", {
            "--record": None, "--sweep": None, "--static-friction": 0.2,
            "--dynamic-friction": None, "--block": None, "--scale": 1.0, "--units": None,
            "--dt": None, "--column": None, "--no-vertical": False})
        return
    refuse_ignored_options(args, "a run on a record (no --table-4-4)", {"--seed": 1})
    if args.sweep:
        refuse_ignored_options(args, "--sweep", {"--static-friction": 0.2,
                                                 "--dynamic-friction": None, "--block": None})


def refuse_stack_options(args) -> None:
    """``--masses``, ``--densities`` and ``--mu`` without ``--stack``: refused, naming them."""
    for option in ("--masses", "--densities", "--mu"):
        if getattr(args, option[2:], None) is not None:
            raise ValueError(f"{option} is for a column of blocks: give --stack (e.g. --stack "
                             "30x6in,30x6in), or leave out " + option)
