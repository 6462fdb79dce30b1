"""Long runs, faults and bad input: checkpoints, signals, atomic results, numerical guards, resources.

The runs are small (n = 32..48) so that each takes a second or two; the killed and interrupted ones
run in a subprocess, as a user's would.
"""
from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from viscontact import cli
from viscontact.running import resources
from viscontact.io import streaming
from viscontact.io.netcdf import open_result
from viscontact.errors import NumericalGuardError
from viscontact.solvers.checks import check_solution

from vc_testing import SEED_A0, SEED_MATERIAL_TOML, SEED_TAU, seed_material, sphere_problem

ROOT = Path(__file__).resolve().parents[2]
EXE = [sys.executable, "-m", "viscontact.cli"]
SLIDING = ROOT / "cases" / "seed_table1_v0.8.toml"  # frictionless sliding, 161 steps at n = 256


def _cmd(*args: str) -> list[str]:
    return [*EXE, "run", *args]


def _run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(_cmd(*args), capture_output=True, text=True, timeout=300)


def _same(a: Path, b: Path, rtol: float = 1e-12) -> float:
    """Largest relative difference of any variable of two result files (must have the same steps)."""
    da, db = xr.open_dataset(a), xr.open_dataset(b)
    assert da.sizes == db.sizes
    worst = 0.0
    for name in da.data_vars:
        x, y = da[name].values.astype(float), db[name].values.astype(float)
        scale = max(float(np.nanmax(np.abs(x))), 1e-300)
        worst = max(worst, float(np.nanmax(np.abs(x - y))) / scale)
    assert worst <= rtol, worst
    return worst


