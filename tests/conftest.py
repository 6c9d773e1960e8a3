"""Fixtures shared by the test folders (which mirror the package's layers).

The suite runs in one process (``pytest``) or on pytest-xdist workers (``pytest -n 2``,
what CI runs; ``--dist loadgroup`` is in pyproject.toml's ``addopts``), in the order
pytest-randomly draws (a test extra). No test needs another to have run, in its process
or before it: each builds what it reads (a module-scoped fixture computes it in whichever
process needs it). As a saving only, tests that share a module- or class-scoped fixture
are put in one ``xdist_group`` (named after their module), so that under ``--dist
loadgroup`` the fixture is computed once, on one worker; a module can also name its group
itself (``pytestmark``). Every other test goes to whichever worker is free. Each worker
reports the CPU time it used (its own and its subprocesses') at the end of the run: the
suite's wall time on a quiet machine is about the largest of them plus start-up.
"""

from __future__ import annotations

import os

import pytest

try:
    import resource
except ImportError:   # not on Windows: no CPU report there
    resource = None

from tests.helpers import REPOSITORY, SHARED_RECORDS

# One BLAS thread per test process (read when numpy loads, after this; a value set in the
# environment wins): with two xdist workers on two cores, or other work on the machine,
# a second OpenBLAS thread waits for a core someone else holds. Measured on the 2-core
# machine under load, a 400 x 400 Cholesky took 1.0 s with two threads and 3.5 ms with one
# (a test of tests/calibration/test_scatter.py took 46 s in the suite before, under 4 s after).
# The same in one process and on the workers, so that both runs compute the same numbers.
for _variable in ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")


@pytest.fixture(scope="session")
def repository():
    """The repository's root folder."""
    return REPOSITORY


@pytest.fixture
def figure_drafts():
    """The test's PNG figures are drafts (:func:`tests.helpers.draft_figures`: every figure
    built and drawn by the same code, at a low dpi without the layout solver), for tests
    that check what a command computes, prints and which files it writes, not how a figure
    looks (tests/plots checks that at full size)."""
    from tests.helpers import draft_figures

    with draft_figures():
        yield


@pytest.fixture(scope="session")
def shared_records():
    """The shared real-records folder; the test is skipped where it is absent."""
    if not (SHARED_RECORDS / "PROVENANCE.md").is_file():
        pytest.skip("the shared records folder is absent")
    return SHARED_RECORDS


_SHARED_SCOPES = ("module", "class", "package")


def _uses_a_shared_fixture(item) -> bool:
    definitions = getattr(item, "_fixtureinfo", None)
    return definitions is not None and any(
        fixturedefs[-1].scope in _SHARED_SCOPES
        for fixturedefs in definitions.name2fixturedefs.values() if fixturedefs)


@pytest.hookimpl(tryfirst=True)   # before xdist reads the groups
def pytest_collection_modifyitems(config, items):
    """Put every test of a module where some test uses a module- or class-scoped fixture
    in one xdist group named after the module (a module's own ``xdist_group`` wins)."""
    shared = {item.nodeid.split("::")[0] for item in items if _uses_a_shared_fixture(item)}
    for item in items:
        module = item.nodeid.split("::")[0]
        if module in shared and item.get_closest_marker("xdist_group") is None:
            item.add_marker(pytest.mark.xdist_group(module))


def _most_first(times: dict[str, float]) -> list[tuple[str, float]]:
    """The (test, CPU time [s]) pairs, the costliest first."""
    return sorted(times.items(), key=lambda pair: -pair[1])


def _cpu_seconds(who: int) -> float:
    usage = resource.getrusage(who)
    return usage.ru_utime + usage.ru_stime


def pytest_sessionfinish(session):
    """On an xdist worker: hand the controller the CPU time this worker used [s]."""
    workeroutput = getattr(session.config, "workeroutput", None)
    if workeroutput is not None and resource is not None:
        workeroutput["cpu_self"] = _cpu_seconds(resource.RUSAGE_SELF)
        workeroutput["cpu_children"] = _cpu_seconds(resource.RUSAGE_CHILDREN)
    if workeroutput is not None and _COMPILES:
        workeroutput["compiles"] = _COMPILES


