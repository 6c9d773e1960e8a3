"""What the subcommands share: reading ``--record`` into a motion."""

from __future__ import annotations

from pathlib import Path


def load_motion(args):
    """``--record``: a bundled record by name, or a record file (``--units``, ``--dt``)."""
    from shaketable.ground import records

    if args.record in records.available():
        return records.load(args.record, vertical=not args.no_vertical)
    path = Path(args.record)
    if not path.exists():
        raise ValueError(f"--record {args.record!r}: no such file and no bundled record of that "
                         f"name (bundled: {', '.join(records.available())})")
    # an AT2 states its step and (usually) its units in its header: --units is checked
    # against it or supplies what it does not say, --dt is refused for it with a clear
    # message; records.read ignores options left at None
    record = records.read(path, units=args.units, dt=args.dt)
    return records.combine(record, name=path.stem)
