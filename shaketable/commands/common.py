"""What the subcommands share: reading ``--record`` into a motion, the first-compile notice."""

from __future__ import annotations

import os
import sys
from pathlib import Path

from shaketable.core.numba_cache import cache_subpath


def add_record_arguments(parser) -> None:
    """The options :func:`load_motion` and :func:`scaled` read: --record, --units, --dt,
    --column, --scale, --no-vertical."""
    parser.add_argument("--record", help="bundled record name (e.g. pacoima-dam-s16e) or a file")
    parser.add_argument("--units", help="units of the record file: g, m/s2 or gal (needed for "
                                        "a text file, and for an AT2 whose header does not "
                                        "state them)")
    from shaketable.commands.options import add_quantity

    add_quantity(parser, "--dt", kind="time", example="0.02s", positive=True,
                 help="sample interval of a one-column record")
    parser.add_argument("--column", help="the acceleration column of a text record with "
                                         "several, by 0-based index or header name")
    scale = parser.add_mutually_exclusive_group()
    scale.add_argument("--scale", type=float, default=None,
                       help="factor on the record [-] (default 1)")
    scale.add_argument("--pga", metavar="ACCELERATION",
                       help="scale the record to this horizontal PGA, with its unit (e.g. "
                            "0.5g, 3m/s2); the record's own PGA and the factor are printed "
                            "(not with --scale)")
    parser.add_argument("--no-vertical", action="store_true",
                        help="drop the vertical component")


def load_motion(args):
    """``--record``: a bundled record by name, or a record file (``--units``, ``--dt``)."""
    from shaketable.ground import records

    if args.record in records.available():
        return records.load(args.record, vertical=not args.no_vertical)
    path = Path(args.record)
    if path.is_dir():
        raise ValueError(f"--record {args.record!r}: is a folder; give a record file or a "
                         f"bundled record name (bundled: {', '.join(records.available())})")
    if not path.exists():
        raise ValueError(f"--record {args.record!r}: no such file and no bundled record of that "
                         f"name (bundled: {', '.join(records.available())})")
    # an AT2 states its step and (usually) its units in its header: --units is checked
    # against it or supplies what it does not say, --dt is refused for it with a clear
    # message; records.read ignores options left at None
    column = getattr(args, "column", None)
    if column is not None and column.strip().lstrip("-").isdigit():
        column = int(column)
    record = records.read(path, units=args.units, dt=args.dt, value_column=column)
    try:
        return records.combine(record, name=path.stem)
    except ValueError as error:  # e.g. values beyond any earthquake: say which file
        raise ValueError(f"{path}: {error}") from None


def scaled(motion, factor, option: str = "--scale"):
    """The motion times ``--scale``, the option checked and named (None: unscaled)."""
    from shaketable.core.validation import number

    if factor is None:
        return motion
    factor = number(option, factor)
    return motion if factor == 1.0 else motion.scaled(factor)


def scaled_record(motion, args):
    """``--scale`` or ``--pga`` applied to the ``--record``: ``(motion, note)``.

    ``note`` says the record's own PGA and the factor used to reach ``--pga``
    (None without ``--pga``). ``--pga`` needs a record with a horizontal component.
    """
    target_text = getattr(args, "pga", None)
    if target_text is None:
        return (None if motion is None else scaled(motion, args.scale)), None
    from shaketable.core.units import parse
    from shaketable.ground.records import scaled_to_pga

    if args.scale is not None:     # argparse refuses both; a programmatic args may not
        raise ValueError("--pga and --scale both scale the record: give one")
    if motion is None or not getattr(args, "record", None):
        raise ValueError(f"--pga {target_text}: scales a --record (a --harmonic or --pulse "
                         "states its amplitude itself)")
    target = parse(target_text, "acceleration", where="--pga")
    return scaled_to_pga(motion, target, name=args.record, where=f"--pga {target_text}")


#: The compiled functions whose numba cache files tell that the engine was compiled
#: before, and what their first compilation costs on the 2-core CI machine (measured, README).
_COMPILED = {"engine": ("engine.integrate_fast-", "the engine", "~3 s", "rocking"),
             "batch": ("batch._run_cases_fast-", "the batch engine", "~1 s", "rocking"),
             "planar": ("engine.integrate-", "the planar engine", "~13 s", "planar"),
             "stack": ("compiled.run_stack-", "the stack engine", "~28 s", "stack")}


def compiled_before(which: str = "engine") -> bool:
    """Whether numba's on-disk cache holds the compiled ``which`` (engine or batch).

    Looks for the cache index files numba writes (``NUMBA_CACHE_DIR``, set by
    ``import shaketable`` to the user's cache folder unless already set) for the
    installed model's folder and this Python version, without importing numba.
    """
    import shaketable.models as models

    folder = os.path.join(os.path.dirname(os.path.abspath(models.__file__)), _COMPILED[which][3])
    cache = Path(os.environ.get("NUMBA_CACHE_DIR", "")) / cache_subpath(folder)
    tag = f"py{sys.version_info.major}{sys.version_info.minor}"
    prefix = _COMPILED[which][0]
    return cache.is_dir() and any(cache.glob(f"{prefix}*.{tag}.nbi"))


def notice_first_compile(quiet: bool = False, which=("engine",)) -> None:
    """One line on stderr when the engine (or the batch engine) is about to compile."""
    if quiet:
        return
    missing = [name for name in which if not compiled_before(name)]
    if missing:
        parts = [f"{_COMPILED[name][1]} ({_COMPILED[name][2]})" for name in missing]
        them = "it" if len(missing) == 1 else "them"
        named = parts[0] if len(parts) == 1 else f"{', '.join(parts[:-1])} and {parts[-1]}"
        print(f"shaketable: compiling {named} once; later runs load {them} "
              f"from the cache in {os.environ.get('NUMBA_CACHE_DIR')}", file=sys.stderr,
              flush=True)


