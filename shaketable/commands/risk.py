"""``shaketable risk SWEEP_FOLDER --hazard CURVE.csv``: the annual rate of overturning at a
site and the probability in a design life, from a sweep's fragility and a hazard curve."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import argparse

#: ``--hazard example``: the bundled SYNTHETIC hazard curve (PGV).
EXAMPLE_HAZARD = "example-hazard-pgv.csv"


def hazard_path(text: str) -> Path:
    """A hazard curve file, or ``example`` for the bundled synthetic one."""
    if text == "example":
        from shaketable.scenes.catalog import experiments_folder

        return experiments_folder() / "sweeps" / EXAMPLE_HAZARD
    return Path(text)


def _risk(args: argparse.Namespace) -> int:
    import math
    import sys

    from shaketable.sweeps.fragility import fragility_fit, measure_column
    from shaketable.sweeps.risk import (
        FEW_RECORDS,
        MAX_YEARS,
        overturning_rate,
        read_hazard_curve,
        share_outside,
    )
    from shaketable.sweeps.store import read_manifest, read_results

    folder = Path(args.sweep)
    if not (folder / "manifest.json").is_file():
        raise FileNotFoundError(f"{folder}: not a sweep folder (no manifest.json); run "
                                "'shaketable sweep SPEC --out FOLDER' first")
    if not (math.isfinite(args.years) and 0 < args.years <= MAX_YEARS):
        raise ValueError(f"--years must be a design life from 0 to {MAX_YEARS:g} yr, got "
                         f"{args.years!r}")
    if args.figure is not None:   # before the work: a bad path loses nothing
        from shaketable.core.files import prepare_output_file

        prepare_output_file(args.figure, "--figure", suffixes=(".png", ".svg", ".pdf"))
    hazard = read_hazard_curve(hazard_path(args.hazard))
    table = read_results(folder)
    expected = read_manifest(folder).get("n_runs")
    if isinstance(expected, int) and len(table) < expected:
        print(f"shaketable risk: warning: {folder} is an unfinished sweep ({len(table)} of "
              f"{expected} runs on disk): the fragility is fitted to the finished runs only; "
              "finish it with 'shaketable sweep SPEC --out FOLDER --resume'", file=sys.stderr)
    if "status" in table:
        stopped = ~table["status"].isin(("completed", "overturned"))
        if stopped.any():
            print(f"shaketable risk: warning: {int(stopped.sum())} run(s) of the sweep stopped "
                  "before their motion ended (see its 'status' column); they count as not "
                  "overturned", file=sys.stderr)
    column = measure_column(table, hazard.column if args.measure is None else args.measure)
    if column != hazard.column:
        raise ValueError(f"--measure {args.measure!r} is column {column!r} but the hazard "
                         f"curve {hazard.source} is of {hazard.column!r}")
    if args.cor is not None:
        table = table[table["cor [-]"].round(9) == round(args.cor, 9)]
        if table.empty:
            raise ValueError(f"--cor {args.cor:g}: no run of the sweep has this COR")
    if args.block is not None:
        table = table[table["block"] == args.block]
        if table.empty:
            raise ValueError(f"--block {args.block!r}: no such block in the sweep (blocks: "
                             f"{', '.join(read_results(folder)['block'].unique())})")
    synthetic = args.hazard == "example"
    source = ("the bundled SYNTHETIC example (not a real site)" if synthetic
              else str(hazard.source))
    # the answer (P(overturn) per block or stack) first; the hazard curve said after it
    curve = (f"hazard curve {source}: {hazard.column}, {len(hazard.im)} points from "
             f"{hazard.im[0]:.3g} to {hazard.im[-1]:.3g}; design life {args.years:g} yr")
    results = []
    headline: list = []
    from shaketable.sweeps.friction import friction_pairs, friction_rows

    # a friction sweep: one fragility per friction pair too (the pairs are not pooled)
    pairs = friction_pairs(table) or [None]
    # a stack sweep's plastic impacts have no COR (NaN): a group of their own
    groups = [(block, (f"COR {cor:g}" if cor == cor else "plastic impacts")
               + ("" if pair is None else f", mu_s {pair[0]:g}, mu_d {pair[1]:g}"), rows)
              for pair in pairs
              for (block, cor), rows in (table if pair is None else friction_rows(
                  table, *pair)).groupby(["block", "cor [-]"], sort=False, dropna=False)]
    from shaketable.sweeps.stacks import finished_runs, overturned_line
    # a stack sweep leads with the answer (P(some block overturns) of each stack against
    # the block alone's): its lines are said after that headline, in their order
    stacks = "overturned block" in table
    said: list = []

    def say(text: str, file=sys.stdout) -> None:
        if stacks:
            said.append((text, file))
        else:
            print(text, file=file)

    for block, label, every in groups:
        # a stack run that stalled is neither a fall nor a survival: left out, and said
        # (overturned_line)
        rows = finished_runs(every) if stacks else every
        try:
            fit = fragility_fit(rows[column], rows["overturned"], measure=column)
        except ValueError as error:
            say(f"shaketable risk: {block}, {label}: no fragility, so no rate ({error})",
                file=sys.stderr)
            continue
        result = overturning_rate(fit, hazard, years=args.years)
        results.append((block, label, fit, result))
        if stacks:
            headline.append((block, label, result, rows))
        say(f"{block}, {label}: {result.summary()}")
        say(f"    fragility {fit.summary()}")
        if fell := overturned_line(every):   # a stack sweep: which block fell
            say(f"    {fell}")
        low, high = float(rows[column].min()), float(rows[column].max())
        outside = share_outside(fit, hazard, low, high)
        if outside > 0.1:   # the lognormal carried beyond the levels run: say how much
            say(f"shaketable risk: warning: {block}, {label}: {100 * outside:.0f} % of "
                f"lambda comes from {column} outside the levels the sweep ran ({low:.3g} "
                f"to {high:.3g}), where the fitted lognormal is extrapolated",
                file=sys.stderr)
        motions = len(rows[[key for key in ("record", "seed") if key in rows]]
                      .drop_duplicates())
        if motions < FEW_RECORDS:
            say(f"shaketable risk: warning: {block}, {label}: the fragility rests on "
                f"{motions} ground motion(s); fewer than {FEW_RECORDS} make its beta, and "
                "lambda, uncertain (the interval above says how much): add records",
                file=sys.stderr)
    for line in stack_headline(headline, args.years):
        print(line)
    for text, file in said:
        print(text, file=file)
    print(curve)
    if not results:
        print(f"shaketable risk: error: no rate of overturning can be given: no block and COR "
              f"of {folder} has a fragility against {column} (see above); exit status 1",
              file=sys.stderr)
        return 1
    if args.figure and results:
        from shaketable.plots.base import pyplot, save
        from shaketable.plots.sweeps import risk_curves, shared_risk_legend

        plt = pyplot()
        figure, axes = plt.subplots(len(results), 1, figsize=(7.5, 3.9 * len(results) + 0.8),
                                    squeeze=False)
        for axis, (block, label, fit, result) in zip(axes[:, 0], results):
            risk_curves(fit, hazard, result, ax=axis, legend=False)
            axis.set_title(f"{block}, {label}: " + axis.get_title(), fontsize=8)
        shared_risk_legend(list(axes[:, 0]))
        if synthetic:
            figure.suptitle("SYNTHETIC example hazard curve (not a real site)", fontsize=9,
                            color="tab:red")
        figure.tight_layout()
        save(figure, args.figure)
        print(f"wrote {args.figure}")
    return 0


def stack_headline(entries: list, years: float) -> list:
    """The answer of ``risk`` on a stack sweep, before the details: per impact law, each
    stack's P(some block overturns in the design life) with its interval, the most
    likely first, as a multiple of the block alone's (the one-block column of the same
    bottom block, when the sweep ran it) and which block fell first.

    ``entries`` holds (stack, impact law, OverturningRate, rows) of each fitted stack.
    """
    from shaketable.sweeps.stacks import overturned_blocks

    lines = []
    laws = dict.fromkeys(label for _, label, _, _ in entries)
    for law in laws:
        group = [entry for entry in entries if entry[1] == law]

        def bottom(rows):
            return (round(float(rows["R [m]"].iloc[0]), 9),
                    round(float(rows["base width [m]"].iloc[0]), 9))

        alone = {bottom(rows): result.probability for _, _, result, rows in group
                 if int(rows["blocks"].iloc[0]) == 1}
        level = group[0][2].confidence
        lines.append(f"P(some block overturns in {years:g} yr), {law}"
                     + (f" ({100 * level:g} % interval from the fragility fit)"
                        if level == level else "") + ":")
        for stack, _, result, rows in sorted(group, key=lambda entry: -entry[2].probability):
            low, high = result.probability_interval
            text = f"    {stack}: {result.probability:.2g}"
            if low == low and high == high:
                text += f" ({low:.2g} to {high:.2g})"
            single = alone.get(bottom(rows))
            if int(rows["blocks"].iloc[0]) > 1 and single:
                text += f", {result.probability / single:.2g} x the block alone's"
            fell = overturned_blocks(rows)
            if fell and int(rows["blocks"].iloc[0]) > 1:
                text += (f"; the first to fall in its {int(rows['overturned'].sum())} runs "
                         f"that overturned: {fell}")
            lines.append(text)
    return lines


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``risk`` subcommand."""
    parser = commands.add_parser(
        "risk", help="annual rate of overturning at a site from a sweep and a hazard curve",
        description="Fit a lognormal fragility (maximum likelihood, with profile-likelihood "
                    "intervals) to a finished sweep against the hazard curve's intensity "
                    "measure, per block and COR, and integrate it over the hazard curve: "
                    "lambda = int P(overturn | im) |d lambda_IM|, with the integral's "
                    "discretisation error, and P(overturn in the design life) = "
                    "1 - exp(-lambda years).")
    parser.add_argument("sweep", help="a sweep's output folder (shaketable sweep --out)")
    parser.add_argument("--hazard", required=True,
                        help="hazard curve CSV: header 'pgv [m/s], annual_rate [1/yr]' (or "
                             "pga [g], sa(1 s) [g], ...), rows IM, rate; 'example' for the "
                             "bundled SYNTHETIC PGV curve")
    parser.add_argument("--measure", default=None,
                        help="the table column (or short name) of the hazard's measure "
                             "(default: from the hazard curve's header)")
    parser.add_argument("--block", default=None, help="only this block (as in the table)")
    parser.add_argument("--cor", type=float, default=None, help="only this COR [-]")
    parser.add_argument("--years", type=float, default=50.0,
                        help="design life [yr] (default 50)")
    parser.add_argument("--figure", default=None,
                        help="also draw hazard, fragility and risk integrand to this PNG")
    parser.set_defaults(handler=_risk)