_WORKER_CPU: dict[str, tuple[float, float]] = {}


@pytest.hookimpl(optionalhook=True)   # an xdist hook: pytest without xdist ignores it
def pytest_testnodedown(node, error):
    """On the xdist controller: keep each worker's CPU time."""
    output = getattr(node, "workeroutput", {})
    if "cpu_self" in output:
        _WORKER_CPU[node.gateway.id] = (output["cpu_self"], output["cpu_children"])
    _COMPILES.extend(tuple(row) for row in output.get("compiles", ()))


def pytest_terminal_summary(terminalreporter, config):
    seed = getattr(config.option, "randomly_seed", None)
    if config.pluginmanager.has_plugin("randomly") and isinstance(seed, int):
        # printed under -q too (pytest-randomly's own line is in the header, which -q hides)
        terminalreporter.write_line(f"tests in random order, seed {seed}: repeat the order "
                                    f"with -p randomly --randomly-seed={seed}")
    count = config.getoption("cpu_durations")
    if count and _TEST_CPU:
        terminalreporter.write_sep("=", f"{count} tests using the most CPU time")
        ranked = _most_first(_TEST_CPU)[:count]
        for nodeid, seconds in ranked:
            terminalreporter.write_line(f"{seconds:8.2f} s CPU  {nodeid}")
        terminalreporter.write_line(f"{sum(_TEST_CPU.values()):8.1f} s CPU in all "
                                    f"{len(_TEST_CPU)} tests (setup to teardown)")
        modules: dict[str, list[float]] = {}
        for nodeid, seconds in _TEST_CPU.items():
            modules.setdefault(nodeid.split("::")[0], []).append(seconds)
        terminalreporter.write_sep("=", f"{count} test files using the most CPU time")
        for module, times in sorted(modules.items(), key=lambda pair: -sum(pair[1]))[:count]:
            terminalreporter.write_line(f"{sum(times):8.2f} s CPU  {len(times):4d} tests  {module}")
        listing = os.environ.get("SHAKETABLE_CPU_LIST")
        if listing:   # every test's CPU time [s], tab-separated, for comparing two runs
            with open(listing, "w", encoding="utf-8") as handle:
                handle.writelines(f"{seconds:.4f}\t{nodeid}\n"
                                  for nodeid, seconds in _most_first(_TEST_CPU))
    _write_compiles(terminalreporter)
    for worker, (own, children) in sorted(_WORKER_CPU.items()):
        terminalreporter.write_line(f"worker {worker}: {own + children:.1f} s CPU "
                                    f"({own:.1f} s its own, {children:.1f} s in subprocesses)")
    if count and _WORKER_CPU and resource is not None:
        # the rest of the run's CPU: the controller itself, and its finished subprocesses
        # beyond what the workers reported at their session's end (the engines' warm-up,
        # each worker's exit after its report)
        workers = sum(own + children for own, children in _WORKER_CPU.values())
        terminalreporter.write_line(
            f"controller: {_cpu_seconds(resource.RUSAGE_SELF):.1f} s CPU its own, "
            f"{_cpu_seconds(resource.RUSAGE_CHILDREN) - workers:.1f} s in its subprocesses "
            f"beyond the workers' reports")


def pytest_addoption(parser, pluginmanager):
    """``--cpu-durations N``. pyproject's addopts ask for ``--dist loadgroup`` (pytest-xdist,
    the test extras); a developer without pytest-xdist (or with ``-p no:xdist``) still runs
    the suite in one process: the option is accepted and ignored then."""
    parser.addoption("--cpu-durations", type=int, default=0, metavar="N",
                     help="list the N tests that used the most CPU time (with subprocesses)")
    if not pluginmanager.has_plugin("xdist") and not pluginmanager.has_plugin("xdist.plugin"):
        parser.addoption("--dist", default="no",
                         help="pytest-xdist's distribution mode (not installed: ignored)")


