"""Rerun the report's experiments and write a Markdown report of the comparison."""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from shaketable.core.files import subfolder, write_csv, write_gallery
from shaketable.core.workers import end_workers_after, ignore_interrupts, interrupts_ignored, process_pool
from shaketable.scenes.catalog import expected_cost, resolve_scene_path, uses_planar
from shaketable.scenes.parse import Study, load_scene
from shaketable.studies.comparison import ComparisonTally

if TYPE_CHECKING:
    import pandas as pd

    from shaketable.models.rocking.result import RockingResult
    from shaketable.scenes.parse import Scene

#: What the run lines and the test-vs-theory tables time differently (Figs. 3.4-3.9).
TIMING_NOTE = ("*Times:* the run lines give the exact block's times (events located in the "
               "integration); the test-vs-theory table reads both curves from the virtual "
               "potentiometer record at 50 samples/s, so its times fall on the 0.02 s sample "
               "grid at or after the exact event (the first sample beyond α).")


#: Sections of ``reproduce --all`` beyond the scenes: name -> "module:function"; the function
#: takes the section's folder and the options the caller gives for it, and returns the
#: section's Markdown (a one-line skip when it cannot run).
EXTRA_SECTIONS = {"validation": "shaketable.validation.report:reproduce_section"}

#: The file beside a section's section.md saying that it was skipped (it could not run).
SKIPPED_MARKER = "skipped"


#: How a section carries its differing comparisons to the report's list (an HTML comment
#: per comparison, ``<!-- differs: KIND | WHAT -->``, removed from report.md).
DIFFERS_MARK = "<!-- differs: "


def run_line(run: RockingResult) -> str:
    """One run in words and units for report.md: which block, from which angle and at which
    COR, then the verdict, instability, impacts and rods."""
    if run.overturned:
        side = "+" if run.overturn_direction > 0 else "−"
        verdict = (f"**F**: overturns ({side}) at {run.t_overturn:.2f} s; largest rocking "
                   f"before instability {run.max_theta_ratio_before_instability:.3f} α")
    else:   # free rocking: when it came to rest, after the impacts a reader can count
        verdict = run.verdict()   # free rocking: when it came to rest, after how many cycles
    unstable = ("never unstable (|θ| stays below α)" if not run.unstable else
                f"unstable ({'+' if run.unstable_direction > 0 else '−'}) at "
                f"{run.t_unstable:.3g} s")
    impacts = f"{run.n_impacts} resolved impacts"
    if run.cascades:
        impacts += (f" + {run.cascades} impact cascade{'s' if run.cascades > 1 else ''} "
                    "summed in closed form (endless impacts to rest)")
    rods = ("" if run.block.rods is None else
            f"; largest rod force {run.max_rod_force:.3g} W (Section 4.4)")
    start = (f"from θ0 = {run.theta[0] / run.block.alpha:.3g} α" if run.theta[0] != 0.0
             else "from rest")
    return (f"* {run.block.describe()} block, {start}, COR {run.cor:g}: {verdict}; {unstable}; "
            f"{impacts}{rods}")


def comparison_kind(scene: Scene, quantity_key: str | None = None) -> str:
    """The kind (:data:`shaketable.studies.comparison.COMPARISON_KINDS`) of a scene's comparison.

    A quantity the scene lists in ``[report] by_construction`` matches by
    construction; any other of a scene on an artificial (substitute) motion is
    a substitute comparison; the rest compare with the report's own inputs.
    """
    if quantity_key is not None and quantity_key in scene.report.get("by_construction", ()):
        return "by construction"
    return "substitute" if scene.motion.get("kind") == "artificial" else "report inputs"


def _format(value) -> str:
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        return "—" if not math.isfinite(value) else f"{value:.3g}"
    return str(value)


def reproduce(names: Iterable[str], out: str | os.PathLike[str] = "reproduce-out", progress: bool = True,
              failures: list | None = None, compile_planar_first: bool = False,
              extra: dict | None = None) -> Path:
    """Run the named scenes; write ``out/report.md`` with figures and comparison tables.

    Each scene's outputs go to ``out/<name>/``, with its Markdown section
    (``section.md``) and its comparison counts (``counts.json``). ``report.md``
    is assembled from every section in ``out``: a run of a few scenes into a
    folder that holds a full reproduction replaces those scenes' sections and
    keeps the others (the report says which were rerun now). A scene that fails
    is reported in its section with its error and the others still run
    (nothing already computed is lost).

    Parameters
    ----------
    names : iterable of str
        Scene names (:func:`shaketable.scenes.catalog.scene_names`).
    out : path
        The output folder.
    progress : bool
        Show a progress bar (tqdm, on stderr).
    failures : list, optional
        Receives the names of the scenes that could not be reproduced.
    compile_planar_first : bool
        The planar engine is not in numba's cache yet: with scenes in two processes, one
        compiles it first (unless the first scene to start is a planar one), so that the
        two never both compile it (~15 s of CPU each).
    extra : dict, optional
        Sections of :data:`EXTRA_SECTIONS` to run after the scenes: name -> its options.

    Returns
    -------
    Path
        The Markdown report.
    """
    import json

    from shaketable.core.files import prepare_output_folder, write_text

    out = prepare_output_folder(out, "out")
    names = list(names)
    extra = extra or {}
    bar = _ProgressBar(names + list(extra)) if progress else None   # the report's sections

    def record(name, section, counts, failed):
        if failed and failures is not None:
            failures.append(name)
        folder = subfolder(out, name, "out")
        write_text(folder / "section.md", section)
        write_text(folder / "counts.json", json.dumps(counts))
        if bar is not None:
            bar.done(name)

    try:
        workers = _worker_count(len(names))
        if workers <= 1:
            for name in names:
                record(name, *_scene_outcome(name, out))
        else:
            _pooled(names, out, workers, compile_planar_first, record)
        extras = _extra_sections(out, extra, failures, bar)
    finally:
        if bar is not None:
            bar.close()
    if failures is not None:   # in the catalogue's order, whatever the order of completion
        failures.sort(key=lambda name: names.index(name) if name in names else len(names))
    return _assemble(out, rerun=names + extras)


