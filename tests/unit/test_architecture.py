"""The shape of the package, read from its source: the layers and their one-way imports (imports made
inside functions counted), no import cycle, private names stay in their module, matplotlib is imported
by the one pyplot helper, and data flows one way (sweep and reproduce use plotting, plotting uses
neither); and what a run loads: no xarray, pandas, dask or matplotlib."""
from __future__ import annotations

import ast
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src" / "viscontact"
MODULES = sorted(SRC.rglob("*.py"))


def _module_name(path: Path) -> str:
    parts = path.relative_to(SRC.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _nodes(tree: ast.AST):
    """Every node of ``tree`` but those of ``if TYPE_CHECKING:`` bodies (they never run)."""
    yield tree
    for child in ast.iter_child_nodes(tree):
        if isinstance(child, ast.If) and "TYPE_CHECKING" in ast.unparse(child.test):
            for node in child.orelse:
                yield from _nodes(node)
            continue
        yield from _nodes(child)


def _imports(path: Path, package: str | None = None) -> list[tuple[str, list[str]]]:
    """(absolute module, imported names) of every import in ``path``, those inside functions too;
    ``package``: the one relative imports start from (by default, that of ``path`` in the source)."""
    if package is None:
        package = _module_name(path) if path.name == "__init__.py" else _module_name(path).rpartition(".")[0]
    out = []
    for node in _nodes(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            base = package.split(".")
            if node.level:
                base = base[:len(base) - node.level + 1]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            out.append((module, [a.name for a in node.names]))
        elif isinstance(node, ast.Import):
            out.extend((a.name, []) for a in node.names)
    return out


#: the layers, lowest first: a module may import its own layer's modules and those of the layers
#: below, never above (docs/architecture.md). Each entry: the layer's name and its module prefixes.
LAYERS = (
    ("foundation", ("viscontact.errors", "viscontact.version")),
    ("numerics", ("viscontact.numerics",)),
    ("physics", ("viscontact.physics",)),
    ("bodies", ("viscontact.bodies",)),
    ("problem", ("viscontact.problem",)),
    ("solvers", ("viscontact.solvers",)),
    ("io", ("viscontact.io",)),
    ("running", ("viscontact.running",)),
    ("plotting", ("viscontact.plotting",)),
    ("edges", ("viscontact.reproduce", "viscontact.sweep")),
    ("command line", ("viscontact.cli", "viscontact._entry", "viscontact.__main__", "viscontact.sweep.__main__")),
    ("package", ("viscontact",)),
)


def layer_of(module: str) -> int:
    """Index in :data:`LAYERS` of ``module`` (the longest matching prefix)."""
    best = max(((len(prefix), i) for i, (_, prefixes) in enumerate(LAYERS) for prefix in prefixes
                if module == prefix or module.startswith(prefix + ".")), default=None)
    assert best is not None, f"{module} is in no layer of LAYERS"
    return best[1]


def _package_modules() -> set[str]:
    return {_module_name(p) for p in MODULES}


def _target(name: str, modules: set[str]) -> str | None:
    """The module of the package that importing ``name`` loads last (``a.b.c`` of ``from a.b import c``
    where c is a module, else ``a.b``)."""
    parts = name.split(".")
    for k in range(len(parts), 0, -1):
        if ".".join(parts[:k]) in modules:
            return ".".join(parts[:k])
    return None


def import_graph() -> dict[str, set[str]]:
    """module -> the package modules it imports (at module level and inside functions)."""
    modules = _package_modules()
    graph: dict[str, set[str]] = {m: set() for m in modules}
    for path in MODULES:
        me = _module_name(path)
        for module, names in _imports(path):
            if not module.startswith("viscontact"):
                continue
            for target in {_target(f"{module}.{n}", modules) for n in names} | ({_target(module, modules)}
                                                                                  if not names else set()):
                if target and target != me:
                    graph[me].add(target)
    return graph


def test_every_module_is_in_a_layer():
    for module in _package_modules():
        layer_of(module)


def test_imports_follow_the_layers():
    """No import, inside functions included, from a layer above the importer's."""
    bad = [f"{m} ({LAYERS[layer_of(m)][0]}) imports {t} ({LAYERS[layer_of(t)][0]})"
           for m, targets in sorted(import_graph().items()) for t in sorted(targets)
           if layer_of(t) > layer_of(m) and not t == "viscontact" and not m.startswith("viscontact.__init__")]
    bad += [f"{m} imports the package itself" for m, targets in import_graph().items()
            if "viscontact" in targets and m != "viscontact"]
    assert not bad, "\n".join(bad)


def test_no_import_cycle():
    """The import graph (imports inside functions counted) is acyclic: Tarjan's strongly connected
    components are single modules."""
    graph = import_graph()
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    cycles = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                cycles.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    assert not cycles, cycles


def test_the_layer_check_sees_an_import_inside_a_function(tmp_path):
    """The walker counts an import made inside a function and skips ``if TYPE_CHECKING:`` bodies."""
    path = tmp_path / "probe.py"
    path.write_text("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import hidden\n"
                    "def f():\n    from viscontact.cli import main\n")
    names = [m for m, _ in _imports(path, "viscontact")]
    assert "viscontact.cli" in names and "hidden" not in names


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(SRC)))
def test_no_private_name_is_imported_from_another_module(path):
    for module, names in _imports(path):
        if module.startswith("viscontact"):
            assert not [n for n in names if _private(n)], f"{path.name} imports {names} from {module}"
    # nor reached through a module attribute (``plotting._pyplot()``)
    tree = ast.parse(path.read_text(encoding="utf-8"))
    modules = {a.asname or a.name for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)
               and (node.level or (node.module or "").startswith("viscontact")) for a in node.names}
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in modules:
            assert not _private(node.attr), f"{path.name}: {node.value.id}.{node.attr}"