# ------------------------------------------------------------ CPU time of each test
# ``--cpu-durations=N`` lists the N tests that used the most CPU time (the process's own
# and its subprocesses', setup to teardown): unlike pytest's --durations (wall time), the
# figure changes little with the machine's load. benchmarks/suite_cost.py asks for it.
_CPU_START = pytest.StashKey[float]()
_TEST_CPU: dict[str, float] = {}


def _cpu_now() -> float:
    return _cpu_seconds(resource.RUSAGE_SELF) + _cpu_seconds(resource.RUSAGE_CHILDREN)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item, nextitem):
    _CURRENT_TEST[0] = item.nodeid
    if resource is not None:
        item.stash[_CPU_START] = _cpu_now()
    yield


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    if call.when == "teardown" and resource is not None and _CPU_START in item.stash:
        outcome.get_result().user_properties.append(("cpu [s]", _cpu_now() - item.stash[_CPU_START]))


def pytest_runtest_logreport(report):
    """Keep each test's CPU time (in the one process, or on the xdist controller)."""
    if report.when == "teardown":
        for key, value in report.user_properties:
            if key == "cpu [s]":
                _TEST_CPU[report.nodeid] = value


# ------------------------------------------------ what numba compiles during the run
# ``SHAKETABLE_COMPILE_LIST=FILE`` (benchmarks/suite_cost.py --compiles FILE): every numba
# compile in the test processes (a function loaded from numba's cache is no compile), with
# the test that asked for it, its CPU time [s] (its callees' compiles included), its depth
# (0: called from Python) and its argument types; a cold run shows what the warm-up below
# leaves to the tests. The tests' own subprocesses are not listed.
_COMPILES: list[tuple] = []
_CURRENT_TEST = ["(before the first test)"]


def pytest_configure(config):
    if os.environ.get("SHAKETABLE_COMPILE_LIST"):
        import time

        from numba.core import event

        starts: list[float] = []

        class _Compiles(event.Listener):
            def on_start(self, event):
                starts.append(time.process_time())

            def on_end(self, event):
                seconds = time.process_time() - starts.pop()
                function = event.data["dispatcher"].py_func
                _COMPILES.append((round(seconds, 3), len(starts),
                                  f"{function.__module__}.{function.__qualname__}",
                                  str(event.data["args"]), _CURRENT_TEST[0]))

        event.register("numba:compile", _Compiles())


def _write_compiles(terminalreporter) -> None:
    listing = os.environ.get("SHAKETABLE_COMPILE_LIST")
    if not listing:
        return
    outermost = [row for row in _COMPILES if row[1] == 0]
    with open(listing, "w", encoding="utf-8") as handle:   # CPU [s], depth, function, types, test
        handle.writelines("\t".join(str(value) for value in row) + "\n"
                          for row in sorted(_COMPILES, key=lambda row: -row[0]))
    terminalreporter.write_line(f"numba compiles in the tests: {len(outermost)} called from "
                                f"Python, {sum(row[0] for row in outermost):.1f} s CPU "
                                f"(listed in {listing})")


# ------------------------------------------------- one compile for the whole run
_WARM_UP = r"""
import numpy as np
import shaketable as st
from shaketable.ground.generators import harmonic
from shaketable.models.rocking.batch import simulate_many
from shaketable.models.sliding.engine import slide

block = st.Block.parse("30x6in")
motion = harmonic(2.0, horizontal=0.5 * st.G, duration=0.5)
for method in ("fast", "predictor-corrector", "linear"):
    st.simulate(block, motion, cor=0.9, method=method)
simulate_many([block], [motion], [0.9], threads=1)
st.simulate(block, motion, cor=0.9, friction=st.Friction(0.3, 0.25))
slide(motion, 0.3)
from shaketable.models.stack import Stack, simulate_stack
simulate_stack(Stack((block, block)), motion)
# the entries the suite compiles besides (each in one test or a few, on either worker)
for method in ("predictor-corrector", "linear"):
    simulate_many([block], [motion], [0.9], threads=1, method=method)
from shaketable.models.rocking.asymmetric import simulate_many_asymmetric
simulate_many_asymmetric([st.AsymmetricBlock.from_angles(0.15, 0.35, 0.5)], [motion],
                         np.array([[0, 0]]), [0.9], threads=1)
from shaketable.models.stack.batch import simulate_many as simulate_stacks
simulate_stacks([Stack((block, block))], [motion], threads=1)
"""