def _pooled(names: list, out: Path, workers: int, compile_planar_first: bool, record) -> None:
    """The scenes in ``workers`` processes of their own (each a fresh interpreter, numba's
    cache loaded once per process), each outcome handed to ``record`` as it completes; a
    scene's outputs do not depend on the process it runs in."""
    from concurrent.futures import as_completed

    pool = process_pool(workers, _one_thread_each)
    try:
        # the longest expected first (the report-table studies and their ensembles: half of
        # the work), so that the processes end together; each result carries its worker's CPU
        order = sorted(names, key=expected_cost, reverse=True)
        with interrupts_ignored():   # the workers start (at submit) ignoring Ctrl-C
            if compile_planar_first and not uses_planar(order[0]) and any(map(uses_planar, order)):
                # one worker compiles the planar engine while another starts the longest
                pool.submit(_load_the_planar_engine)
            futures = {pool.submit(_pooled_outcome, name, out): name for name in order}
        WORKER_CPU.clear()
        for future in as_completed(futures):
            outcome, worker, cpu = future.result()
            WORKER_CPU[worker] = max(cpu, WORKER_CPU.get(worker, 0.0))
            record(futures[future], *outcome)
    except BaseException:  # Ctrl-C or a scene's crash: the workers end now, mid-scene
        end_workers_after(pool)   # a second Ctrl-C meanwhile: this error is still raised
        raise
    pool.shutdown(wait=True)


def _extra_sections(out: Path, extra: dict, failures: list | None,
                    bar: _ProgressBar | None = None) -> list[str]:
    """Run the sections of :data:`EXTRA_SECTIONS` named in ``extra``; their names."""
    import importlib

    from shaketable.core.files import write_text

    for name, options in extra.items():
        module, function = EXTRA_SECTIONS[name].split(":")
        folder = subfolder(out, name, "out")
        try:
            section = getattr(importlib.import_module(module), function)(folder, **options)
        except (ValueError, OSError) as error:
            section = f"## {name}\n\n**Not reproduced:** {error}\n"
            if failures is not None:
                failures.append(name)
        write_text(folder / "section.md", section)
        write_text(folder / "counts.json", "{}")
        # a section that could not run says so in its first paragraph ("Skipped: ..."):
        # the report's headline must not count it as rerun
        marker = folder / SKIPPED_MARKER
        if section.split("\n\n", 1)[-1].startswith("Skipped:"):
            write_text(marker, "skipped\n")
        elif marker.exists():
            marker.unlink()
        if bar is not None:
            bar.done(name)
    return list(extra)


class _ProgressBar:
    """A progress bar (tqdm, on stderr) that counts sections and moves by their expected cost.

    The scenes differ 50-fold in cost and the longest run first: a bar that moved one
    step per scene would estimate the time left from the slowest scenes (and the first
    compile) and say minutes for a job of seconds. This one's fraction and estimate are
    of the expected CPU done (:func:`~shaketable.scenes.catalog.expected_cost`, in hundredths of a second, at
    least 0.1 s a scene); it shows the sections done (scenes, then extra ones) as ``12/49
    sections``, the report's own count.
    """

    def __init__(self, names: list[str]) -> None:
        from tqdm import tqdm

        # whole hundredths of a second: float sums in another order than the total's
        # would end a few ulps past it (tqdm then warns that it clamps the bar)
        self.costs = {name: max(round(100 * expected_cost(name)), 10) for name in names}
        self.scenes = len(names)
        self.finished = 0
        # the scenes done in the description: tqdm puts ", " before a postfix
        self.tqdm: Any = tqdm(total=sum(self.costs[name] for name in names),  # repeats too
                              desc=f"0/{self.scenes} sections",
                              bar_format="reproducing: {percentage:3.0f}%|{bar}| {desc} "
                                         "[{elapsed}<{remaining}]")

    def done(self, name: str) -> None:
        """Count the scene ``name`` as done."""
        self.finished += 1
        self.tqdm.set_description_str(f"{self.finished}/{self.scenes} sections", refresh=False)
        self.tqdm.update(self.costs.get(name, 10))

    def close(self) -> None:
        self.tqdm.close()


