"""``shaketable records``: the bundled records with their PGA, PGV, duration and source."""

from __future__ import annotations

import math


def _number(value: float, spec: str) -> str:
    return "-" if isinstance(value, float) and math.isnan(value) else format(value, spec)


def _records(args) -> int:
    from shaketable.ground.records import catalog

    table = catalog()
    header = (f"{'name':<20} {'components':<22} {'PGA [g]':>8} {'PGV [m/s]':>9} "
              f"{'vert. PGA [g]':>13} {'duration [s]':>12} {'dt [s]':>7}")
    print(header)
    for row in table.itertuples(index=False):
        print(f"{row.name:<20} {row.components:<22} {_number(row[2], '.3f'):>8} "
              f"{_number(row[3], '.3f'):>9} {_number(row[4], '.3f'):>13} "
              f"{row[5]:>12.2f} {row[6]:>7.3g}")
    print("\nsources:")
    for row in table.itertuples(index=False):
        print(f"  {row.name}: {row.title}; {row.source}")
    print("\nPGA and PGV of the horizontal (PGV from rest, not baseline-corrected); use a "
          "name with --record, and --pga 0.5g to scale it to a target PGA")
    if args.csv:
        from shaketable.core.files import write_csv

        write_csv(args.csv, table)
        print(f"wrote {args.csv}")
    return 0


def register(commands) -> None:
    """Add the ``records`` subcommand."""
    parser = commands.add_parser(
        "records", help="list the bundled records: PGA, PGV, duration, dt, components, source",
        description="List the strong-motion records bundled with shaketable (the names "
                    "--record takes) with their PGA [g], PGV [m/s], duration, time step, "
                    "components and source, computed from the files.")
    parser.add_argument("--csv", metavar="FILE", help="also write the table as CSV")
    parser.set_defaults(handler=_records)
