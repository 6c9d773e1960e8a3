"""Fixtures shared by the test folders (which mirror the package's layers).

The suite runs in one process (``pytest``) or on pytest-xdist workers (``pytest -n 2``,
what CI runs; ``--dist loadgroup`` is in pyproject.toml's ``addopts``). Tests that share a
module- or class-scoped fixture are put in one ``xdist_group`` (named after their module),
so that the fixture is computed once, on one worker, and the tests run in their file's
order (``tests/test_readme.py`` runs the README's commands one after another in one
folder); a module can also name its group itself (``pytestmark``). Every other test goes
to whichever worker is free. Each worker reports the CPU time it used (its own and its
subprocesses') at the end of the run: the suite's wall time on a quiet machine is about
the largest of them plus start-up.
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


def _cpu_seconds(who: int) -> float:
    usage = resource.getrusage(who)
    return usage.ru_utime + usage.ru_stime


def pytest_sessionfinish(session):
    """On an xdist worker: hand the controller the CPU time this worker used [s]."""
    workeroutput = getattr(session.config, "workeroutput", None)
    if workeroutput is not None and resource is not None:
        workeroutput["cpu_self"] = _cpu_seconds(resource.RUSAGE_SELF)
        workeroutput["cpu_children"] = _cpu_seconds(resource.RUSAGE_CHILDREN)


_WORKER_CPU: dict[str, tuple[float, float]] = {}


@pytest.hookimpl(optionalhook=True)   # an xdist hook: pytest without xdist ignores it
def pytest_testnodedown(node, error):
    """On the xdist controller: keep each worker's CPU time."""
    output = getattr(node, "workeroutput", {})
    if "cpu_self" in output:
        _WORKER_CPU[node.gateway.id] = (output["cpu_self"], output["cpu_children"])


def pytest_terminal_summary(terminalreporter):
    for worker, (own, children) in sorted(_WORKER_CPU.items()):
        terminalreporter.write_line(f"worker {worker}: {own + children:.1f} s CPU "
                                    f"({own:.1f} s its own, {children:.1f} s in subprocesses)")


def pytest_addoption(parser, pluginmanager):
    """pyproject's addopts ask for ``--dist loadgroup`` (pytest-xdist, the test extras); a
    developer without pytest-xdist (or with ``-p no:xdist``) still runs the suite in one
    process: the option is accepted and ignored then."""
    if not pluginmanager.has_plugin("xdist") and not pluginmanager.has_plugin("xdist.plugin"):
        parser.addoption("--dist", default="no",
                         help="pytest-xdist's distribution mode (not installed: ignored)")