#: Scenes below this count run in the calling process (starting a process costs ~1 s).
PARALLEL_SCENES = 6


def _worker_count(scenes: int) -> int:
    """Processes for ``scenes`` scenes: the cores this process may use, at most 2 per the
    brief's machine, 1 for a handful of scenes (``SHAKETABLE_REPRODUCE_WORKERS`` overrides)."""
    chosen = os.environ.get("SHAKETABLE_REPRODUCE_WORKERS")
    if chosen is not None:
        return max(1, int(chosen))
    if scenes < PARALLEL_SCENES:
        return 1
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return max(1, min(2, cores or 1))


#: CPU seconds [s] each worker process of the last parallel :func:`reproduce` had used
#: when it handed back its last scene (start-up and imports included), by process id:
#: what ``benchmarks/reproduce_time.py`` reports as the load balance.
WORKER_CPU: dict[int, float] = {}


def _one_thread_each() -> None:
    """A worker: batches on one thread (the cores are shared), Ctrl-C ignored (end_workers)."""
    from shaketable.models.rocking.batch import set_default_threads

    ignore_interrupts()
    set_default_threads(1)


def _load_the_planar_engine() -> None:
    """Compile (cold numba cache) or load the planar engine in this worker: a short run."""
    from shaketable.core.geometry import Block
    from shaketable.models.api import simulate
    from shaketable.models.sliding.result import Friction

    block = Block(height=1.0, width=0.25)
    simulate(block, None, cor=0.9, theta0=0.5 * block.alpha, friction=Friction(0.5),
             duration=0.1)


def _pooled_outcome(name: str, out: Path) -> tuple[tuple[str, dict, bool], int, float]:
    """:func:`_scene_outcome` in a worker, with the worker's id and its CPU seconds so far."""
    outcome = _scene_outcome(name, out)
    times = os.times()
    return outcome, os.getpid(), times.user + times.system


def _scene_outcome(name: str, out: Path) -> tuple[str, dict, bool]:
    """One scene's section, its comparison counts and whether it failed."""
    tally = ComparisonTally()
    try:
        section = _scene_section(name, out, tally)
    except (ValueError, OSError) as error:
        return f"## {name}\n\n**Not reproduced:** {error}\n", tally.counts, True
    # the differing comparisons, for the report's list (comments: not shown in the section)
    section += "".join(f"{DIFFERS_MARK}{kind} | {what} -->\n"
                       for kind, what in tally.differing)
    return section, tally.counts, False


def _scene_section(name: str, out: Path, tally: ComparisonTally) -> str:
    """Run one scene into ``out/<name>/``; its Markdown section (counts into ``tally``)."""
    # imported here: the process that only hands scenes to the workers never loads the
    # pipeline (the table stage's SciPy signal tools: ~1 s before the first worker starts)
    from shaketable.scenes.run import length_in, run_scene

    scene = load_scene(resolve_scene_path(name))
    if isinstance(scene, Study):
        return _study_section(scene, out, tally)
    from shaketable.scenes.stack import StackScene, stack_scene_section

    if isinstance(scene, StackScene):   # [stack]: a column of blocks
        return stack_scene_section(scene, subfolder(out, scene.name, "out"))
    result = run_scene(scene)
    result.write(subfolder(out, scene.name, "out"))
    lines = [f"## {scene.source or scene.name} — `{scene.name}`", "", scene.description, "",
             f"![{scene.name}]({scene.name}/calcomp.png)", ""]
    for index, test in enumerate(result.tests):
        label = "" if len(result.tests) == 1 else f"-{index + 1}"
        metrics = test.metrics()
        lines += [f"![test vs theory]({scene.name}/test-vs-theory{label}.png)", "",
                  "| test vs theory | value |", "|---|---|"]
        lines += [f"| {key} | {_format(value)} |" for key, value in metrics.items()]
        lines.append("")
    for run in result.runs:
        lines.append(run_line(run))
    unit = result.slip_unit   # one length unit for the section's slips
    for index, run in enumerate(result.slides):
        label = "" if len(result.slides) == 1 else f"-{index + 1}"
        mode = run.mode_choice.get('mode (Section 2.1)', 'n/a')
        lines.append(f"* sliding, μs {run.friction.static:g}, μd {run.friction.dynamic:g}: peak slip "
                     f"{length_in(run.peak_slip, unit)}, residual {length_in(run.residual_slip, unit, signed=True)}, "
                     f"{run.slip_episodes} slip episodes (Section 2.1: {mode})")
        lines.append(f"\n![sliding]({scene.name}/sliding{label}.png)\n")
    for index, run in enumerate(result.planar):
        label = "" if len(result.planar) == 1 else f"-{index + 1}"
        summary = run.summary()
        lines.append(f"* the planar block, μs {run.friction.static:g}, μd "
                     f"{run.friction.dynamic:g}, COR {run.cor:g}: {summary['verdict']}; modes "
                     f"{summary['modes visited']}; peak slip {length_in(summary['peak slip [m]'], unit)}")
        lines.append(f"\n![planar]({scene.name}/planar{label}.png)\n")
    if scene.mode() is not None:
        lines.append(f"* Section 2.1: {scene.mode()}")
    if result.tests:
        lines += ["", TIMING_NOTE]
    if result.comparisons:
        lines += ["", "| quantity | report | reproduced | unit | agrees |",
                  "|---|---|---|---|---|"]
        for line in result.comparisons:
            kind = comparison_kind(scene, line.key)
            unit = "" if line.unit in ("", "-") else f" {line.unit}"
            tally.add(kind, line.agrees, what=f"{line.quantity}: the report gives "
                      f"{_format(line.report)}, reproduced {_format(line.reproduced)}{unit}")
            mark = "yes" if line.agrees else "**no**"
            if kind == "by construction":
                mark += " (by construction)"
            lines.append(f"| {line.quantity} | {_format(line.report)} | "
                         f"{_format(line.reproduced)} | {line.unit} | {mark} |")
    if scene.report.get("note"):
        lines += ["", f"*Note:* {scene.report['note']}"]
    return "\n".join(lines) + "\n"


