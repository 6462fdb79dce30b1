"""The shipped cases are package data: found through the package wherever it is installed."""
from __future__ import annotations

import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

import viscontact
from viscontact import load_case, shipped_case
from viscontact.errors import ParameterError
from viscontact.io.shipped import shipped_case_names, shipped_cases_dir

ROOT = Path(__file__).resolve().parents[2]


def test_shipped_cases_live_in_the_package() -> None:
    folder = shipped_cases_dir()
    assert folder == Path(viscontact.__file__).parent / "cases"
    names = shipped_case_names()
    assert {"creep_indentation", "seed_table1_v0.4", "seed_table3_case4", "sweeps/base_steady"} <= set(names)
    assert len(names) == len(list(folder.rglob("*.toml")))
    assert (ROOT / "cases").resolve() == folder.resolve()     # the repository's cases/ is the same folder
    for name in names:
        if not name.startswith("sweeps/"):
            assert load_case(shipped_case(name)).grid.n >= 8, name


def _case_files() -> list[Path]:
    """Every file under the shipped cases folder: the case files and the data they read."""
    return [p for p in shipped_cases_dir().rglob("*") if p.is_file() and "__pycache__" not in p.parts]


def test_package_data_covers_every_case_file() -> None:
    """pyproject's package-data patterns match every file under cases/ (a term file a case reads,
    ``material.file``, ships with it), and every file a shipped case reads is there."""
    import tomllib
    from fnmatch import fnmatch

    patterns = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]["viscontact"]
    package = Path(viscontact.__file__).parent
    for path in _case_files():
        relative = path.relative_to(package).as_posix()
        assert any(fnmatch(relative, pattern) and relative.count("/") == pattern.count("/") for pattern in patterns), \
            relative
    for name in shipped_case_names():
        case = load_case(shipped_case(name)) if not name.startswith("sweeps/") else None
        material_file = getattr(case.material, "file", None) if case else None
        if material_file:
            assert (shipped_case(name).parent / material_file).is_file(), (name, material_file)


def test_shipped_case_by_name() -> None:
    path = shipped_case("creep_indentation")
    assert path == shipped_case("creep_indentation.toml") and path.is_file()
    with pytest.raises(ParameterError, match="no shipped case named 'creep'.*creep_indentation") as info:
        shipped_case("creep")
    assert info.value.key == "case"


def test_reproduce_finds_the_shipped_cases_outside_the_repository(tmp_path: Path, monkeypatch) -> None:
    from viscontact.reproduce import find_cases_dir

    monkeypatch.chdir(tmp_path)                                # no ./cases here
    assert find_cases_dir() == shipped_cases_dir()


@pytest.mark.slow
def test_wheel_ships_every_case(tmp_path: Path) -> None:
    """The built wheel holds every case file (what ``viscontact reproduce`` needs once installed)
    and every module of the package."""
    subprocess.run([sys.executable, "-m", "pip", "wheel", str(ROOT), "--no-deps", "-q", "-w", str(tmp_path)],
                   check=True, timeout=600)
    (wheel,) = tmp_path.glob("viscontact-*.whl")
    with zipfile.ZipFile(wheel) as archive:
        names = set(archive.namelist())
    shipped = {n for n in names if n.startswith("viscontact/cases/")}
    assert shipped == {f"viscontact/cases/{p.relative_to(shipped_cases_dir()).as_posix()}" for p in _case_files()}
    assert {f"viscontact/cases/{name}.toml" for name in shipped_case_names()} <= shipped
    package = Path(viscontact.__file__).parent
    modules = {f"viscontact/{p.relative_to(package).as_posix()}" for p in package.rglob("*.py")}
    assert modules <= names, sorted(modules - names)
