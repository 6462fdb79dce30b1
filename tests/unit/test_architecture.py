"""The shape of the package, read from its source: private names stay in their module, matplotlib
is imported by the one pyplot helper, and data flows one way (sweep and reproduce use plotting,
plotting uses neither)."""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src" / "viscontact"
MODULES = sorted(SRC.rglob("*.py"))


def _module_name(path: Path) -> str:
    parts = path.relative_to(SRC.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports(path: Path) -> list[tuple[str, list[str]]]:
    """(absolute module, imported names) of every import in ``path``."""
    package = _module_name(path) if path.name == "__init__.py" else _module_name(path).rpartition(".")[0]
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
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