def _scope(order: list, rerun: list, kept: list, skipped: list) -> str:
    """The report's count of its sections: rerun now, kept from an earlier run, skipped."""
    sections_word = "section" if len(order) == 1 else "sections"
    if not kept and not skipped:
        return f"{len(order)} {sections_word}, all rerun now."
    parts = [f"{len(rerun)} rerun now" + (f" ({', '.join(rerun)})" if kept else "")]
    if kept:
        parts.append(f"{len(kept)} kept from an earlier run into this folder")
    if skipped:
        parts.append(f"{len(skipped)} skipped ({', '.join(skipped)}: "
                     f"{'its section says' if len(skipped) == 1 else 'their sections say'} "
                     "why and how to give what it needs)")
    return f"{len(order)} {sections_word}: " + ", ".join(parts) + "."


def _assemble(out: Path, rerun) -> Path:
    """``report.md`` from every scene section in ``out``, in the report's order; gallery.md."""
    import json

    from shaketable.core.files import write_text
    from shaketable.scenes.catalog import scene_names

    known = scene_names()
    present = [path.parent.name for path in out.glob("*/section.md")]
    order = [name for name in known if name in present] + sorted(
        name for name in present if name not in known)
    tally = ComparisonTally()
    sections = []
    for name in order:
        sections.append((out / name / "section.md").read_text(encoding="utf-8"))
        counts_path = out / name / "counts.json"
        if counts_path.is_file():
            for kind, (agree, differ) in json.loads(counts_path.read_text()).items():
                if kind in tally.counts:
                    tally.add_many(kind, agree, agree + differ)
    skipped = [name for name in order if (out / name / SKIPPED_MARKER).is_file()]
    rerun = [name for name in rerun if name in order and name not in skipped]
    kept = [name for name in order if name not in rerun and name not in skipped]
    scope = _scope(order, rerun, kept, skipped)
    sections, differing, contents = _contents(order, sections, tally)
    header = ["# shaketable: the report reproduced", "",
              "Aslam, Godden & Scalise, *Rocking and overturning response of rigid bodies to "
              "earthquake motions* (BLOKROC). Each section reruns one figure or table as a "
              "scene of `experiments/` and compares the values the report states with the "
              "reproduced ones (within the report's ~10 % unless the scene says otherwise).",
              "", scope, "", *"\n\n".join(tally.headline()).split("\n"), "",
              "An overturned run is the report's **F** everywhere (its peak before "
              "instability is given beside it, never (π/2)/α as a peak). Table 4.4 (sliding) "
              "is computed by the Coulomb stick-slip block, outside the rocking model "
              "(section `table-4-4`).", "", *differing, *contents]
    anchored = [f'<a id="{name}"></a>\n\n{section}' for name, section in zip(order, sections)]
    path = write_text(out / "report.md", "\n".join(header + anchored))
    write_gallery(out)
    return path


def _differing(section: str) -> tuple[str, list[tuple[str, str]]]:
    """A section without its differs-comments, and the ``(kind, what)`` they carry."""
    kept, found = [], []
    for line in section.splitlines(keepends=True):
        if line.startswith(DIFFERS_MARK) and line.rstrip().endswith("-->"):
            kind, _, what = line[len(DIFFERS_MARK):].rstrip()[:-3].strip().partition(" | ")
            found.append((kind, what))
        else:
            kept.append(line)
    return "".join(kept), found