def _start_and_wait_for(path: Path, *args: str) -> subprocess.Popen:
    proc = subprocess.Popen(_cmd(*args), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 120
    while not path.exists():
        if proc.poll() is not None or time.time() > deadline:
            proc.kill()
            pytest.fail(f"no checkpoint appeared: {proc.communicate()}")
        time.sleep(0.02)
    return proc


def test_kill_9_then_resume_equals_uninterrupted(tmp_path):
    # 8 tau of sliding at 64^2: 321 steps, about 2 s of solving on a fast core, so that the kill at
    # most 0.3 s after the first checkpoint (step 4) lands inside the run (the case's 4 tau are 41
    # steps at this grid, 0.2 s: the run could end before the kill)
    common = (str(SLIDING), "--set", "grid.n=64", "--set", "time.t_end=0.32", "--quiet")
    full, part = tmp_path / "full.nc", tmp_path / "part.nc"
    assert _run(*common, "--out", str(full)).returncode == 0
    ckpt = Path(str(part) + ".checkpoint.npz")
    proc = _start_and_wait_for(ckpt, *common, "--out", str(part), "--checkpoint-every", "4")
    time.sleep(0.3 * np.random.default_rng().random())  # a moment of the run: computing or writing
    os.kill(proc.pid, signal.SIGKILL)
    proc.communicate()
    assert not part.exists()  # no result file until the run completes
    assert not list(tmp_path.glob("*.tmp"))
    # the steps done are in the streamed file (viscontact.io.streaming), readable with complete = 0; a
    # kill inside HDF5's (not atomic) flush can tear the record being flushed: open_result reads the
    # records_flushed whole ones (the raw file showed the last step as 0 in about one run of ten)
    streamed = open_result(streaming.partial_path(part))
    with xr.open_dataset(streaming.partial_path(part)) as raw:
        assert raw.sizes["t"] - streamed.sizes["t"] in (0, 1)
    with np.load(ckpt) as saved:
        assert streamed.attrs["complete"] == 0 and 4 <= streamed.sizes["t"] < 321
        assert np.array_equal(streamed["step"].values, np.arange(streamed.sizes["t"]))
        assert np.all(np.isfinite(streamed["pressure"].values)) and streamed["load"].values[-1] > 0
        assert 4 <= int(saved["extra__records"]) <= streamed.sizes["t"]  # resume drops the steps after it
    resumed = _run(*common, "--out", str(part), "--resume")
    assert resumed.returncode == 0, resumed.stderr
    assert not list(tmp_path.glob("*.tmp*"))  # a write killed half way is cleaned up by the resume
    assert xr.open_dataset(part).attrs["complete"] == 1
    _same(full, part)
    assert not ckpt.exists()  # removed after the complete write
    assert not streaming.partial_path(part).exists()  # renamed to the result


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_signal_stops_after_the_step_and_keeps_a_valid_partial_file(tmp_path, sig, code):
    out = tmp_path / "r.nc"
    proc = _start_and_wait_for(Path(str(out) + ".checkpoint.npz"), str(SLIDING), "--set", "grid.n=64",
                               "--set", "time.t_end=0.32", "--quiet", "--out", str(out), "--checkpoint-every", "3")
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == code
    lines = [line for line in err.splitlines() if line.strip() and "warning" not in line]
    assert len(lines) == 1 and signal.Signals(sig).name in lines[0] and "Traceback" not in err
    ds = xr.open_dataset(out)
    assert ds.attrs["complete"] == 0 and ds.attrs["stopped_by"] == signal.Signals(sig).name
    assert 0 < ds.sizes["t"] < 321
    assert np.all(np.isfinite(ds["pressure"].values))


def test_existing_result_is_not_overwritten_without_force(tmp_path, capsys):
    out = tmp_path / "r.nc"
    out.write_text("precious")
    code = cli.main(["run", str(ROOT / "cases" / "creep_indentation.toml"), "--out", str(out), "--quiet"])
    assert code == 2 and out.read_text() == "precious"
    assert "--force" in capsys.readouterr().err


def test_dry_run_prints_the_estimate_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "r.nc"
    code = cli.main(["run", str(ROOT / "cases" / "creep_indentation.toml"), "--out", str(out), "--dry-run"])
    said = capsys.readouterr().out
    assert code == 0 and not out.exists()
    assert "161 records" in said and "MiB" in said


def test_dry_run_time_counts_the_start_and_the_tangential_mode(tmp_path, capsys):
    """Seed Table 3 cases 1 and 4 have the same grid and steps; partial slip (case 4) alternates normal
    and tangential solves, so its estimate is the larger (a step measured 3.3 times case 1's at 128²,
    BENCHMARKS.md); and every estimate includes the start (imports, kernels), about a second."""
    said = {}
    for case in ("seed_table3_case1", "seed_table3_case4"):
        code = cli.main(["run", str(ROOT / "cases" / f"{case}.toml"), "--out", str(tmp_path / "r.nc"), "--dry-run"])
        out = capsys.readouterr().out
        assert code == 0
        said[case] = float(out.split("run time about ")[1].split()[0])  # seconds at this size
    assert said["seed_table3_case4"] > 1.5 * said["seed_table3_case1"] > 1.5 * resources.START_SECONDS


def test_a_run_too_big_is_refused_before_its_problem_is_built(tmp_path, capsys, monkeypatch):
    """At n = 16384 the problem alone (gap, checks) took 8.5 GB and 28 s before the estimate that
    refuses the run was made; the estimate now comes from the case's outline, so the problem is
    never built (Case.to_problem would raise here)."""
    from viscontact.io.case import Case

    def built(self):
        raise AssertionError("the problem was built before the estimate")

    monkeypatch.setattr(Case, "to_problem", built)
    code = cli.main(["run", str(ROOT / "cases" / "creep_indentation.toml"), "--out", str(tmp_path / "r.nc"),
                     "--dry-run", "--set", "grid.n=16384"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "GiB" in err[0]  # the disk, else the memory (24 GiB), else the time
    assert err[0].split(":")[2].strip() in ("output.every", "grid.n", "time.t_end")


def test_refuses_when_the_disk_cannot_hold_the_result(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(shutil, "disk_usage", lambda path: shutil._ntuple_diskusage(10**9, 10**9 - 1000, 1000))
    code = cli.main(["run", str(ROOT / "cases" / "creep_indentation.toml"), "--out", str(tmp_path / "r.nc")])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    assert "output.every" in err[0] and "free" in err[0]


# --- numerical guards, each triggered by a crafted case --------------------------------------------------
def _case(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "case.toml"
    path.write_text(text)
    return path


BASE = """
title = "guard"
""" + SEED_MATERIAL_TOML + """\
[indenter]
shape = "sphere"
radius = 0.01
[grid]
n = 32
half_width = {half_width}
[normal]
control = "load"
value = 0.15
[tangential]
mode = "{mode}"
sliding_speed = {speed}
[time]
t_end = {t_end}
{dt}
scheme = "{scheme}"
{extra}
"""


def _guard_run(tmp_path, capsys, half_width=1.5e-3, mode="none", speed=0.05, t_end=0.002, dt="dt = 2e-4",
               scheme="constant", extra=""):
    case = _case(tmp_path, BASE.format(half_width=half_width, mode=mode, speed=speed, t_end=t_end, dt=dt,
                                       scheme=scheme, extra=extra))
    code = cli.main(["run", str(case), "--out", str(tmp_path / "r.nc"), "--force"])  # not --quiet: warnings shown
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    return code, err


def test_guard_contact_beyond_the_domain_suggests_a_half_width(tmp_path, capsys):
    # refused before the run (viscontact.running.guards), no longer at the first step (exit 1)
    code, err = _guard_run(tmp_path, capsys, half_width=3e-4)
    assert code == 2 and len(err) == 1 and err[0].startswith("viscontact: error: grid.half_width:")
    assert "use grid.half_width = " in err[0]


def test_guard_contact_at_the_domain_edge_during_the_run():
    """What the estimate cannot see (a height file without curvature, a history it misjudges) is
    still caught at the step: pressure on the edge of the domain."""
    pb = sphere_problem(seed_material(), 8, 1e-3)
    p = np.zeros((8, 8))
    p[3:5, 3:5] = 1.0
    p[0, 4] = 0.5
    with pytest.raises(NumericalGuardError, match="edge of the domain.*half_width"):
        check_solution(pb, p, float(p.sum() * pb.grid.cell_area), float(p.sum() * pb.grid.cell_area))


def test_steady_state_cut_off_by_the_domain_edge_is_refused():
    """The steady solver checks its answer as a transient step is checked: at v tau / a0 = 1 the
    steady contact of the seed's material (about 2 a0 long) does not fit in +-2 a0; it used to be
    returned with the pressure at the edge equal to its peak. On +-3 a0 it fits."""
    from viscontact.solvers.steady import solve_steady

    def problem(half_width: float):
        return sphere_problem(seed_material(), 24, half_width, mode="frictionless_sliding", speed=SEED_A0 / SEED_TAU)

    with pytest.raises(NumericalGuardError, match="edge of the domain at v = .*half_width"):
        solve_steady(problem(2.0 * SEED_A0))
    p = solve_steady(problem(3.0 * SEED_A0)).pressure
    assert p[0].max() == p[-1].max() == p[:, 0].max() == p[:, -1].max() == 0.0


def test_guard_non_convergence_gives_the_residual(tmp_path, capsys):
    code, err = _guard_run(tmp_path, capsys, extra="[solver]\nmax_iterations = 2")
    assert code == 1 and len(err) == 1 and "did not converge" in err[0] and "residual" in err[0]


def test_guard_unstable_time_step_is_bad_input(tmp_path, capsys):
    code, err = _guard_run(tmp_path, capsys, dt="dt = 5e-3", t_end=0.02)
    assert code == 2 and len(err) == 1 and "time.dt" in err[0] and "linear" in err[0]


def test_warning_coarse_time_step_is_one_line(tmp_path, capsys):
    # the linear scheme at dt = 2.5 ms (a quarter of the retardation time) misses the creep by ~10 %
    code, err = _guard_run(tmp_path, capsys, dt="dt = 2.5e-3", t_end=0.02, scheme="linear")
    assert code == 0 and len(err) == 1 and err[0].startswith("viscontact: warning:") and "time.dt" in err[0]
    assert "%" in err[0]


def test_too_coarse_time_step_is_refused(tmp_path, capsys):
    # dt = 5 ms used to run with a warning only: the estimate is 33 % (viscontact.running.guards)
    code, err = _guard_run(tmp_path, capsys, dt="dt = 5e-3", t_end=0.02, scheme="linear")
    assert code == 2 and len(err) == 1 and err[0].startswith("viscontact: error: time.dt:")


def test_warning_wake_dropped_at_the_trailing_edge(tmp_path, capsys):
    # v tau / a0 = 10 on +-2.6 a0: the wake is 10 a0 long (measured bias ~10 %)
    code, err = _guard_run(tmp_path, capsys, half_width=2.6 * 588.7e-6, mode="frictionless_sliding",
                           speed=10 * 588.7e-6 / 0.01, t_end=0.02, dt="", scheme="linear")
    assert code == 0 and any("history dropped" in line for line in err)


def test_wake_warning_at_the_end_gives_the_largest_bias(tmp_path, capsys):
    """The first warning gives the estimate when it passes 1 %; the wake then lengthens and the bias
    grows tenfold (v tau / a0 = 10 on +-2.7 a0; against the steady state, mu_app is 11.5 % low at the
    end). The run's last line must give the largest estimate, the one in the result's wake_loss."""
    code, err = _guard_run(tmp_path, capsys, half_width=1.6e-3, mode="frictionless_sliding", speed=0.589,
                           t_end=0.06, dt="", scheme="linear")
    wake = [line for line in err if "history dropped" in line]
    assert code == 0 and len(wake) == 2
    largest = float(xr.open_dataset(tmp_path / "r.nc")["wake_loss"].max())
    assert largest > 0.1
    assert f"up to about {100 * largest:.2g}%" in wake[1]


def test_a_run_that_stops_short_of_t_end_says_so(tmp_path, capsys):
    """The steps are k dt up to t_end: with t_end = 2.1 ms and dt = 0.2 ms the last is at 2.0 ms,
    4.8 % short of what was asked, which used to pass without a word."""
    code, err = _guard_run(tmp_path, capsys, t_end=0.0021)
    assert code == 0 and len(err) == 1 and err[0].startswith("viscontact: warning: time.t_end")
    assert "ends at t = 0.002 s, 4.8 % short" in err[0]
    assert float(xr.open_dataset(tmp_path / "r.nc")["t"][-1]) == pytest.approx(0.002, rel=1e-12)
    code, err = _guard_run(tmp_path, capsys, t_end=0.002)
    assert code == 0 and err == []


def test_guards_nan_and_load_balance():
    pb = sphere_problem(seed_material(), 8, 1e-3)
    p = np.zeros((8, 8))
    p[3:5, 3:5] = 1.0
    with pytest.raises(NumericalGuardError, match="NaN"):
        check_solution(pb, np.where(p > 0, np.nan, 0.0), 1.0, 1.0)
    with pytest.raises(NumericalGuardError, match="load balance"):
        check_solution(pb, p, 0.9, 1.0)
    check_solution(pb, p, 1.0, 1.0)


def test_every_warning_is_a_viscontact_warning():
    """Every ``warnings.warn`` in the package names ViscontactWarning, which the command line prints
    as one ``viscontact: warning:`` line (a bare ``warnings.warn(text)`` would be a UserWarning with a
    source line under it); the package warns through ``errors.warn_caller``, which does."""
    import ast

    calls = 0
    for path in (ROOT / "src" / "viscontact").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "warn_caller":
                calls += 1
            elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "warn":
                category = node.args[1] if len(node.args) > 1 else \
                    next((k.value for k in node.keywords if k.arg == "category"), None)
                assert isinstance(category, ast.Name) and category.id == "ViscontactWarning", \
                    f"{path.name}:{node.lineno} warns without ViscontactWarning"
    assert calls >= 3  # the wake, the coarse time step, the resources, the failed sweep run
