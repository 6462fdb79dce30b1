"""The command line on bad input: status 2, one line on stderr naming the key, no traceback, no file."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BASE = (ROOT / "cases" / "creep_indentation.toml").read_text()
SCRIPT = Path(sys.executable).with_name("viscontact")
COMMAND = [str(SCRIPT)] if SCRIPT.exists() else [sys.executable, "-m", "viscontact.cli"]
TINY = {"\nn = 128": "\nn = 16", "half_width = 2.0e-3": "half_width = 1.6e-3", "t_end = 0.04": "t_end = 5e-4"}


def viscontact(*args: str | Path, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([*COMMAND, *map(str, args)], cwd=cwd, capture_output=True, text=True, timeout=300, check=False)


def edited(text: str, changes: dict[str, str]) -> str:
    for old, new in changes.items():
        assert old in text, old
        text = text.replace(old, new, 1)
    return text


BAD = {
    "wrong_type": ({"\nn = 128": '\nn = "big"'}, "grid.n"),
    "unknown_key": ({"poisson_ratio = 0.3": "poison_ratio = 0.3"}, "material.poison_ratio"),
    "out_of_range": ({"poisson_ratio = 0.3": "poisson_ratio = 0.7"}, "material.poisson_ratio"),
    "not_toml": ({"[time]": "[time"}, "case file"),
    "value_and_history": ({"value = 0.15 ": "value = 0.15\nhistory = [[0.0, 0.15]] "}, "normal.value"),
    "bad_mode": ({'mode = "none"': 'mode = "rolling"'}, "tangential.mode"),
}


def assert_one_line_error(proc: subprocess.CompletedProcess, key: str) -> None:
    assert proc.returncode == 2, proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith(f"viscontact: error: {key}: "), lines[0]
    assert "Traceback" not in proc.stderr + proc.stdout


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_case(tmp_path: Path, name: str) -> None:
    changes, key = BAD[name]
    (tmp_path / "case.toml").write_text(edited(BASE, changes))
    proc = viscontact("run", "case.toml", "--out", "out.nc", cwd=tmp_path)
    assert_one_line_error(proc, key)
    assert not (tmp_path / "out.nc").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["case.toml"]


def test_missing_case_file(tmp_path: Path) -> None:
    proc = viscontact("run", "nope.toml", "--out", "out.nc", cwd=tmp_path)
    assert_one_line_error(proc, "case file")
    assert list(tmp_path.iterdir()) == []


def test_bad_override(tmp_path: Path) -> None:
    (tmp_path / "case.toml").write_text(BASE)
    proc = viscontact("run", "case.toml", "--out", "out.nc", "--set", "grid.n=2", cwd=tmp_path)
    assert_one_line_error(proc, "grid.n")
    assert not (tmp_path / "out.nc").exists()


def test_existing_result_is_kept(tmp_path: Path) -> None:
    (tmp_path / "case.toml").write_text(BASE)
    (tmp_path / "out.nc").write_text("precious")
    proc = viscontact("run", "case.toml", "--out", "out.nc", cwd=tmp_path)
    assert_one_line_error(proc, "out.nc")
    assert "--force" in proc.stderr
    assert (tmp_path / "out.nc").read_text() == "precious"


def test_plot_missing_result(tmp_path: Path) -> None:
    proc = viscontact("plot", "nope.nc", "--out", "figs", cwd=tmp_path)
    assert_one_line_error(proc, "nope.nc")
    assert not (tmp_path / "figs").exists()


def test_tiny_run_and_plot(tmp_path: Path) -> None:
    """End to end on a 16 x 16 grid, 3 steps: the contract commands succeed."""
    (tmp_path / "case.toml").write_text(edited(BASE, TINY))
    proc = viscontact("run", "case.toml", "--out", "out.nc", "--quiet", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == "" and "Traceback" not in proc.stderr
    proc = viscontact("plot", "out.nc", "--out", "figs", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "figs" / "pressure_profiles.png").exists()
    import xarray as xr

    with xr.open_dataset(tmp_path / "out.nc", engine="h5netcdf") as ds:
        assert ds.sizes["t"] == 3 and ds.attrs["complete"] == 1


def test_version() -> None:
    from viscontact import __version__

    proc = subprocess.run([*COMMAND, "--version"], capture_output=True, text=True, timeout=60, check=False)
    assert proc.returncode == 0 and __version__ in proc.stdout
