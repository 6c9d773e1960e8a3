"""COR calibration on lab-like records from an INDEPENDENT generator.

The records of ``benchmarks/calibration_coverage.py`` come from the package's own engine
and sensors, so they obey the calibration's model exactly. Here they come from
``tests/calibration/lab_records.py``, which uses nothing of ``shaketable``: SciPy's
``solve_ivp`` (DOP853, rtol 1e-11) of the rocking equation of the 30 x 6 in block with an
event at each impact, theta' multiplied at each impact by that impact's COR, the exact top
displacement through a 4-pole 20 Hz *analog* Butterworth filter (``scipy.signal.lsim``),
sampled at 50 samples/s at a random phase, 0.005 in noise, a random offset (+-0.3 in)
and a 12-bit ADC over +-15 in; released from [0.3, 0.7] alpha at an unknown time;
10 s records. The scenarios:

* ``constant``: one COR (0.85 and 0.925) for every impact -- the model holds;
* ``scatter sigma``: each impact's COR drawn from N(0.90, sigma^2), sigma 0.01, 0.02, 0.03
  (a real block's edges);
* ``velocity``: COR = 0.90 - 0.1 s/rad x (|theta'| - 0.4 rad/s) at each impact.

Each record is calibrated with the default ``calibrate(record, block)``. Reported per
scenario: coverage of the truth (the block's mean COR, i.e. the mean of the distribution
the impacts are drawn from) by the least-squares interval, by the peak method's constant
interval and by the random-effects mean's interval; coverage of the true sigma by the
scatter's interval; how often each warning fires; the period fit's error in R.

Run: ``python3 benchmarks/calibration_scatter.py [--records 50] [--workers 1]`` (the
default, 375 records, runs in about 10 minutes on one core). Writes its section of
benchmarks/CALIBRATION.md (between the markers, the rest of the file kept) and prints
the table; ``--save-rows FILE`` / ``--load-rows FILE`` keep or reuse the per-record rows.
"""

from __future__ import annotations

import argparse
import json
import math
import multiprocessing
import platform
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import shaketable as st  # noqa: E402
from shaketable.calibration.diagnostics import KINDS  # noqa: E402
from shaketable.calibration.fit import calibrate  # noqa: E402
from shaketable.calibration.record import FreeRockingRecord  # noqa: E402
from tests.calibration.lab_records import lab_record  # noqa: E402

BLOCK = st.Block.parse("30x6in")
#: name -> (options of lab_record, true mean COR, true sigma, share of the records)
SCENARIOS = {
    "constant 0.85": (dict(cor=0.85), 0.85, 0.0, 1.0),
    "constant 0.925": (dict(cor=0.925), 0.925, 0.0, 1.0),
    "scatter 0.01": (dict(cor=0.90, sigma=0.01), 0.90, 0.01, 1.5),
    "scatter 0.02": (dict(cor=0.90, sigma=0.02), 0.90, 0.02, 1.5),
    "scatter 0.03": (dict(cor=0.90, sigma=0.03), 0.90, 0.03, 1.5),
    "velocity -0.1 s/rad": (dict(cor=0.90, velocity_slope=-0.1), math.nan, math.nan, 1.0),
}
BEGIN, END = "<!-- BEGIN benchmarks/calibration_scatter.py -->", \
    "<!-- END benchmarks/calibration_scatter.py -->"


def job(args):
    name, seed = args
    options, mean, sigma, _ = SCENARIOS[name]
    started = time.perf_counter()
    lab = lab_record(20_000 + seed, **options)
    record = FreeRockingRecord.from_top_displacement(lab.t, lab.displacement_in, units="in",
                                                     name=f"{name} {seed}")
    generated = time.perf_counter()
    try:
        result = calibrate(record, BLOCK)
    except Exception as error:          # counted, not hidden
        return dict(scenario=name, seed=seed, failed=f"{type(error).__name__}: {error}")
    row = dict(scenario=name, seed=seed, mean=mean, sigma=sigma, failed="",
               drawn_mean=float(np.mean(lab.cors[:12])),
               ls=result.cor, ls_low=result.cor_interval[0], ls_high=result.cor_interval[1],
               cutoff=result.filter_cutoff, order=result.filter_order,
               lag1=result.goodness["residual_lag1_autocorrelation"],
               kinds=list(result.warning_kinds),
               generate_seconds=generated - started,
               fit_seconds=time.perf_counter() - generated)
    if result.peaks is not None:
        row.update(peak=result.peaks.cor, peak_low=result.peaks.cor_interval[0],
                   peak_high=result.peaks.cor_interval[1], slope_z=result.peaks.slope_z)
    if result.scatter is not None:
        s = result.scatter
        row.update(re=s.mean, re_low=s.mean_interval[0], re_high=s.mean_interval[1],
                   re_se=s.mean_se, re_sigma=s.sigma, sigma_low=s.sigma_interval[0],
                   sigma_high=s.sigma_interval[1], impacts=s.impacts,
                   methods_z=(result.cor - s.mean) / math.hypot(result.cor_se, s.mean_se))
    if result.periods is not None:
        row.update(R_error=result.periods.R / BLOCK.R - 1.0,
                   R_z=result.periods.nominal_discrepancy())
    if result.periods_alpha_held is not None:
        row.update(R_held_error=result.periods_alpha_held.R / BLOCK.R - 1.0,
                   R_held_z=result.periods_alpha_held.nominal_discrepancy())
    return row