#: Headings of the report's lists of differing comparisons, by kind.
DIFFERING_HEADINGS = {"report inputs": "against the report's own inputs",
                      "substitute": "against SUBSTITUTE accelerograms (not expected to match)",
                      "by construction": "by construction"}


def _contents(order: list[str], sections: list[str],
              tally: ComparisonTally) -> tuple[list[str], list[str], list[str]]:
    """The sections without their differs-comments, the report's lists of the comparisons
    that differ (by kind, linked to their sections) and its table of contents."""
    contents = ["## Contents", ""]
    by_kind: dict[str, list[str]] = {kind: [] for kind in DIFFERING_HEADINGS}
    cleaned = []
    for name, section in zip(order, sections):
        section, found = _differing(section)
        cleaned.append(section)
        heading = next((line[3:].strip() for line in section.splitlines()
                        if line.startswith("## ")), name)
        contents.append(f"- [{heading}](#{name})"
                        + (f" ({len(found)} differ)" if found else ""))
        for kind, what in found:
            by_kind.setdefault(kind, []).append(f"- [`{name}`](#{name}): {what}")
    lists = []
    for kind, items in by_kind.items():
        counted = tally.counts.get(kind, [0, 0])[1]
        if not counted and not items:
            continue
        things = ("comparison", "differs") if counted == 1 else ("comparisons", "differ")
        lists += [f"## The {counted} {things[0]} {DIFFERING_HEADINGS.get(kind, kind)} that "
                  f"{things[1]}", ""] + items
        if len(items) != counted:   # sections kept from a run of an earlier version
            lists.append(f"- ({counted - len(items)} more in sections written by an earlier "
                         "version, which do not list them: rerun those sections)")
        lists.append("")
    return cleaned, lists, contents + [""]


def _markdown(frame) -> str:
    columns = list(frame.columns)
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for row in frame.itertuples(index=False):
        lines.append("| " + " | ".join(_format(value) if not isinstance(value, str) else value
                                       for value in row) + " |")
    return "\n".join(lines)


