"""The package's architecture, enforced (the rules of docs/architecture.md).

Each folder of ``shaketable/`` is a layer; a module may import its own layer and
the layers below it, never above. The one exception is a ``.plot()``
convenience: a function body may import :mod:`shaketable.plots` (a thin
delegate, loaded only when a figure is asked for). Third-party libraries with
one home: matplotlib only in ``plots/``, obspy only in ``ground/readers/``,
the TOML reader only in ``core/tomlfile.py`` (read by ``scenes/`` and ``sweeps/``), numba
only in ``models`` and ``numerics`` (and ``core/numba_cache.py``, its cache locator), Panel
and Bokeh only in ``classroom/page.py`` (the classroom's model is plain functions). No
module imports another module's private (``_``) names. No module imports itself through
others (no import cycle), except through the listed ``.plot()`` and ObsPy delegates. The
scene parser knows no study and no pipeline module. The benchmark harness does
not drive the CLI module.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from tests.helpers import REPOSITORY

#: Layer of each top-level folder or module of the package: a module may import
#: from a layer of lower rank, or from its own folder.
#: ``numerics`` (integrator code the models' engines share) sits between ``core`` and the
#: models; ``solvers`` holds only the deprecated old paths of the moved modules (``_moved``).
RANK = {"_moved": -1, "core": 0, "numerics": 0.5, "solvers": 1, "ground": 1, "models": 1,
        "lab": 2, "calibration": 3, "sweeps": 3, "validation": 3, "studies": 4, "scenes": 5, "plots": 6, "reproduce": 7,
        "bench": 7, "assessment": 7, "classroom": 7, "commands": 8, "cli": 9,
        "__init__": 10, "__main__": 10, "simulate": 10, "version": 0}

#: Third-party modules and the layers allowed to import them.
#: Lazy (function-level) imports allowed upward besides the plots delegates: the ObsPy
#: conversions of :class:`Motion` (``Motion.from_stream``/``to_stream``) are thin delegates
#: to the reader layer, which is the only one that may import ObsPy.
DELEGATES = {("core/motion.py", "shaketable.ground.readers.waveform"),
             # simulate() hands another model's input (a Stack), or a model named by
             # model=, to that model (the registry imports the models; a model's run is
             # simulate's own branch for the rocking and planar models)
             ("models/api.py", "shaketable.models.registry")}

#: The lazy imports allowed to close an import cycle: ``.plot()`` delegates of a result or
#: study to the figure module that draws it (and that imports the result's own module
#: back), and the ObsPy delegates above. Any other cycle, through module-level or
#: function-level imports, fails :func:`test_no_module_imports_itself_through_others`.
CYCLE_DELEGATES = DELEGATES | {
    ("models/planar/result.py", "shaketable.plots.planar"),
    ("models/planar/reference_result.py", "shaketable.plots.planar"),
    ("studies/mode_map.py", "shaketable.plots.mode_map"),
    ("sweeps/fragility.py", "shaketable.plots.sweeps"),
}

#: The house's sizes: no module longer than this many lines, no function (from its ``def``
#: to its last line, docstring included) longer than that.
MAX_MODULE_LINES = 800
MAX_FUNCTION_LINES = 150
#: Modules and functions allowed past those sizes, by exact name (none today): an entry
#: that drops back under the limit fails :func:`test_every_size_allowance_is_still_needed`.
SIZE_ALLOWANCES: set[str] = set()

TOML_HOMES = ("core/tomlfile.py", "scenes", "sweeps")
HOMES = {"matplotlib": ("plots",), "obspy": ("ground/readers",), "tomllib": TOML_HOMES,
         "tomli": TOML_HOMES, "numba": ("core/numba_cache.py", "models", "numerics"),
         "panel": ("classroom/page.py",), "bokeh": ("classroom/page.py",), "selenium": ()}


def _layer(relative: Path) -> str:
    return relative.parts[0] if len(relative.parts) > 1 else relative.stem


def _type_checking_imports(tree: ast.Module) -> set[int]:
    """Ids of the import statements inside ``if TYPE_CHECKING:`` blocks (never executed)."""
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and (
                (isinstance(node.test, ast.Name) and node.test.id == "TYPE_CHECKING")
                or (isinstance(node.test, ast.Attribute) and node.test.attr == "TYPE_CHECKING")):
            found.update(id(inner) for statement in node.body for inner in ast.walk(statement)
                         if isinstance(inner, (ast.Import, ast.ImportFrom)))
    return found


def _imports(tree: ast.Module):
    """(imported module, names, whether inside a function, whether for type checking only)
    for each import statement."""
    module_level = {id(node) for node in tree.body}
    type_only = _type_checking_imports(tree)
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name, [], id(node) not in module_level, id(node) in type_only
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            yield (node.module, [a.name for a in node.names], id(node) not in module_level,
                   id(node) in type_only)


def facts(text: str) -> tuple[list, list]:
    """What the checks read of a module's text: its import statements (as :func:`_imports`
    gives them) and each function's (name, length in lines, from its ``def`` to its last
    line; methods and nested functions included)."""
    tree = ast.parse(text)
    functions = [(node.name, node.end_lineno - node.lineno + 1) for node in ast.walk(tree)
                 if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))]
    return list(_imports(tree)), functions


def violations(package: Path, read=facts) -> list[str]:
    """Every breach of the rules above in the package folder ``package`` (each module's
    text read by ``read``: :func:`facts`, or the memo of it of this file's tests)."""
    found = []
    for path in sorted(package.rglob("*.py")):
        relative = path.relative_to(package)
        layer = _layer(relative)
        own = ".".join((package.name,) + relative.with_suffix("").parts)
        imports, _ = read(path.read_text(encoding="utf-8"))
        for module, names, lazy, type_only in imports:
            top = module.split(".")[0]
            # a type-only import (``if TYPE_CHECKING:``, e.g. matplotlib's Figure for a
            # .plot() return type) never runs: the third-party homes do not apply to it
            if top in HOMES and not type_only \
                    and not any(str(relative).startswith(home) for home in HOMES[top]):
                found.append(f"{relative}: imports {module} (allowed only in {HOMES[top]})")
            if top != package.name:
                continue
            parts = module.split(".")
            if len(parts) == 1:   # `from shaketable import X`: the package's public names
                target = "__init__"
            else:
                target = parts[1]
            if target not in RANK:
                continue
            if target == "plots" and lazy and layer != "plots":
                pass  # a .plot() delegate
            elif lazy and (str(relative), module) in DELEGATES:
                pass
            elif target != layer and RANK[target] >= RANK.get(layer, 0):
                found.append(f"{relative}: imports {module} (layer {target!r} is not below "
                             f"{layer!r})")
            private = [name for name in names if name.startswith("_") and name != "__version__"]
            if private and module != own:
                found.append(f"{relative}: imports private {private} from {module}")
            if str(relative) == "scenes/parse.py" and (target == "studies" or module in (
                    f"{package.name}.scenes.run", f"{package.name}.reproduce")):
                found.append(f"{relative}: the scene parser imports {module}")
    return found


def oversized(package: Path, read=facts) -> dict[str, int]:
    """Every module longer than :data:`MAX_MODULE_LINES` (``"relative/path.py"``) and every
    function longer than :data:`MAX_FUNCTION_LINES` (``"relative/path.py:name"``, methods and
    nested functions included), with its length in lines."""
    found = {}
    for path in sorted(package.rglob("*.py")):
        relative = str(path.relative_to(package))
        text = path.read_text(encoding="utf-8")
        if len(text.splitlines()) > MAX_MODULE_LINES:
            found[relative] = len(text.splitlines())
        for name, length in read(text)[1]:
            if length > MAX_FUNCTION_LINES:
                found[f"{relative}:{name}"] = length
    return found


def import_graph(package: Path, read=facts) -> dict[str, set[str]]:
    """Module -> the package's modules it imports (at module level or in a function body),
    without ``if TYPE_CHECKING:`` imports and the :data:`CYCLE_DELEGATES`."""
    modules = {}
    for path in package.rglob("*.py"):
        parts = path.relative_to(package.parent).with_suffix("").parts
        modules[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        relative = str(path.relative_to(package))
        graph[name] = set()
        for module, names, _, type_only in read(path.read_text(encoding="utf-8"))[0]:
            if type_only or (relative, module) in CYCLE_DELEGATES:
                continue
            # `from shaketable.ground import records` imports the module records
            for target in [f"{module}.{n}" for n in names if f"{module}.{n}" in modules] or [module]:
                while target and target not in modules:
                    target = target.rpartition(".")[0]
                if target and target != name:
                    graph[name].add(target)
    return graph


def import_cycles(package: Path, read=facts) -> list[list[str]]:
    """The import cycles of the package: each group of modules that import each other,
    directly or through others (strongly connected components, Tarjan's algorithm)."""
    graph = import_graph(package, read)
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    cycles = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        for target in graph[node]:
            if target not in index:
                visit(target)
                low[node] = min(low[node], low[target])
            elif target in stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            group = [stack.pop()]
            while group[-1] != node:
                group.append(stack.pop())
            if len(group) > 1:
                cycles.append(sorted(group))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return sorted(cycles)


#: What ``numerics`` (shared by the engines, knowing none of them) may import of the package
#: outside itself: the physical constants.
NUMERICS_IMPORTS = {"shaketable.core.constants"}


def numerics_violations(package: Path) -> list[str]:
    """The imports of ``numerics/`` from the package beyond its own and NUMERICS_IMPORTS."""
    found = []
    for path in sorted((package / "numerics").rglob("*.py")):
        for module, _, _, _ in _imports(ast.parse(path.read_text())):
            if (module.split(".")[0] == "shaketable" and module not in NUMERICS_IMPORTS
                    and not module.startswith("shaketable.numerics")):
                found.append(f"numerics/{path.name}: imports {module}")
    return found


def test_numerics_imports_only_the_core_constants(tmp_path):
    assert numerics_violations(REPOSITORY / "shaketable") == []
    numerics = tmp_path / "shaketable" / "numerics"
    numerics.mkdir(parents=True)
    (numerics / "roots.py").write_text("from shaketable.core.constants import G\n"
                                       "from shaketable.numerics import dop853\n"
                                       "from shaketable.core.units import parse\n")
    assert numerics_violations(tmp_path / "shaketable") == [
        "numerics/roots.py: imports shaketable.core.units"]


@pytest.fixture(scope="module")
def read_once():
    """:func:`facts` with a memo (by the module's text) for this file's tests: four of them
    read the whole package, and parsing it costs ~0.6 s of CPU. The memo keeps the facts,
    not the syntax trees (a third of a million objects the garbage collector would scan)."""
    memo: dict[str, tuple[list, list]] = {}

    def read(text: str) -> tuple[list, list]:
        if text not in memo:
            memo[text] = facts(text)
        return memo[text]

    return read


def test_the_package_respects_its_layers(read_once):
    assert violations(REPOSITORY / "shaketable", read_once) == []


def test_the_check_fails_when_core_imports_plots(tmp_path):
    # the same rules on a copy of two modules, one of them changed to break a rule
    package = tmp_path / "shaketable"
    for relative in ("core/geometry.py", "plots/base.py"):
        (package / relative).parent.mkdir(parents=True, exist_ok=True)
        (package / relative).write_text((REPOSITORY / "shaketable" / relative).read_text())
    assert violations(package) == []
    geometry = package / "core" / "geometry.py"
    geometry.write_text(geometry.read_text() + "\nfrom shaketable.plots.base import save\n"
                        "import matplotlib\nfrom shaketable.core.units import _NUMBER_UNIT\n")
    found = violations(package)
    assert any("imports shaketable.plots.base (layer 'plots'" in v for v in found)
    assert any("imports matplotlib" in v for v in found)
    assert any("imports private ['_NUMBER_UNIT']" in v for v in found)


def test_no_module_imports_itself_through_others(read_once):
    assert import_cycles(REPOSITORY / "shaketable", read_once) == []


def test_every_listed_cycle_delegate_exists():
    # the list stays exact: an entry whose import is gone is removed from it
    package = REPOSITORY / "shaketable"
    for relative, module in CYCLE_DELEGATES:
        tree = ast.parse((package / relative).read_text(encoding="utf-8"))
        assert any(m == module and lazy for m, _, lazy, _ in _imports(tree)), (relative, module)


def test_the_cycle_check_sees_module_and_function_level_cycles(tmp_path):
    # a tiny package: a -> b at module level, b -> a inside a function; c -> plots.d in a
    # .plot() body not listed as a delegate, plots.d -> c at module level
    package = tmp_path / "shaketable"
    (package / "plots").mkdir(parents=True)
    (package / "__init__.py").write_text("")
    (package / "a.py").write_text("from shaketable.b import g\n")
    (package / "b.py").write_text("def g():\n    from shaketable import a\n    return a\n")
    (package / "c.py").write_text("def plot():\n    from shaketable.plots.d import draw\n")
    (package / "plots" / "__init__.py").write_text("")
    (package / "plots" / "d.py").write_text("from shaketable.c import plot\n")
    (package / "e.py").write_text("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n"
                                  "    from shaketable.f import F\n")
    (package / "f.py").write_text("from shaketable.e import TYPE_CHECKING\n")
    assert import_cycles(package) == [["shaketable.a", "shaketable.b"],
                                      ["shaketable.c", "shaketable.plots.d"]]


def test_benchmarks_do_not_drive_the_cli_module():
    for path in sorted((REPOSITORY / "benchmarks").glob("*.py")):
        for module, _, _, _ in _imports(ast.parse(path.read_text(encoding="utf-8"))):
            assert not module.startswith("shaketable.commands"), f"{path.name}: {module}"


def test_a_type_only_matplotlib_import_is_allowed_but_not_an_upward_one(tmp_path):
    # `if TYPE_CHECKING:` imports never run: matplotlib's Figure may name a return type
    # outside plots; the ranks of the package's own layers still apply to them
    package = tmp_path / "shaketable"
    (package / "core").mkdir(parents=True)
    geometry = package / "core" / "geometry.py"
    geometry.write_text((REPOSITORY / "shaketable" / "core" / "geometry.py").read_text()
                        + "\nfrom typing import TYPE_CHECKING\nif TYPE_CHECKING:\n"
                        "    from matplotlib.figure import Figure\n")
    assert violations(package) == []
    geometry.write_text(geometry.read_text()
                        + "    from shaketable.scenes.parse import Scene\n")
    assert violations(package) == [
        "core/geometry.py: imports shaketable.scenes.parse (layer 'scenes' is not below 'core')"]


def test_no_module_or_function_is_too_long(read_once):
    found = oversized(REPOSITORY / "shaketable", read_once)
    assert {name: size for name, size in found.items() if name not in SIZE_ALLOWANCES} == {}


def test_every_size_allowance_is_still_needed(read_once):
    assert SIZE_ALLOWANCES <= set(oversized(REPOSITORY / "shaketable", read_once))


def test_the_size_check_counts_from_def_to_the_last_line(tmp_path):
    # a function of exactly the limit passes, one line more fails (its docstring and a
    # decorator's line: the decorator is not counted); a method is checked as a function
    package = tmp_path / "shaketable"
    package.mkdir()
    body = "    x = 1\n" * (MAX_FUNCTION_LINES - 2)
    (package / "fits.py").write_text(f"@staticmethod\ndef f():\n    \"\"\"Doc.\"\"\"\n{body}")
    assert oversized(package) == {}
    (package / "long.py").write_text("class C:\n    def g(self):\n        x = 0\n"
                                     + body.replace("    ", "        ") + "        return x\n")
    (package / "big.py").write_text("x = 1\n" * (MAX_MODULE_LINES + 1))
    assert oversized(package) == {"long.py:g": MAX_FUNCTION_LINES + 1,
                                  "big.py": MAX_MODULE_LINES + 1}
