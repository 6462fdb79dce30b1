"""The run's warnings point at the user's line that called the API, not into the package: the
observers (:mod:`viscontact.running.observers`) and the checks before the run (:mod:`viscontact.running.guards`)
warn several calls deep, at a depth that differs between :func:`viscontact.running.api.run`,
:func:`viscontact.running.api.run_to_file` and the generator :func:`viscontact.running.loop.simulate`
(:func:`viscontact.errors.warn_caller`)."""
from __future__ import annotations

import subprocess
import sys
import warnings
from pathlib import Path

import pytest

from viscontact.running import api
from viscontact.running import loop
from viscontact.errors import ViscontactWarning
from viscontact.physics.materials import Material
from viscontact.problem.problem import PiecewiseLinear

from vc_testing import SEED_A0, SEED_TAU, seed_material, sphere_problem


def _growing_partial_slip():
    """Partial slip under the total slip with a load rising 4-fold over 8 steps at n = 32: the
    contact grows (ContactGrowthWarning)."""
    return sphere_problem(Material.elastic(1e6, 0.5), 32, 1.2e-3, value=PiecewiseLinear((0.0, 4e-3), (0.05, 0.2)),
                          mode="partial_slip", friction=0.5, rate=5e-4, speed=2.4e-3 / 32 / 5e-4, t_end=4e-3, dt=5e-4,
                          scheme="linear")


def _short_wake():
    """Fast frictionless sliding on a grid too short for its wake (WakeWarning, twice)."""
    return sphere_problem(seed_material(), 24, 2.6 * SEED_A0, value=0.148, mode="frictionless_sliding",
                          speed=10 * SEED_A0 / SEED_TAU, t_end=2.5 * SEED_TAU, scheme="linear", every=10**6)


def _run(problem, tmp: Path) -> int:
    """Calls the API on the line after the one it returns (so do the two below)."""
    line = sys._getframe().f_lineno + 1
    api.run(problem)
    return line


def _run_to_file(problem, tmp: Path) -> int:
    line = sys._getframe().f_lineno + 1
    api.run_to_file(problem, tmp / "r.nc")
    return line


def _simulate(problem, tmp: Path) -> int:
    line = sys._getframe().f_lineno + 1
    list(loop.simulate(problem))
    return line


ENTRY_POINTS = {"run": _run, "run_to_file": _run_to_file, "simulate": _simulate}


@pytest.mark.parametrize("entry", sorted(ENTRY_POINTS))
@pytest.mark.parametrize("problem, match", [(_growing_partial_slip, "contact grew"),
                                            (_short_wake, "trailing edge")], ids=["growth", "wake"])
def test_run_warnings_point_at_the_callers_line(entry: str, problem, match: str, tmp_path: Path) -> None:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        line = ENTRY_POINTS[entry](problem(), tmp_path)
    ours = [w for w in caught if issubclass(w.category, ViscontactWarning) and match in str(w.message)]
    assert ours, [str(w.message) for w in caught]
    assert [(w.filename, w.lineno) for w in ours] == [(__file__, line)] * len(ours)


def _uneven_end():
    """time.t_end = 2.5 dt: the guard before the run warns that it ends a step short."""
    return sphere_problem(seed_material(), 16, 2.6 * SEED_A0, t_end=2.5 * SEED_TAU / 20)


@pytest.mark.parametrize("entry", ["run", "run_to_file"])
def test_guard_warnings_point_at_the_callers_line(entry: str, tmp_path: Path) -> None:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        line = ENTRY_POINTS[entry](_uneven_end(), tmp_path)
    ours = [w for w in caught if "is not a multiple of time.dt" in str(w.message)]
    assert [(w.filename, w.lineno) for w in ours] == [(__file__, line)]


SCRIPT = Path(sys.executable).with_name("viscontact")
CREEP = Path(__file__).resolve().parents[2] / "cases" / "creep_indentation.toml"


@pytest.mark.skipif(not SCRIPT.exists(), reason="the viscontact console script is not installed")
def test_the_console_script_prints_each_warning_once_as_a_line(tmp_path: Path) -> None:
    """Under the console script every frame but the script's own line is the package's, so every
    warning is attributed to that one line; Python's once-per-place registry still tells two
    messages apart: the coarse grid and the uneven end, two lines, each ``viscontact: warning:``,
    no source line under them."""
    proc = subprocess.run([str(SCRIPT), "run", str(CREEP), "--set", "grid.n=12", "--set", "time.dt=0.001",
                           "--set", "time.t_end=0.0024", "--out", str(tmp_path / "r.nc")],
                          capture_output=True, text=True, timeout=300, check=False)
    lines = proc.stderr.splitlines()
    assert proc.returncode == 0 and len(lines) == 2, proc.stderr
    assert all(line.startswith("viscontact: warning: ") for line in lines), lines
    assert "grid.n = 12" in lines[0] and "is not a multiple of time.dt" in lines[1], lines