def _study_section(study: Study, out: Path, tally: ComparisonTally) -> str:
    """Recompute one of the report's tables; write its CSV; return the Markdown section."""
    from shaketable.studies.report_tables import reproduce_table, table_3_1

    folder = subfolder(out, study.name, "out")
    lines = [f"## {study.source} — `{study.name}`", "", study.description, ""]
    if study.table == "table_4_4":  # the sliding mode (shaketable.studies.sliding)
        return _table_4_4_section(study, folder, lines, tally)
    if study.kind == "pitch-repeatability":
        return _repeatability_section(study, folder, lines, tally)
    if study.kind == "teaching":
        return _teaching_section(study, folder, lines)
    if study.kind == "overturning-spectrum":
        return _spectrum_section(study, folder, lines)
    if study.kind == "mode-map":
        return _mode_map_section(study, folder, lines)
    if study.kind == "stacks":   # stacks beside single blocks
        from shaketable.scenes.stack import stacks_section
        return stacks_section(folder, lines)
    if study.kind == "report-figure":
        from shaketable.plots.base import save
        from shaketable.plots.studies import section_2_figure
        from shaketable.studies import pulses, section2

        figures: dict[str, Callable[[], pd.DataFrame]] = {
            "2.3": section2.figure_2_3, "2.4": section2.figure_2_4,
            "2.5": section2.figure_2_5, "2.6": section2.figure_2_6,
            "4.3.4": pulses.section_4_3_4}
        frame = figures[study.figure]()
        write_csv(folder / "curves.csv", frame)
        save(section_2_figure(frame, study.figure), folder / "figure.png")
        lines += [f"![{study.name}]({study.name}/figure.png)", "", _markdown(frame.round(4))]
        if study.figure == "4.3.4":
            # the report's one number: 4.6 g by Eq. (2-9) for a 0.1 s pulse
            row = frame[frame["pulse duration [s]"] == 0.1].iloc[0]
            agrees = abs(row["Eq. 2-9 [g]"] / 4.6 - 1) <= 0.05
            tally.add("report inputs", agrees, what=f"Eq. 2-9, 0.1 s pulse: the report gives "
                      f"4.6 g, reproduced {row['Eq. 2-9 [g]']:.3g} g")
            lines += ["", "| quantity | report | reproduced | unit | agrees |",
                      "|---|---|---|---|---|",
                      f"| Eq. 2-9, 0.1 s pulse | 4.6 | {row['Eq. 2-9 [g]']:.3g} | g | "
                      f"{'yes' if agrees else '**no**'} |",
                      f"| engine (exact), 0.1 s pulse | — | {row['engine [g]']:.3g} | g | — |"]
        return "\n".join(lines) + "\n"
    if study.table == "table_3_1":
        from shaketable.plots.base import save
        from shaketable.plots.studies import figure_3_6

        frame = table_3_1()
        write_csv(folder / "table.csv", frame)
        save(figure_3_6(frame), folder / "figure.png")
        lines += [f"![{study.name}]({study.name}/figure.png)", ""]
        agrees = (abs(frame["test / exact [-]"] - 1) <= 0.03)
        tally.add_many("report inputs", int(agrees.sum()), len(agrees), differing=[
            f"amplitude {row['amplitude [deg]']:g} deg: test / exact period "
            f"{row['test / exact [-]']:.3f} (within 3 %: no)"
            for _, row in frame[~agrees].iterrows()])
        lines += [_markdown(frame.round(3)), "",
                  "The report's test/theory agreement is within 2–3 %; the exact nonlinear "
                  f"period agrees with the printed test periods within "
                  f"{100 * abs(frame['test / exact [-]'] - 1).max():.1f} %. The virtual test "
                  "(50 samples/s potentiometer record, period = 4 × max-to-zero, the "
                  "report's reading) agrees with the exact period within "
                  f"{100 * abs(frame['virtual / exact [-]'] - 1).max():.1f} %."]
        return "\n".join(lines) + "\n"
    comparison = reproduce_table(study.table, columns=study.columns or None, seed=study.seed)
    frame = comparison.to_frame()
    write_csv(folder / "table.csv", frame)
    counts = comparison.counts()
    for substitute, cells in frame.groupby("substitute motion"):
        tally.add_many("substitute" if substitute else "report inputs",
                       int(cells["verdict_agrees"].sum()), len(cells), differing=[
                           f"{row['height [ft]']:g} x {row['width [ft]']:g} ft, COR "
                           f"{row['cor [-]']:g}, {row['column']}: the report gives "
                           f"{row['report']}, reproduced {row['reproduced']} (F = overturns)"
                           for _, row in cells[~cells["verdict_agrees"].astype(bool)].iterrows()])
    wide = frame.assign(cell=frame["report"] + " / " + frame["reproduced"]).pivot_table(
        index=["height [ft]", "width [ft]", "cor [-]"], columns="column", values="cell",
        aggfunc="first", sort=False).reset_index()
    lines += ["Each cell: **report / reproduced** (F = overturns).", "", _markdown(wide), "",
              "| column | cells | same F / not F | both numbers | median abs. difference |",
              "|---|---|---|---|---|"]
    for column, count in counts.items():
        lines.append(f"| {column} | {count['cells']} | {count['same F / not F']} | "
                     f"{count['both numbers']} | {_format(count['median |difference|'])} |")
    pacoima = [column for column in counts if column.startswith("pacoima")]
    if pacoima:
        # the default reading of the Pacoima vertical was chosen by agreement with these
        # tables: show the agreement under the other readings too (docs/section4.md)
        from shaketable.studies.report_tables import PACOIMA_VERTICAL_READINGS

        lines += ["", "Verdicts of the Pacoima Dam columns under each reading of its vertical "
                  "(labelled DWN in the file; the default uses the values as written, "
                  "upward; see docs/section4.md):", "",
                  "| reading of the vertical | same F / not F |", "|---|---|"]
        for reading in PACOIMA_VERTICAL_READINGS:
            if reading == "up":
                agreeing = int(frame[frame["column"].isin(pacoima)]["verdict_agrees"].sum())
            else:
                other = reproduce_table(study.table, columns=pacoima,
                                        pacoima_vertical=reading).to_frame()
                agreeing = int(other["verdict_agrees"].sum())
            label = {"up": "values as written, upward (default)",
                     "down": "as labelled, downward", "none": "left out"}[reading]
            cells = int(frame["column"].isin(pacoima).sum())
            lines.append(f"| {label} | {agreeing}/{cells} |")
    from shaketable.studies.predictability import predictability_markdown

    lines += predictability_markdown(study.table, columns=study.columns or None,
                                     motion_seed=study.seed)
    return "\n".join(lines) + "\n"


def _repeatability_section(study: Study, folder: Path, lines: list, tally: ComparisonTally) -> str:
    """Section 3.7 (2): the same command on a table pitching with different phases."""
    import pandas as pd

    from shaketable.plots.base import save
    from shaketable.plots.studies import pitch_repeatability_figure
    from shaketable.scenes.studies import section_3_7_cases
    from shaketable.studies.repeatability import section_3_7_contrast

    cases = section_3_7_cases(phases=study.phases)
    save(pitch_repeatability_figure(cases), folder / "figure.png")
    write_csv(folder / "runs.csv", pd.concat([case.to_frame() for case in cases]))
    frame = pd.DataFrame([case.summary() for case in cases])
    frame["overturn directions"] = frame["overturn directions"].map(
        lambda values: ", ".join(f"{v:+d}" for v in values) or "—")
    lines += [f"![{study.name}]({study.name}/figure.png)", "", _markdown(frame), "",
              "| quantity | report | reproduced | unit | agrees |", "|---|---|---|---|---|"]
    # every case row is a comparison with the report's finding ('agrees' column); the
    # earthquake-type cases run on the SUBSTITUTE accelerogram, as do the contrast lines
    for _, row in frame.iterrows():
        kind = "substitute" if "substitute" in row["case"] else "report inputs"
        agrees = row["agrees"]
        tally.add(kind, agrees == "yes" if isinstance(agrees, str) else bool(agrees),
                  what=f"{row['case']}: the report found "
                       f"'{row.get('report (Section 3.7 (2))', '—')}', reproduced "
                       f"'{row.get('reproduced', '—')}'")
    for line in section_3_7_contrast(cases):
        tally.add("substitute", line.agrees, what=f"{line.quantity}: the report gives "
                  f"{_format(line.report)}, reproduced {_format(line.reproduced)}")
        lines.append(f"| {line.quantity} | {_format(line.report)} | {_format(line.reproduced)} "
                     f"| {line.unit} | {'yes' if line.agrees else '**no**'} |")
    return "\n".join(lines) + "\n"


