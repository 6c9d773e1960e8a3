"""``shaketable validate calibrate|predict|score``: measured shake-table tests.

* ``calibrate FOLDER --out cal.json``: an equivalent block per specimen by maximum
  likelihood with its bagged ensemble, 95 % profile-likelihood and bootstrap sets checked
  by an independent bootstrap, k-fold cross-validated scores with the baselines (all in
  the JSON, with the ids of the tests it was fitted on); progress lines on stderr;
* ``predict FOLDER --calibration cal.json --out predictions.csv``: P(overturn) and the
  verdict of every test and specimen (the folder's outcome columns are not needed), each
  row marked ``in_training`` when the calibration was fitted on that test;
* ``score predictions.csv FOLDER``: accuracy, confusion, log loss, Brier, reliability and
  fragility against the folder's outcomes, in-sample and out-of-sample rows also apart
  (``--figures DIR`` draws them).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path


def _floats(text: str, option: str) -> tuple[float, ...]:
    try:
        values = tuple(float(part) for part in text.split(",") if part.strip())
    except ValueError:
        raise ValueError(f"{option} {text!r}: give numbers separated by commas") from None
    if not values:
        raise ValueError(f"{option} {text!r}: give at least one number")
    return values


def _grid(args):
    from shaketable.validation.model import CandidateGrid

    default = CandidateGrid()
    cors: list[float | str] = []
    if args.cors:
        for part in args.cors.split(","):
            part = part.strip().lower()
            cors.append(part if part == "housner" else _floats(part, "--cors")[0])
    return CandidateGrid(
        alphas=_floats(args.alphas, "--alphas") if args.alphas else default.alphas,
        ratios=_floats(args.ratios, "--ratios") if args.ratios else default.ratios,
        heights=_floats(args.heights, "--heights") if args.heights else default.heights,
        cors=tuple(cors) if cors else default.cors)


class _Progress:
    """Progress lines of ``validate calibrate`` on stderr: the stage, done/total, the time
    since the command started; at most one line every few seconds per stage (and the
    stage's last), nothing under --quiet."""

    EVERY = 5.0

    def __init__(self, quiet: bool) -> None:
        import time

        self.quiet = quiet
        self.clock = time.perf_counter
        self.start = self.clock()
        self.last = -math.inf

    def stage(self, name: str, unit: str):
        """A ``progress(done, total)`` callback for one stage."""
        def report(done: int, total: int) -> None:
            now = self.clock()
            if self.quiet or (done < total and now - self.last < self.EVERY):
                return
            self.last = now
            elapsed = int(round(now - self.start))
            print(f"validate calibrate: {name}: {done}/{total} {unit} "
                  f"({100.0 * done / max(total, 1):.0f} %), {elapsed // 60} min "
                  f"{elapsed % 60:02d} s elapsed", file=sys.stderr, flush=True)
        return report


def _calibrate(args) -> int:
    import pandas as pd

    from shaketable.core.files import prepare_output_file, write_csv, write_text
    from shaketable.validation.check import (
        bootstrap_refits,
        bootstrap_sets,
        coverage,
        cross_validate,
        out_of_fold,
    )
    from shaketable.validation.fit import BAGS
    from shaketable.validation.folder import read_folder, specimen_labels
    from shaketable.validation.workflow import (
        axis_with_unit,
        calibrate_folder,
        calibration_json,
        describe_calibration,
        format_set,
    )

    if args.bags is None:
        args.bags = BAGS
    if args.bags < 0:
        raise ValueError(f"--bags must be >= 0, got {args.bags}")
    folder = read_folder(args.folder)
    grid = _grid(args)
    out = prepare_output_file(args.out, "--out", suffixes=(".json",))
    labels = specimen_labels(folder)
    if not args.quiet:
        print(f"{len(folder.tests)} tests, specimens {', '.join(labels.values())}; "
              f"{len(grid.candidates())} candidate blocks")
    progress = _Progress(args.quiet)
    calibrations, overturned, candidates = calibrate_folder(
        folder, grid, threads=args.threads, cache=args.verdicts,
        progress=progress.stage("simulating the candidates", "runs"), bags=args.bags,
        seed=args.seed)
    pgv = folder.metadata["pgv [m/s]"].to_numpy()  # type: ignore[index]
    checks: dict = {}
    held_out = []
    for name, calibration in calibrations.items():
        outcomes = folder.outcomes(name)
        entry: dict = {}
        if args.folds:
            frame = cross_validate(overturned, outcomes, candidates, pgv, k=args.folds,
                                   repeats=args.repeats, seed=args.seed, bags=args.bags,
                                   progress=progress.stage(f"{name} cross-validation",
                                                           "folds"))
            entry["cross_validation"] = {
                model: {metric: {"mean": float(part[metric].mean()),
                                 "std": float(part[metric].std(ddof=1))}
                        for metric in ("accuracy", "log_loss", "brier")}
                for model, part in frame.groupby("model")}
            entry["cross_validation"]["folds"] = args.folds
            entry["cross_validation"]["repeats"] = args.repeats
            if args.cv_predictions:
                p = out_of_fold(overturned, outcomes, candidates, k=args.folds, seed=args.seed,
                                bags=args.bags)
                held_out.append(pd.DataFrame({"test": folder.metadata["test"],  # type: ignore[index]
                                              "specimen": name, "p_overturn": p,
                                              "predicted_overturned": (p >= 0.5).astype(int),
                                              "in_training": 0}))
        if args.bootstrap:
            # one bootstrap gives the percentile sets; an independent one checks them and
            # the profile-likelihood sets
            refits = bootstrap_refits(overturned, outcomes, candidates,
                                      resamples=args.bootstrap, seed=args.seed,
                                      progress=progress.stage(f"{name} bootstrap", "refits"))
            check = bootstrap_refits(overturned, outcomes, candidates,
                                     resamples=args.bootstrap, seed=args.seed + 1,
                                     progress=progress.stage(f"{name} bootstrap check",
                                                             "refits"))
            sets = bootstrap_sets(refits)
            entry["bootstrap"] = {"resamples": args.bootstrap, "sets": sets,
                                  "coverage_of_profile_sets": coverage(
                                      check, calibration.intervals),
                                  "coverage_of_bootstrap_sets": coverage(check, sets)}
        checks[name] = entry
        if not args.quiet:
            print(describe_calibration(calibration, labels.get(name, name)))
            for model, values in entry.get("cross_validation", {}).items():
                if isinstance(values, dict):
                    accuracy = values["accuracy"]
                    print(f"  {args.folds}-fold CV accuracy, {model}: {accuracy['mean']:.3f} "
                          f"+- {accuracy['std']:.3f} (log loss {values['log_loss']['mean']:.3f}, "
                          f"Brier {values['brier']['mean']:.3f})")
            if "bootstrap" in entry:
                boot = entry["bootstrap"]
                for axis, accepted in boot["sets"].items():
                    print(f"  95 % bootstrap set of {axis_with_unit(axis)}: "
                          f"{format_set(accepted)} (independent "
                          f"refits inside: {boot['coverage_of_bootstrap_sets'][axis]:.1%}; "
                          f"inside the profile set: "
                          f"{boot['coverage_of_profile_sets'][axis]:.1%})")
    if held_out:
        write_csv(prepare_output_file(args.cv_predictions, "--cv-predictions", (".csv",)),
                  pd.concat(held_out, ignore_index=True), index=False)
    write_text(out, calibration_json(calibrations, {"folder": str(folder.path),
                                                    "grid": {"alphas": grid.alphas,
                                                             "ratios": grid.ratios,
                                                             "heights": grid.heights,
                                                             "cors": grid.cors},
                                                    "bags": args.bags, "seed": args.seed,
                                                    "checks": checks}))
    if not args.quiet:
        print(f"wrote {out}")
    return 0


def _predict(args) -> int:
    from shaketable.core.files import prepare_output_file, write_csv
    from shaketable.validation.folder import read_folder, specimen_labels
    from shaketable.validation.workflow import (
        predict_folder,
        predict_from_geometry,
        read_calibration,
    )

    if (args.calibration is None) == (args.geometry is None):
        raise ValueError("give --calibration (a calibrated block) or --geometry (the "
                         "specimens' measured geometry), one of them")
    folder = read_folder(args.folder)
    out = prepare_output_file(args.out, "--out", suffixes=(".csv",))
    if args.geometry is not None:
        import pandas as pd

        geometry = pd.read_csv(args.geometry)
        frame = predict_from_geometry(folder, geometry, sign=args.sign, threads=args.threads)
        # no calibration: in-sample or out-of-sample does not apply; `score` reads this
        frame[MODEL_COLUMN] = SCAN_BASED
    else:
        frame = predict_folder(folder, read_calibration(args.calibration), threads=args.threads)
    write_csv(out, frame, index=False)
    if not args.quiet:
        if args.geometry is not None:
            print(f"{SCAN_BASED}: each specimen's measured geometry, Housner's COR per pivot")
        for name in frame.attrs.get("missing", []):
            print(f"specimen {name}: not in the calibration, left out")
        counts = frame.groupby("specimen")["predicted_overturned"].agg(["sum", "count"])
        labels = specimen_labels(folder)
        for name, row in counts.iterrows():
            print(f"{labels.get(name, name)}: {int(row['sum'])} of {int(row['count'])} tests "
                  "predicted to overturn")
        unknown = sorted(set(frame.loc[frame["in_training"] == -1, "specimen"]))
        if unknown:
            print(f"{', '.join(unknown)}: the calibration does not record the tests it was "
                  "fitted on (in_training -1: in-sample or not is unknown)")
        inside = frame[frame["in_training"] == 1].groupby("specimen").size()
        for name, count in inside.items():
            print(f"{name}: {count} of these tests were in the calibration's training set "
                  "(in-sample: column in_training)")
        print(f"wrote {out}")
    return 0


def _score(args) -> int:
    from shaketable.core.files import json_ready_dict, prepare_output_folder, write_csv, write_text
    from shaketable.validation.folder import read_folder, specimen_labels
    from shaketable.validation.workflow import read_predictions, score_folder

    predictions = read_predictions(args.predictions)
    folder = read_folder(args.folder)
    result = score_folder(predictions, folder)
    result["scan_based"] = _scan_based(predictions)
    labels = specimen_labels(folder)
    figures = prepare_output_folder(args.figures, "--figures") if args.figures else None
    if not args.quiet:
        for line in _score_lines(result, labels):
            print(line)
        if result["unmatched"]:
            print(f"{result['unmatched']} prediction rows have no outcome in the folder")
        print("reliability (predicted P in bins against the measured fraction):")
        print(result["reliability"].to_string(index=False, float_format=lambda x: f"{x:.3f}"))
    if args.json:
        summary = {"specimens": result["specimens"], "all": result["all"],
                   "reliability": result["reliability"].to_dict(orient="records")}
        summary.update({key: result[key] for key in ("in_sample", "out_of_sample")
                        if key in result})
        write_text(Path(args.json), json.dumps(json_ready_dict(summary), indent=2,
                                               default=str))
    if figures is not None:
        from shaketable.plots.base import save
        from shaketable.plots.validation import fragility_figure, reliability_figure

        kind = _sample_kind(result)
        pooled = ", ".join(labels.get(name, name) for name in result["specimens"])
        save(reliability_figure(result["reliability"], title=f"{kind} reliability ({pooled})".strip()),
             figures / "reliability.png")
        for key, measure, name in (("fragility_pga", "PGA [g]", "fragility_pga.png"),
                                   ("fragility_pgv_over_pga", "PGV/PGA [s]",
                                    "fragility_pgv_over_pga.png")):
            save(fragility_figure(result[key], measure, log=True,
                                  title=f"{kind} fragility against {measure.split(' [')[0]} "
                                        f"({pooled}; tests per bin marked)".strip()),
                 figures / name)
        write_csv(figures / "fragility_pga.csv", result["fragility_pga"], index=False)
        write_csv(figures / "fragility_pgv_over_pga.csv", result["fragility_pgv_over_pga"],
                  index=False)
        if not args.quiet:
            print(f"wrote the figures to {figures}")
    return 0


#: The column ``validate predict --geometry`` adds to its predictions, and its value: a
#: prediction from the scanned geometry, which no calibration was fitted for.
MODEL_COLUMN = "model"
SCAN_BASED = "scan-based prediction (no calibration)"


def _scan_based(predictions) -> bool:
    """Whether every row of a predictions frame is a scan-based (uncalibrated) prediction."""
    return bool(MODEL_COLUMN in predictions.columns and len(predictions)
                and (predictions[MODEL_COLUMN] == SCAN_BASED).all())


#: The score blocks of ``validate score``, in the order said: the fair one first.
_SAMPLES = (("out_of_sample", "out-of-sample (tests the calibration never saw)"),
            ("in_sample", "in-sample (tests the calibration was fitted on: optimistic; the "
                          "fair figure is the out-of-sample one, or the k-fold "
                          "cross-validated accuracy of `validate calibrate`)"))


def _score_lines(result: dict, labels: dict) -> list[str]:
    """The score's console lines. Rows that mix tests the calibration saw and tests it
    never saw lead with the out-of-sample score, then the in-sample one, then all rows
    pooled; rows of one kind are scored once, that kind named first."""
    def block(part: dict) -> list[str]:
        return ["  " + _score_line(labels.get(name, name), values)
                for name, values in [*part["specimens"].items(), ("all", part["all"])]]

    if result.get("scan_based"):   # no calibration: no in- or out-of-sample split
        return [f"{SCAN_BASED}; no test was used to fit it:", *block(result)]
    present = [(key, what) for key, what in _SAMPLES if key in result]
    if len(present) == 2 or (present and
                             result[present[0][0]]["all"]["n"] != result["all"]["n"]):
        lines = []
        for key, what in present:
            lines += [f"{what}:", *block(result[key])]
        return lines + ["all rows pooled (in-sample and out-of-sample together):",
                        *block(result)]
    if present:
        return [f"{present[0][1]}:", *block(result)]
    return ["scores (the predictions do not say which tests the calibration was fitted "
            "on):", *block(result)]


def _sample_kind(result: dict) -> str:
    """``"out-of-sample"``, ``"in-sample"`` or ``"mixed ..."`` (both, or either with rows of
    unknown kind), or ``"scan-based (no calibration)"``: what a score's figures show, for
    their titles ("" when unknown)."""
    if result.get("scan_based"):
        return "scan-based (no calibration)"
    kinds = [key for key, _ in _SAMPLES if key in result]
    if len(kinds) == 1 and result[kinds[0]]["all"]["n"] == result["all"]["n"]:
        return kinds[0].replace("_", "-")
    return "mixed in-/out-of-sample" if kinds else ""


def _score_line(name: str, values: dict) -> str:
    return (f"{name}: accuracy {values['accuracy']:.3f} on {values['n']} (overturned: "
            f"{values['true_positive']} right, {values['false_negative']} missed; standing: "
            f"{values['true_negative']} right, {values['false_positive']} false alarms); "
            f"log loss {values['log_loss']:.3f}, Brier {values['brier']:.3f}")


def register(commands) -> None:
    """Add the ``validate`` subcommand and its three steps."""
    parser = commands.add_parser(
        "validate", help="calibrate on, predict and score measured shake-table tests",
        description="Validation against measured shake-table tests (a folder: metadata.csv, "
                    "one motion per test, '<specimen>_overturned' outcome columns).")
    steps = parser.add_subparsers(dest="step", required=True, metavar="STEP")

    calibrate = steps.add_parser("calibrate", help="an equivalent block per specimen, by "
                                                    "maximum likelihood, with intervals")
    calibrate.add_argument("folder", help="folder of tests with outcome columns")
    calibrate.add_argument("--out", required=True, help="calibration file to write (.json)")
    calibrate.add_argument("--alphas", help="weak-side block angles in rad, comma-separated "
                                            "(default 0.04 to 0.19)")
    calibrate.add_argument("--ratios", help="alpha_strong / alpha_weak, comma-separated "
                                            "(default 1,1.5,2)")
    calibrate.add_argument("--heights", help="centroid heights in m, comma-separated "
                                             "(default 0.3)")
    calibrate.add_argument("--cors", help="CORs, comma-separated, 'housner' allowed "
                                          "(default housner,0.9,0.8)")
    calibrate.add_argument("--folds", type=int, default=5, help="cross-validation folds "
                                                                "(0: none; default 5)")
    calibrate.add_argument("--repeats", type=int, default=5,
                           help="cross-validation repetitions with other folds (default 5)")
    calibrate.add_argument("--bootstrap", type=int, default=200,
                           help="bootstrap refits checking the intervals (0: none; default 200)")
    calibrate.add_argument("--bags", type=int,
                           help="bootstrap refits of the bagged ensemble that gives the "
                                "probabilities (default 30, shaketable.validation.fit.BAGS; "
                                "0: the 24 most likely candidates weighted by their "
                                "likelihood)")
    calibrate.add_argument("--seed", type=int, default=0, help="seed of folds and bootstrap")
    calibrate.add_argument("--cv-predictions", metavar="CSV",
                           help="write the out-of-fold predictions (each test predicted by the "
                                "calibration on the other folds) for 'validate score'")
    calibrate.add_argument("--verdicts", help="cache of the simulated verdicts (.npz): reused "
                                              "when it matches the grid and the tests")
    calibrate.add_argument("--threads", type=int, help="threads of the simulations")
    calibrate.set_defaults(handler=_calibrate)

    predict = steps.add_parser("predict", help="P(overturn) and verdicts of a folder's tests")
    predict.add_argument("folder", help="folder of tests (outcome columns not needed)")
    predict.add_argument("--calibration", help="calibration file (.json)")
    predict.add_argument("--geometry", help="instead of a calibration: the specimens' geometry "
                                            "CSV (columns specimen, direction, side, b_m, h_m, "
                                            "R_m, I_O_over_mR2): the scan-based block, "
                                            "Housner's COR per pivot")
    predict.add_argument("--sign", type=int, choices=(1, -1), default=1,
                         help="with --geometry: +1 if a positive recorded acceleration tips "
                              "the block over its +x side, -1 the other way (default 1)")
    predict.add_argument("--out", required=True, help="predictions to write (.csv)")
    predict.add_argument("--threads", type=int, help="threads of the simulations")
    predict.set_defaults(handler=_predict)

    score = steps.add_parser("score", help="score predictions against a folder's outcomes")
    score.add_argument("predictions", help="predictions CSV of 'validate predict'")
    score.add_argument("folder", help="folder of tests with outcome columns")
    score.add_argument("--json", help="write the scores to this JSON file")
    score.add_argument("--figures", help="folder for the reliability and fragility figures")
    score.set_defaults(handler=_score)
    for step in (calibrate, predict, score):
        # after the step too; SUPPRESS: a step's default must not undo `validate -q STEP`
        step.add_argument("-q", "--quiet", action="store_true", default=argparse.SUPPRESS,
                          help="print nothing but errors")