def pytest_sessionstart(session):
    """On the pytest-xdist controller, before the workers start: compile the engines into
    numba's cache (or load them), so that the workers and the tests' subprocesses load them
    instead of each compiling its own copy at the same time on a fresh machine. About 60 s
    of CPU, most of a cold run's extra cost (measured on 2 shared cores: the stack engine
    ~37 s, the planar engine ~14 s, the three rocking integrators ~7 s, the rest ~6 s;
    ``benchmarks/suite_cost.py --cold --compiles FILE`` lists what the tests still compile).
    A saving only: any test compiles what it misses. ``import shaketable`` in a subprocess
    names the cache folder the workers use."""
    config = session.config
    if getattr(config, "workerinput", None) is not None or config.option.collectonly:
        return
    if not getattr(config.option, "numprocesses", None):
        return   # one process: it compiles what it uses, once
    sources = getattr(pytest.Config, "ArgsSource", None)
    if sources is not None and getattr(config, "args_source", None) != sources.TESTPATHS:
        return   # a few files named on the command line: compile only what they use
    if _engines_cached():
        return   # the workers load them: a warm-up would only load them too (1.7 s of CPU)
    import subprocess
    import sys

    subprocess.run([sys.executable, "-c", _WARM_UP], cwd=REPOSITORY, check=False,
                   env=dict(os.environ, MPLBACKEND="Agg"), capture_output=True)


def _engines_cached() -> bool:
    """Whether numba's cache folder (the one ``import shaketable`` names) holds the
    package's compiled functions for today's sources: an index (``.nbi``) for every module
    that asks numba to cache (``cache=True``), each stamped with its module's SHA-256 (the
    freshness stamp numba 0.68 writes and checks; an index of other sources, or of an
    older numba's stamp, means a warm-up). numba checks each function itself when it loads
    it: this only decides whether the warm-up is worth its CPU."""
    import hashlib
    from pathlib import Path

    import shaketable  # light: no numba; sets NUMBA_CACHE_DIR unless the user did
    from shaketable.core.numba_cache import cache_subpath

    root = os.environ.get("NUMBA_CACHE_DIR")
    if not root or not os.path.isdir(root):
        return False
    for folder in {source.parent for source in Path(shaketable.__file__).parent.rglob("*.py")}:
        cached = Path(root, cache_subpath(str(folder)))
        for source in folder.glob("*.py"):
            indexes = list(cached.glob(f"{source.stem}.*.nbi")) if cached.is_dir() else []
            if not indexes and "cache=True" in source.read_text(encoding="utf-8"):
                return False
            digest = hashlib.sha256(source.read_bytes()).digest() if indexes else b""
            if any(digest not in index.read_bytes() for index in indexes):
                return False
    return True


# ------------------------------------------------------- garbage collection of a big heap
def pytest_collection_finish(session):
    """Once the tests are collected (numba, pandas, matplotlib, SciPy and the package
    imported), one garbage collection, then every object left is frozen (``gc.freeze``):
    the automatic full collections during the run then skip those long-lived objects
    instead of scanning them all again each time (about 0.15 s of CPU each). The garbage
    the tests make is collected as usual: only objects alive at this point are frozen
    (and stay uncollected: the modules and libraries a test session keeps anyway)."""
    import gc

    gc.collect()
    gc.freeze()


# ------------------------------------------------------------------ a quick exit
@pytest.hookimpl(trylast=True)
def pytest_unconfigure(config):
    """After the run (its reports written): one garbage collection, then every object
    left is frozen (``gc.freeze``), so that the collections that follow skip them. pytest
    collects five times at its clean-up (to find exceptions raised in objects' finalizers
    by then), and the interpreter again as it exits, each a full pass over a heap that
    holds numba, pandas and matplotlib: about 1-2 s of CPU per process, per xdist worker.
    The one collection here still runs every finalizer of the garbage the tests left, and
    pytest reports what they raise; objects only a later pass would free are left to the exit."""
    import gc

    gc.collect()
    gc.freeze()