def _teaching_section(study: Study, folder: Path, lines: list) -> str:
    """One item of the teaching gallery (:mod:`shaketable.studies.teaching`): figure, numbers, CSV."""
    from shaketable.plots.teaching import save_item
    from shaketable.studies.teaching import run_item

    item = run_item(study.item)
    frame = item.to_frame()
    write_csv(folder / "numbers.csv", frame)
    save_item(item, folder / "figure.png")
    return "\n".join(lines + [f"![{study.name}]({study.name}/figure.png)", ""]
                     + [f"* {line}" for line in item.highlights()]
                     + ["", _markdown(frame.round(4))]) + "\n"


def _spectrum_section(study: Study, folder: Path, lines: list) -> str:
    """An overturning spectrum: every band, its flags, the figure, and the
    published edges the scene gives beside the reproduced ones.

    The published values are the literature's, not the report's: they are shown with
    their own agreement column and not counted in the report's headline.
    """
    import math

    from shaketable.core.files import atomic_write
    from shaketable.plots.base import save
    from shaketable.studies.overturning_spectrum import overturning_spectrum

    settings = study.spectrum
    assert settings is not None   # an "overturning-spectrum" study has its settings
    result = overturning_spectrum(settings.block, pulses=settings.pulses,
                                  ratios=settings.ratios, cor=settings.cor,
                                  ceiling=settings.ceiling, scan_step=settings.scan_step,
                                  tolerance=settings.tolerance, method=settings.method)
    atomic_write(folder / "spectrum.csv", result.to_csv)
    save(result.plot().figure, folder / "spectrum.png")
    block = settings.block
    cor = ("Housner's 1 − 1.5 sin²α = " if settings.cor == "housner" else "") + f"{result.cor:.6g}"
    lines += [f"![{study.name}]({study.name}/spectrum.png)", "",
              f"Block α = {block.alpha:.6g} rad, p = {block.p:.6g} rad/s; COR {cor}. Scan: "
              f"geometric, {100 * result.scan_step:g} % relative step from a/(g tan α) = 1 "
              f"(below it the block does not rock); every edge bisected to "
              f"{result.tolerance:g} relative; {result.runs} runs of the batch engine "
              "(`shaketable.studies.overturning_spectrum`; the verdict after the pulse "
              "decided by energy). Bands (a/(g tan α)):", ""]
    frame = result.to_frame()
    shown = frame.drop(columns=["impacts"]).assign(
        flagged=frame["flagged"].map(lambda flag: "**yes**" if flag else ""),
        note=frame["note"].str.replace("|", "\\|", regex=False))   # |theta| in a table cell
    for column in ("from a/(g tan alpha) [-]", "to a/(g tan alpha) [-]"):
        shown[column] = shown[column].map(lambda x: f"{x:.7g}")
    lines.append(_markdown(shown))
    if result.flags:
        lines += ["", "**Flagged** (a window narrower than the scan may hide, or was found "
                  "only because its sides differ; the CSV's `note` says which):", ""]
        lines += [f"* {flag}" for flag in result.flags]
    lines += ["", "Minimum overturning amplitude against Housner's Eq. (2-8), the report's "
              "half-sine estimate a/(g α) = √(1 + (ω/p)²), drawn on the figure with α ≈ tan α "
              "(the slender-block reading of Section 2.4):", "",
              "| pulse | ω/p | minimum (engine) | Eq. (2-8) | bands above the minimum |",
              "|---|---|---|---|---|"]
    for pulse in settings.pulses:
        for ratio in settings.ratios:
            minimum = result.minimum(pulse, ratio)
            eq_2_8 = math.sqrt(1.0 + ratio ** 2)
            above = len(result.edges(pulse, ratio)) - 1
            lines.append(f"| {pulse} | {ratio:g} | {minimum:.7g} | {eq_2_8:.4g} | "
                         + (f"{above} more edge(s): a safe region above the minimum"
                            if above else "one transition") + " |")
    if settings.references:
        lines += ["", "Published band edges (the literature, not the report: not counted in "
                  "the report's headline):", "",
                  "| source | pulse | ω/p | published edges | reproduced edges | largest "
                  "difference | tolerance | agrees |", "|---|---|---|---|---|---|---|---|"]
        for reference in settings.references:
            found = result.edges(reference.pulse, reference.omega_over_p)
            same = len(found) == len(reference.edges)
            worst = (max(abs(a - b) for a, b in zip(found, reference.edges)) if same
                     else math.inf)
            agrees = worst <= reference.tolerance
            lines.append(
                f"| {reference.source or '—'} | {reference.pulse} | "
                f"{reference.omega_over_p:g} | {', '.join(f'{x:g}' for x in reference.edges)} "
                f"| {', '.join(f'{x:.6f}' for x in found)} | "
                + (f"{worst:.1e}" if same else f"{len(found)} edges, not {len(reference.edges)}")
                + f" | {reference.tolerance:g} | {'yes' if agrees else '**no**'} |")
    return "\n".join(lines) + "\n"


