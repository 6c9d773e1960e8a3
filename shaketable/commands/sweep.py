"""``shaketable sweep SPEC.toml``: a parameter sweep into a tidy, resumable table."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import argparse


def _sweep(args: argparse.Namespace) -> int:
    from shaketable.commands.common import compiled_before, notice_first_compile
    from shaketable.core.files import prepare_output_folder
    from shaketable.scenes.catalog import resolve_sweep_path
    from shaketable.sweeps.execute import refuse_a_second_sweep, run_sweep
    from shaketable.sweeps.spec import load_spec

    if args.workers is not None and args.workers < 1:
        raise ValueError(f"--workers must be a positive number (of threads; of processes for a "
                         f"stack sweep), got {args.workers}")
    if args.max_chunks is not None and args.max_chunks < 0:
        raise ValueError(f"--max-chunks must be 0 or more, got {args.max_chunks}")
    spec = load_spec(resolve_sweep_path(args.spec))
    out = prepare_output_folder(args.out or Path("shaketable-out") / spec.name)
    if not args.resume:   # said first, before what would have run
        refuse_a_second_sweep(out)
    where = f"Dask cluster {args.scheduler}" if args.scheduler else (
        (f"{args.workers} local process(es)" if args.workers and args.workers > 1
         else "one local process") if spec.model.processes else
        f"{args.workers} local thread(s)" if args.workers else "all local cores")
    # what is about to run, on stderr beside the progress bar: the console's output leads
    # with the answer
    setup = [f"{spec.name}: {spec.n_runs} runs in {spec.n_chunks} chunk(s) of "
             f"{spec.chunk_size}, on {where}"]
    if spec.ensemble is not None:
        setup.append(f"{spec.name}: each run is an ensemble of {spec.ensemble['members']} "
                     f"perturbed copies ([ensemble]: {spec.n_runs * spec.ensemble['members']} "
                     "simulations)")
    if spec.model.describe() is not None:   # the model the spec chose (not the default)
        setup.append(f"{spec.name}: {spec.model.describe()}")
    if spec.model.processes and not args.scheduler and (args.workers or 1) > spec.n_chunks:
        setup.append(f"{spec.name}: note: {args.workers} processes for {spec.n_chunks} "
                     "chunk(s): a process computes whole chunks; a smaller [run] chunk_size "
                     "gives each process one")
    from shaketable.sweeps import store

    fmt = "parquet" if store.parquet_available() else "csv"   # run_sweep's own default
    if fmt == "csv":   # said with the rest, so that --quiet silences it too
        setup.append("shaketable sweep: note: pyarrow is not installed, writing CSV instead "
                     "of Parquet (pip install pyarrow: the 'parquet' extra)")
    if not args.quiet:
        for line in setup:
            print(line, file=sys.stderr)
    engine = {"rocking": "batch", "planar": "planar"}.get(spec.model.name)
    compiling = engine is not None and not args.scheduler and not compiled_before(engine)
    if engine is not None and not args.scheduler:
        notice_first_compile(args.quiet, which=(engine,))
    outcome = run_sweep(spec, out, workers=args.workers, scheduler=args.scheduler,
                        resume=args.resume, progress=not (args.no_progress or args.quiet),
                        max_chunks=args.max_chunks, fmt=fmt)
    rate = outcome.computed_runs / outcome.seconds if outcome.seconds > 0 else float("nan")
    computed = (f"{spec.name}: computed {outcome.computed_runs} runs in {outcome.seconds:.1f} s "
                f"({rate:.3g} runs/s{', the first compile included' if compiling else ''}); "
                f"{outcome.skipped_runs} were already on disk")
    if not outcome.complete:
        print(computed)
        print(f"{spec.name}: stopped before the end; run again with --resume to finish "
              f"(finished chunks are in {out / 'parts'})")
        return 0
    table = outcome.table
    assert table is not None   # complete: the joined table was read
    # the answer first, then how it was computed
    if spec.friction is not None:
        from shaketable.sweeps.friction import friction_summary, verdict_counts

        print(f"{spec.name}: verdicts of the {len(table)} runs: {verdict_counts(table)}")
        for line in friction_summary(table):
            print(f"    {line}")
    elif spec.model.name == "stack":
        from shaketable.sweeps.stacks import DEFAULT_STACK_RTOL, overturn_answer, retried_line

        print(f"{spec.name}: {overturn_answer(table)}; "
              f"{int(table['airborne'].sum())} stopped where a block would leave its support")
        if retried := retried_line(table, spec.options.get("rtol", DEFAULT_STACK_RTOL)):
            print(f"{spec.name}: {retried}")
    else:
        print(f"{spec.name}: {int(table['overturned'].sum())} of {len(table)} runs overturn, "
              f"{int(table['airborne'].sum())} airborne (vertical reached -g; stopped there)")
    print(computed)
    from shaketable.commands.checks import report_stopped_rows

    status = report_stopped_rows(table, spec.name)
    if "mark" in table:
        assert spec.ensemble is not None   # the mark column comes from [ensemble]
        fragile = table[table["mark"] == "fragile"]
        print(f"{spec.name}: {len(fragile)} of {len(table)} verdicts are fragile (some of the "
              f"{spec.ensemble['members']} perturbed copies disagree; see 'P(overturn) [-]'), "
              f"{len(table) - len(fragile)} robust")
    # (a CSV table: run_sweep said at the start that pyarrow is missing)
    print(f"wrote {outcome.path}")
    if "spectrum_scale [-]" in table:   # the factors to the target spectrum
        factors = table[["record", "seed", "spectrum_scale [-]"]].drop_duplicates()
        from shaketable.core.files import write_csv

        write_csv(out / "spectrum-scale-factors.csv", factors)
        print(f"wrote {out / 'spectrum-scale-factors.csv'} (each record's factor to the "
              "target spectrum)")
    if args.figures and spec.model.name == "stack":
        from shaketable.core.files import subfolder
        from shaketable.plots.sweep_stacks import stack_sweep_figures

        paths = stack_sweep_figures(table, subfolder(out, "figures"))
        print("wrote " + ", ".join(str(path) for path in paths))
    elif args.figures:
        from shaketable.core.files import subfolder
        from shaketable.plots.sweeps import sweep_figures
        from shaketable.sweeps.friction import friction_figure_sets

        paths = [path for rows, folder in friction_figure_sets(table, subfolder(out, "figures"))
                 for path in sweep_figures(rows, folder)]
        print("wrote " + (", ".join(str(path) for path in paths) if paths else
                          "no figure (the table has no grid of blocks or of PGA to draw)"))
    return status


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``sweep`` subcommand."""
    parser = commands.add_parser(
        "sweep", help="run a parameter sweep (TOML spec) into a table, resumable",
        description="Run every combination of blocks (or stacks of blocks), COR, records, "
                    "PGA levels, pitch phases and friction coefficients named in a sweep "
                    "spec, with the model it names (see "
                    "shaketable.sweeps.spec) and write one row per run to "
                    "OUT/results.parquet (OUT/results.csv where pyarrow is not "
                    "installed: pip install pyarrow). Finished chunks are kept on disk: a killed sweep "
                    "continues with --resume.")
    from shaketable.scenes.catalog import sweep_names

    parser.add_argument("spec", help="path to a sweep spec .toml, or the name of a bundled "
                                     f"one ({', '.join(sweep_names())})")
    parser.add_argument("--out", help="output folder (default shaketable-out/<sweep name>)")
    parser.add_argument("--workers", type=int, default=None,
                        help="local threads (default all cores); for a stack sweep, local "
                             "processes, each computing whole chunks (default one); with "
                             "--scheduler, threads inside each Dask task (default 1)")
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS",
                        help="run the chunks on a dask.distributed cluster "
                             "(e.g. tcp://host:8786)")
    parser.add_argument("--resume", action="store_true",
                        help="continue the sweep already in --out (keeps finished chunks)")
    parser.add_argument("--max-chunks", type=int, default=None,
                        help="compute at most this many chunks now, then stop")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    parser.add_argument("--figures", action="store_true",
                        help="also draw what the table supports: overturning maps and rocking "
                             "spectra per record and COR, fragility curves over PGA; for "
                             "a sweep scaled to an intensity measure, fragility against it, "
                             "PGA and PGV p/(g tan a) with confidence bands, the PGA-PGV "
                             "surface and the IM comparison (OUT/figures/; a [friction] "
                             "sweep: one folder per friction pair; a [stacks] sweep: P(some "
                             "block overturns) per stack beside the block alone, with fits, "
                             "and which block falls first)")
    parser.set_defaults(handler=_sweep)
