"""Work-precision of the coupled planar model, as ``shaketable bench`` measures it.

The study is :mod:`shaketable.studies.planar_work_precision` (``shaketable bench`` draws it
beside the rocking methods); this script runs it at the full settings and prints the
Markdown tables:

* the coupled cases (``planar_cases``: the 30 x 6 in block, mu_s 0.25, mu_d 0.22, COR 0.9,
  3 Hz 0.6 g ramped, 3 s sampled every 0.05 s; the 16 x 4 ft block, mu 0.3, COR 0.95, under
  Pacoima Dam S16E + vertical), the compiled engine (``planar``) and the SciPy reference
  (``planar-reference``) at several rtol, each against the planar reference at rtol 1e-13,
  and on the first 1.2 s and 3.5 s of the two the Moreau-Jean time stepping
  (``moreau-jean``) at h = 1e-3, 2.5e-4, 6.25e-5 s against the planar reference with ``cor="housner"``;
* the rocking limit (``free-rocking``: Fig. 3.4's free rocking of the 30 x 6 in block with
  mu_s = mu_d = 10) against the rocking ``reference`` at rtol 2.5e-14.

Run: ``python benchmarks/planar_work_precision.py [--figure docs/figures/planar_work_precision.png]``
(about a minute on one core); ``--figure`` also draws the three panels as ``shaketable bench``
does (the free-rocking panel with the rocking methods too), the figure of docs/planar.md. With 5 ms
samples one DOP853 step per sample is exact to rounding at any rtol, which says nothing:
the first coupled case is sampled every 0.05 s so that the tolerance sets the steps; on
Pacoima Dam (10 ms samples) both solvers are at rounding at every rtol.

Measured on this machine (2 shared cores; medians of 5 engine runs and of 2 reference runs,
where the study now runs the reference once; 53 s in all), the coupled case ``slide-rock-3hz``:

| method | rtol | run time [s] | error max theta [-] | error events [-] | error peak slip [-] |
|---|---|---|---|---|---|
| planar | 1e-6 ... 1e-10 | 0.0015-0.0017 | 5.0e-11 | 7.8e-12 | 2.0e-10 |
| planar | 1e-12 | 0.0057 | 3.9e-11 | 2.7e-12 | 2.2e-11 |
| planar | 1e-13 | 0.0057 | 4.0e-13 | 3.6e-13 | 3.3e-12 |
| planar-reference | 1e-8 | 0.22 | 2.7e-9 | 2.0e-10 | 1.6e-9 |
| planar-reference | 1e-12 | 0.28 | 1.2e-11 | 9.1e-13 | 1.7e-11 |

All 36 events (mode changes and impacts) in the same order at every setting. On Pacoima
(44 events, overturn at 9.98 s) every setting of both is within 5e-12 (engine 0.008 s,
reference 0.9-1.4 s per run). In the rocking limit (free rocking, 218 impacts) the engine is
within 2e-13 of the rocking truth at every rtol (0.018 s per run); the reference at rtol 1e-6
and 1e-8 ends the cascade early (146 and 205 impacts), from 1e-10 on all 218 (2.5-3.7 s).
"""

from __future__ import annotations

import argparse

import pandas as pd

from shaketable.studies import benchmark_cases, planar_work_precision, work_precision

COLUMNS = ["case", "method", "setting", "time [s]", "error max_theta [-]",
           "error events [-]", "error peak slip [-]", "events", "events truth", "same events"]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--figure", help="also write the work-precision panels here (PNG)")
    args = parser.parse_args(argv)
    coupled = planar_work_precision.planar_work_precision(
        repeats=5, progress=print, moreau=planar_work_precision.MOREAU_STEPS)
    print()
    print(work_precision.markdown_table(coupled, COLUMNS))
    case = benchmark_cases.benchmark_cases(names=[planar_work_precision.ROCKING_LIMIT_CASE])[0]
    cache: dict = {}
    rows = planar_work_precision.rocking_limit_rows(case, work_precision.truth_run(case, cache),
                                                    repeats=5)
    print()
    print(work_precision.markdown_table(pd.DataFrame(rows), [
        "case", "method", "setting", "time [s]", "error max_theta [-]", "error events [-]",
        "impacts", "impacts truth", "same verdict"]))
    if args.figure:
        from shaketable.plots.bench import save_work_precision_figure

        rocking = work_precision.work_precision([case], repeats=5, cache=cache)
        frame = pd.concat([rocking, pd.DataFrame(rows)], ignore_index=True)
        save_work_precision_figure(frame, args.figure, planar=coupled)
        print(f"wrote {args.figure}")


if __name__ == "__main__":
    main()