def test_matplotlib_is_imported_by_the_one_pyplot_helper_only():
    importers = {_module_name(p) for p in MODULES for module, _ in _imports(p) if module.startswith("matplotlib")}
    assert importers == {"viscontact.plotting.base"}


@pytest.mark.parametrize("user, used", [("viscontact.plotting", "viscontact.sweep"),
                                        ("viscontact.plotting", "viscontact.reproduce"),
                                        ("viscontact.plotting", "viscontact.cli"),
                                        ("viscontact.sweep", "viscontact.plotting"),
                                        ("viscontact.reproduce", "viscontact.cli")])
def test_data_flows_one_way(user, used):
    for path in MODULES:
        if _module_name(path).startswith(user):
            bad = [m for m, _ in _imports(path) if m.startswith(used)]
            assert not bad, f"{_module_name(path)} imports {bad}"


#: what neither ``import viscontact`` nor a whole ``viscontact run`` may load (issue 15's memory
#: target: xarray with pandas is ~60 MiB, dask and matplotlib more; they belong to reading results,
#: plots and sweeps)
HEAVY = ("xarray", "pandas", "dask", "matplotlib")
RUN_IN_A_FRESH_PROCESS = textwrap.dedent("""
    import json, sys
    import viscontact
    after_import = sorted(m for m in {heavy} if m in sys.modules)
    from viscontact.cli import main
    code = main(["run", sys.argv[1], "--out", sys.argv[2], "--quiet", "--set", "grid.n=32",
                 "--set", "time.t_end=0.001", "--set", 'output.fields=["pressure", "shear_x", "stick"]'])
    print(json.dumps([code, after_import, sorted(m for m in {heavy} if m in sys.modules)]))
""")


def test_a_run_loads_no_xarray_pandas_dask_or_matplotlib(tmp_path):
    """``import viscontact`` and then ``viscontact run`` of a case to a streamed result file, in a
    fresh interpreter: none of :data:`HEAVY` is in ``sys.modules`` after either (the file is the
    same as xarray's: ``test_streaming.test_layout_is_what_xarray_writes_byte_for_byte``)."""
    import json

    case = SRC / "cases" / "creep_indentation.toml"
    out = subprocess.run([sys.executable, "-c", RUN_IN_A_FRESH_PROCESS.format(heavy=HEAVY), str(case),
                          str(tmp_path / "r.nc")], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    code, after_import, after_run = json.loads(out.stdout.splitlines()[-1])
    assert code == 0 and (tmp_path / "r.nc").exists(), out.stderr
    assert after_import == [] and after_run == [], (after_import, after_run)


#: what building the command line's parser may not load: the case layer, the solvers' FFTs and the
#: sweeps (their import took 0.44 s of every command's start, ``viscontact --help`` 0.5 s in all)
PARSER_MUST_NOT_LOAD = ("pydantic", "scipy", "viscontact.io.case", "viscontact.sweep", "dask")
HELP_IN_A_FRESH_PROCESS = textwrap.dedent("""
    import contextlib, io, json, sys
    from viscontact.cli import main
    with contextlib.redirect_stdout(io.StringIO()):
        try:
            main(["--help"])
        except SystemExit:
            pass
    print(json.dumps(sorted(m for m in {names} if m in sys.modules)))
""")


def test_the_parser_loads_no_solver_case_or_sweep_module():
    """``viscontact --help`` (and the parser every command builds first) in a fresh interpreter: none
    of :data:`PARSER_MUST_NOT_LOAD` is imported."""
    import json

    out = subprocess.run([sys.executable, "-c", HELP_IN_A_FRESH_PROCESS.format(names=PARSER_MUST_NOT_LOAD)],
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout.splitlines()[-1]) == []


ARCHITECTURE_PAGE = SRC.parents[1] / "docs" / "architecture.md"


def _layer_rows() -> list[tuple[str, tuple[str, ...]]]:
    """(layer, packages) of the table between the ``layer-table`` markers of docs/architecture.md."""
    text = ARCHITECTURE_PAGE.read_text(encoding="utf-8")
    table = text.split("<!-- layer-table")[1].split("<!-- /layer-table -->")[0]
    rows = []
    for line in table.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) >= 3 and cells[1].startswith("`"):
            rows.append((cells[0], tuple(p.strip(" `") for p in cells[1].split(","))))
    return rows


def test_the_architecture_page_has_the_layer_table_of_this_test():
    """docs/architecture.md's layer table is :data:`LAYERS`, row by row (names and packages)."""
    assert _layer_rows() == [(name, tuple(prefixes)) for name, prefixes in LAYERS]


def test_every_module_the_architecture_page_names_exists():
    """Each ``pkg/module.py`` path and ``viscontact.x.y`` name in docs/architecture.md is in the source."""
    import re

    text = ARCHITECTURE_PAGE.read_text(encoding="utf-8")
    paths = set(re.findall(r"`((?:[a-z_]+/)+[a-z_]+\.py)", text)) - {"tests/unit/test_architecture.py",
                                                                    "tests/unit/test_docs_architecture.py"}
    missing = [p for p in sorted(paths) if not (SRC / p).exists() and not (SRC.parents[1] / p).exists()]
    modules = _package_modules()
    names = set(re.findall(r"`(viscontact(?:\.[A-Za-z_]+)+)", text))
    unknown = [n for n in sorted(names) if _target(n, modules) is None]
    assert not missing and not unknown, (missing, unknown)