def run(records, workers):
    jobs = [(name, seed) for name, (*_, share) in SCENARIOS.items()
            for seed in range(int(round(records * share)))]
    rows, started = [], time.perf_counter()
    if workers == 1:
        results = map(job, jobs)
    else:
        pool = multiprocessing.Pool(workers)
        results = pool.imap_unordered(job, jobs, chunksize=2)
    for done, row in enumerate(results, start=1):
        rows.append(row)
        if done % 50 == 0 or done == len(jobs):
            print(f"{done}/{len(jobs)} records, {time.perf_counter() - started:.0f} s", flush=True)
    if workers != 1:
        pool.close()
    return rows


def _covered(rows, low, high, truth):
    values = [r[low] <= r[truth] <= r[high] for r in rows if low in r and math.isfinite(r[truth])]
    return (f"{100 * np.mean(values):.0f} % ({sum(values)}/{len(values)})" if values else "-")


def table(rows):
    head = ("| scenario | records | least-squares interval covers the mean | peak method (constant) "
            "covers | **random-effects mean covers** | mean half-width (RE) | sigma interval "
            "covers sigma | median sigma (true) | " + " | ".join(f"warns: {k}" for k in KINDS)
            + " | any warning |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for name, (_, mean, sigma, _) in SCENARIOS.items():
        chosen = [r for r in rows if r["scenario"] == name and not r["failed"]]
        failed = sum(1 for r in rows if r["scenario"] == name and r["failed"])
        if not chosen:
            continue
        warn = [f"{100 * np.mean([k in r['kinds'] for r in chosen]):.0f} %" for k in KINDS]
        anyone = f"{100 * np.mean([bool(r['kinds']) for r in chosen]):.0f} %"
        half = np.mean([(r["re_high"] - r["re_low"]) / 2 for r in chosen if "re" in r])
        sigmas = [r["re_sigma"] for r in chosen if "re" in r]
        lines.append(
            f"| {name} | {len(chosen)}{f' ({failed} failed)' if failed else ''} | "
            f"{_covered(chosen, 'ls_low', 'ls_high', 'mean')} | "
            f"{_covered(chosen, 'peak_low', 'peak_high', 'mean')} | "
            f"**{_covered(chosen, 're_low', 're_high', 'mean')}** | {half:.4f} | "
            f"{_covered(chosen, 'sigma_low', 'sigma_high', 'sigma') if sigma == sigma else '-'} | "
            f"{np.median(sigmas):.4f} ({sigma if sigma == sigma else '-'}) | "
            + " | ".join(warn) + f" | {anyone} |")
    return "\n".join(lines)


def findings(rows):
    ok = [r for r in rows if not r["failed"]]
    constant = [r for r in ok if r["scenario"].startswith("constant")]
    lines = []
    errors = np.array([r["R_error"] for r in constant if "R_error" in r])
    zs = np.array([r["R_z"] for r in constant if "R_z" in r])
    lines.append(f"Period fit on the {errors.size} constant-COR records: R error median "
                 f"{100 * np.median(errors):+.1f} %, 90 % within +-"
                 f"{100 * np.percentile(np.abs(errors), 90):.1f} %, largest "
                 f"{100 * np.max(np.abs(errors)):.1f} %; |error|/se above 2.5 in "
                 f"{np.count_nonzero(np.abs(zs) > 2.5)} of {zs.size}.")
    held = np.array([r["R_held_error"] for r in constant if "R_held_error" in r])
    held_z = np.array([r["R_held_z"] for r in constant if "R_held_z" in r])
    lines.append(f"The same with alpha held at the nominal block's: R error median "
                 f"{100 * np.median(held):+.2f} %, 90 % within +-"
                 f"{100 * np.percentile(np.abs(held), 90):.2f} %, largest "
                 f"{100 * np.max(np.abs(held)):.2f} %; |error|/se above 3 in "
                 f"{np.count_nonzero(np.abs(held_z) > 3)} of {held_z.size}.")
    all_errors = np.array([r["R_error"] for r in ok if "R_error" in r])
    lines.append(f"Over all {all_errors.size} records (alpha free): 90 % of the R errors "
                 f"within +-{100 * np.percentile(np.abs(all_errors), 90):.1f} %.")
    for kind, key, limit in (("methods", "methods_z", 2.58), ("velocity", "slope_z", 2.58)):
        values = np.array([abs(r[key]) for r in constant if key in r])
        lines.append(f"Constant-COR records, |{key}| (the `{kind}` check, limit {limit}): "
                     f"median {np.median(values):.2f}, largest {np.max(values):.2f}.")
    lag = {name: np.median([r["lag1"] for r in ok if r["scenario"] == name])
           for name in SCENARIOS}
    lines.append("Median lag-1 autocorrelation of the residuals: " + ", ".join(
        f"{name} {value:.2f}" for name, value in lag.items()) + ".")
    cut = {name: np.median([r["cutoff"] for r in ok if r["scenario"] == name])
           for name in SCENARIOS}
    lines.append("Median fitted anti-alias cutoff [Hz] (true 20 Hz): " + ", ".join(
        f"{name} {value:.1f}" for name, value in cut.items()) + ".")
    failed = [r for r in rows if r["failed"]]
    lines.append(f"Records that could not be calibrated: {len(failed)}"
                 + (f" ({failed[0]['failed']})" if failed else "") + ".")
    seconds = np.mean([r["fit_seconds"] for r in ok])
    generate = np.mean([r["generate_seconds"] for r in ok])
    lines.append(f"One calibration takes {seconds:.2f} s on average, one record's generation "
                 f"{generate:.2f} s.")
    return lines


def write_section(text):
    path = ROOT / "benchmarks" / "CALIBRATION.md"
    current = path.read_text() if path.exists() else ""
    section = f"{BEGIN}\n{text}\n{END}"
    if BEGIN in current and END in current:
        current = current[:current.index(BEGIN)] + section + current[current.index(END) + len(END):]
    else:
        current = current.rstrip("\n") + "\n\n" + section + "\n"
    path.write_text(current)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", type=int, default=50,
                        help="records per constant scenario (1.5 x for the scatter ones)")
    parser.add_argument("--workers", type=int, default=1)
    parser.add_argument("--save-rows")
    parser.add_argument("--load-rows")
    args = parser.parse_args(argv)
    started = time.perf_counter()
    if args.load_rows:
        saved = json.loads(Path(args.load_rows).read_text())
        rows, elapsed = saved["rows"], saved["seconds"]
    else:
        rows = run(args.records, args.workers)
        elapsed = time.perf_counter() - started
    if args.save_rows:
        Path(args.save_rows).write_text(json.dumps({"seconds": elapsed, "rows": rows},
                                                   default=float))
    main_table = table(rows)
    listed = "\n".join(f"* {line}" for line in findings(rows))
    text = f"""## Lab-like records from an independent generator

Made by `python3 benchmarks/calibration_scatter.py --records {args.records} --workers \
{args.workers}` (Python {platform.python_version()}, numpy {np.__version__}; {len(rows)} \
records, {elapsed:.0f} s on {args.workers} worker process(es) on this machine).

Records from `tests/calibration/lab_records.py` (nothing of the package: SciPy `solve_ivp`
of the rocking equation with an event per impact, 30 x 6 in block, 4-pole 20 Hz analog
anti-alias filter by `scipy.signal.lsim`, 50 samples/s at a random phase, 0.005 in noise, a
random offset, 12-bit ADC), calibrated by the default `calibrate(record, block)`. The truth
for the coverage is the block's mean COR (the mean of the distribution each impact's COR is
drawn from); "RE" is the random-effects model of the per-impact CORs
(`Calibration.scatter`). Binomial +-2 sd of a 95 % coverage: +-6 % at 50 records, +-5 % at 75. A warning
column gives the share of records on which that warning fired
(`shaketable.calibration.diagnostics`).

{main_table}

{listed}
"""
    write_section(text)
    print(main_table)
    print(listed)
    return 0


if __name__ == "__main__":
    sys.exit(main())