def _mode_map_section(study: Study, folder: Path, lines: list) -> str:
    """The planar block's mode map and sliding limits against Section 2.1."""
    from shaketable.ground import records
    from shaketable.plots.base import save
    from shaketable.studies.mode_map import mode_map, mode_map_markdown, sliding_limits

    settings = study.mode_map
    assert settings is not None   # a "mode-map" study has its settings
    motion = records.load(settings.record)
    result = mode_map(motion, pga_levels=settings.pga_levels,
                      aspect_ratios=settings.aspect_ratios, frictions=settings.frictions,
                      height=settings.height, cor=settings.cor)
    limits = sliding_limits(motion=motion, cor=settings.cor)
    write_csv(folder / "mode_map.csv", result.frame)
    write_csv(folder / "sliding_limits.csv", limits)
    save(result.plot(), folder / "figure.png")
    return "\n".join(lines + [f"![{study.name}]({study.name}/figure.png)", "",
                              mode_map_markdown(result, limits)]) + "\n"


def _table_4_4_section(study: Study, folder: Path, lines: list, tally: ComparisonTally) -> str:
    """Table 4.4 (Section 4.5): maximum sliding displacement, report beside reproduced."""
    from shaketable.studies.sliding import table_4_4, table_4_4_markdown

    frame = table_4_4(columns=study.columns or None, seed=study.seed)
    write_csv(folder / "table.csv", frame)
    for substitute, cells in frame.groupby("substitute motion"):
        agrees = abs(cells["ratio [-]"] - 1.0) <= 0.10
        tally.add_many("substitute" if substitute else "report inputs", int(agrees.sum()),
                       len(cells), differing=[
                           f"{row['column']}, mu_d {row['mu_d [-]']:g}: the report gives "
                           f"{row['report [in]']:g} in, reproduced {row['reproduced [in]']:.3g} "
                           f"in (within 10 %: no)" for _, row in cells[~agrees].iterrows()])
    body = table_4_4_markdown(frame).split("\n", 1)[1]  # drop its own heading
    lines += ["*Outside the rocking model:* Table 4.4 is the report's sliding mode "
              "(Section 4.5), a block that slides without rocking; it is computed here by the "
              "Coulomb stick-slip block (`shaketable.models.sliding.engine`), not by the rocking "
              "engine of the other sections. Counted in the headline: the Pacoima Dam cells "
              "against the report's inputs, the substitute columns as substitute comparisons "
              "(within ~10 %).", ""]
    from shaketable.studies.mode_map import table_4_4_coupled, table_4_4_coupled_markdown

    coupled = table_4_4_coupled()   # the planar block beside the sliding model
    write_csv(folder / "planar.csv", coupled)
    return "\n".join(lines) + body + "\n" + table_4_4_coupled_markdown(coupled) + "\n"


def run_study_tally(study: Study, out: str | os.PathLike[str]) -> tuple[Path, ComparisonTally]:
    """Run one ``[study]`` scene into folder ``out``: its CSV, figure and ``report.md``.

    What ``reproduce`` writes for the study, on its own: the files go straight into
    ``out`` (not ``out/<name>``), and ``out/report.md`` holds the study's section
    with its comparison with the report.

    Returns the report and its comparisons counted by kind (own inputs, substitutes).
    """
    import tempfile

    from shaketable.core.files import prepare_output_folder, write_text

    folder = prepare_output_folder(out, "out")
    tally = ComparisonTally()
    with tempfile.TemporaryDirectory(dir=folder, prefix=".staging-") as staging:
        section = _study_section(study, Path(staging), tally)
        for produced in sorted((Path(staging) / study.name).iterdir()):
            os.replace(produced, folder / produced.name)
    section = section.replace(f"]({study.name}/", "](")
    report = write_text(folder / "report.md", section)
    return report, tally


def run_study(study: Study, out: str | os.PathLike[str]) -> tuple[Path, tuple[int, int]]:
    """:func:`run_study_tally`, the report and its comparisons that agree and differ."""
    report, tally = run_study_tally(study, out)
    agree, differ = (sum(pair[k] for pair in tally.counts.values()) for k in (0, 1))
    return report, (agree, differ)
