"""Sweeps on dask.distributed (viscontact.sweep): same numbers as one-by-one runs, resume after an
interruption without recomputing, sweep-file validation before any run starts."""
from __future__ import annotations

import json
import os
import time
import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from viscontact import cli
from viscontact.running import api
from viscontact.io.case import load_case
from viscontact.errors import ParameterError, ViscontactWarning
from viscontact.plotting import plot_sweep
from viscontact.sweep import SweepSpec, load_sweep, plan, run_file_name, runs_dir, sweep

from vc_testing import SEED_MATERIAL_TOML

pytestmark = [pytest.mark.timeout(90),
              pytest.mark.filterwarnings("ignore:time.dt = .* the transient is resolved coarsely")]

# retardation time 0.04 s: the coarse dt of this tiny grid (4 ms) resolves its creep (viscontact.running.guards)
BASE = """\
title = "tiny sweep base"
""" + SEED_MATERIAL_TOML.replace("retardation_time = 0.01", "retardation_time = 0.04") + """\
[indenter]
shape = "sphere"
radius = 0.01
[grid]
n = 16
half_width = 1.507e-3
[normal]
control = "load"
value = 0.148
[tangential]
mode = "frictionless_sliding"
sliding_speed = 0.0471
[time]
t_end = 0.012
scheme = "linear"  # stable at the coarse dt of this tiny grid
"""

SPEEDS = [0.0471, 0.0942]
MODULI = [0.193e6, 0.643e6]


def write_sweep(folder: Path, solver: str = "transient", parameters: str | None = None, base: str = "base.toml",
                extra: str = "") -> Path:
    (folder / "base.toml").write_text(BASE)
    parameters = parameters if parameters is not None else (
        f'"tangential.sliding_speed" = {SPEEDS}\n"material.shear_modulus_long_term" = {MODULI}\n')
    path = folder / "sweep.toml"
    path.write_text(f'base = "{base}"\nsolver = "{solver}"\n{extra}[parameters]\n{parameters}')
    return path


@pytest.fixture(scope="module")
def client():
    distributed = pytest.importorskip("distributed")
    from viscontact.sweep import local_cluster

    with local_cluster(2) as cluster, distributed.Client(cluster) as c:
        yield c


@pytest.fixture(scope="module")
def transient_sweep(tmp_path_factory, client):
    folder = tmp_path_factory.mktemp("transient")
    spec = write_sweep(folder)
    out = folder / "sweep.nc"
    with pytest.warns(ViscontactWarning, match="2 of 4 runs recorded other times"):  # the slow runs' dt
        ds = sweep(spec, client=client, out=out)
    return folder, spec, out, ds


def point_label(speed: float, modulus: float) -> str:
    return f"tangential.sliding_speed={speed!r}, material.shear_modulus_long_term={modulus:g}"


# --- distributed == one by one ---------------------------------------------------------------------
def test_transient_sweep_matches_runs_one_by_one(transient_sweep):
    folder, _, out, ds = transient_sweep
    base = load_case(folder / "base.toml")
    assert ds.attrs["kind"] == "sweep" and ds.attrs["runs_computed"] == 4 and ds.attrs["runs_failed"] == 0
    assert "Friction (2023)" in ds.attrs["references"] and ds.attrs["source"].startswith("viscontact")
    assert "created by viscontact" in ds.attrs["history"]
    assert ds["mu_app"].dims == ("tangential__sliding_speed", "material__shear_modulus_long_term")
    assert ds["tangential__sliding_speed"].attrs["key"] == "tangential.sliding_speed"
    assert ds["mu_app_t"].dims[-1] == "t"
    for i, v in enumerate(SPEEDS):
        for j, g in enumerate(MODULI):
            ref = api.run(base.with_overrides({"tangential.sliding_speed": v, "material.shear_modulus_long_term": g,
                                               "solver.workers": 1}))
            point = ds.isel(tangential__sliding_speed=i, material__shear_modulus_long_term=j)
            for name in ("mu_app", "contact_area", "contact_shift", "delta_z", "load"):
                assert float(point[name]) == float(ref[name][-1]), name
            assert float(point["peak_pressure"]) == float(ref["pressure"][-1].max())
            assert float(point["t_gross_sliding"]) == ref.attrs["t_gross_sliding"]
            assert str(point["error"].values) == ""
            # the time series, on the union time axis, holds the run's own records exactly
            series = point["mu_app_t"].sel(t=ref["t"].values, method="nearest")
            np.testing.assert_array_equal(series.values, ref["mu_app"].values)
            # the slow runs recorded every other time of the axis: interpolated there, and listed
            interpolated = json.loads(ds.attrs["interpolated_runs"])
            assert (point["tangential__sliding_speed"].item() == SPEEDS[0]) == (point_label(v, g) in interpolated)
            # the kept result file is the full run
            name = run_file_name({"tangential.sliding_speed": v, "material.shear_modulus_long_term": g})
            with xr.open_dataset(runs_dir(out) / name, engine="h5netcdf") as kept:
                assert kept.attrs["complete"] == 1
                np.testing.assert_array_equal(kept["pressure"].values, ref["pressure"].values)
    on_disk = xr.open_dataset(out, engine="h5netcdf").load()
    xr.testing.assert_identical(on_disk[["mu_app", "mu_app_t", "error"]], ds[["mu_app", "mu_app_t", "error"]])


def test_steady_sweep_matches_steady_one_by_one(tmp_path, client):
    spec = write_sweep(tmp_path, solver="steady", parameters=f'"tangential.sliding_speed" = {SPEEDS}\n')
    ds = sweep(spec, client=client)  # out=None: nothing written
    assert not list(tmp_path.glob("*.runs")) and "t" not in ds.dims
    base = load_case(tmp_path / "base.toml")
    for i, v in enumerate(SPEEDS):
        ref = api.run_steady(base.with_overrides({"tangential.sliding_speed": v, "solver.workers": 1}))
        assert float(ds["mu_app"][i]) == float(ref["mu_app"][-1])
        assert float(ds["peak_pressure"][i]) == float(ref["pressure"][-1].max())


# --- resume ----------------------------------------------------------------------------------------
def test_resume_recomputes_only_unfinished_runs(tmp_path, transient_sweep, client):
    src, _, _, first = transient_sweep
    spec = write_sweep(tmp_path)
    out = tmp_path / "sweep.nc"
    folder = runs_dir(out)
    folder.mkdir()
    names = sorted(p.name for p in runs_dir(src / "sweep.nc").iterdir())
    assert len(names) == 4
    # state of a sweep killed part way: two complete files, one file of an interrupted run
    # (complete = 0) and the temporary file of a write that was cut off
    for name in names[:2]:
        (folder / name).write_bytes((runs_dir(src / "sweep.nc") / name).read_bytes())
    partial = xr.open_dataset(runs_dir(src / "sweep.nc") / names[2], engine="h5netcdf").load()
    partial = partial.isel(t=slice(0, 1)).assign_attrs(complete=0)
    partial.to_netcdf(folder / names[2], engine="h5netcdf")
    (folder / f"{names[3]}.tmpab12cd").write_bytes(b"\x89HDF cut off")
    old = 1_000_000_000
    for name in names[:3]:
        os.utime(folder / name, (old, old))

    ds = sweep(spec, client=client, out=out)

    assert (ds.attrs["runs_reused"], ds.attrs["runs_computed"], ds.attrs["runs_failed"]) == (2, 2, 0)
    assert [(folder / n).stat().st_mtime for n in names[:2]] == [old, old]   # not recomputed
    assert (folder / names[2]).stat().st_mtime > old                       # recomputed
    assert sorted(p.name for p in folder.iterdir()) == names              # temp file cleaned
    for name in ("mu_app", "peak_pressure", "contact_area", "mu_app_t"):
        xr.testing.assert_identical(ds[name], first[name])
    # a third run of the same command computes nothing
    again = sweep(spec, client=client, out=out)
    assert (again.attrs["runs_reused"], again.attrs["runs_computed"]) == (4, 0)


@pytest.mark.timeout(300)  # two sweep processes with their dask workers: slow on a loaded machine
def test_sweep_killed_part_way_is_resumed(tmp_path):
    """The real thing: ``python -m viscontact.sweep`` killed (SIGKILL, with its workers) once some run
    files exist; the same command then computes only the missing runs."""
    import signal
    import subprocess
    import sys

    spec = write_sweep(tmp_path, parameters='"normal.value" = [0.10, 0.11, 0.12, 0.13, 0.14, 0.15, 0.16, 0.17, '
                                            '0.18, 0.19, 0.20, 0.21]\n', extra='[overrides]\n"time.t_end" = 0.04\n')
    out = tmp_path / "sweep.nc"
    command = [sys.executable, "-m", "viscontact.sweep", str(spec), "--out", str(out), "--workers", "1"]
    proc = subprocess.Popen(command, cwd=tmp_path, start_new_session=True, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 180
        while len(list(runs_dir(out).glob("*.nc"))) < 2 and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.02)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)  # the sweep and the worker processes it started
        proc.wait()
    time.sleep(0.5)
    finished = {p.name: p.stat().st_mtime_ns for p in runs_dir(out).glob("*.nc")}
    assert 2 <= len(finished) < 12 and not out.exists()
    result = subprocess.run(command, cwd=tmp_path, capture_output=True, text=True, timeout=240)
    assert result.returncode == 0, result.stderr
    assert f"({12 - len(finished)} computed, {len(finished)} reused, 0 failed)" in result.stdout
    assert {n: (runs_dir(out) / n).stat().st_mtime_ns for n in finished} == finished
    assert sorted(p.name for p in runs_dir(out).iterdir()) == sorted(
        run_file_name({"normal.value": v}) for v in np.arange(0.10, 0.215, 0.01).round(2))


def test_run_file_of_another_case_is_recomputed(tmp_path, transient_sweep, client):
    src, _, _, _ = transient_sweep
    spec = write_sweep(tmp_path, parameters=f'"tangential.sliding_speed" = {SPEEDS[:1]}\n'
                                            f'"material.shear_modulus_long_term" = {MODULI[:1]}\n',
                       extra='[overrides]\n"time.t_end" = 0.008\n')
    out = tmp_path / "sweep.nc"
    runs_dir(out).mkdir()
    name = run_file_name({"tangential.sliding_speed": SPEEDS[0], "material.shear_modulus_long_term": MODULI[0]})
    (runs_dir(out) / name).write_bytes((runs_dir(src / "sweep.nc") / name).read_bytes())  # t_end = 0.012
    ds = sweep(spec, client=client, out=out)
    assert ds.attrs["runs_computed"] == 1 and float(ds["t"][-1]) < 0.0085  # t_end = 0.008 (was 0.012)


def test_failed_run_is_nan_with_its_error_and_the_rest_finish(tmp_path, client):
    spec = write_sweep(tmp_path, parameters='"solver.max_iterations" = [1, 500]\n')
    with pytest.warns(ViscontactWarning, match=r"run failed \(solver.max_iterations=1\)"):
        ds = sweep(spec, client=client, out=tmp_path / "sweep.nc")
    assert ds.attrs["runs_failed"] == 1 and ds.attrs["complete"] == 0
    assert np.isnan(float(ds["mu_app"][0])) and "ConvergenceError" in str(ds["error"].values[0])
    assert np.isfinite(float(ds["mu_app"][1])) and str(ds["error"].values[1]) == ""


def test_cli_sweep_resumes_and_plots(tmp_path, transient_sweep, client, monkeypatch, capsys):
    """The CLI on a finished sweep: nothing computed, no cluster started, figures written."""
    import viscontact.sweep.execute as execute

    _, spec, out, _ = transient_sweep

    class NoCluster:
        def __init__(self, *a):
            raise AssertionError("a cluster was started although every run is complete")

    monkeypatch.setattr(execute, "cluster_client", NoCluster)
    assert cli.main(["sweep", str(spec), "--out", str(out), "--plots", str(tmp_path / "fig")]) == 0
    assert "0 computed, 4 reused, 0 failed" in capsys.readouterr().out
    assert (tmp_path / "fig" / "sweep_mu_app.png").stat().st_size > 0


# --- the union time axis -------------------------------------------------------------------------------
def _fake_result(t):
    """What a transient run hands to assemble (viscontact.sweep.summarize): mu_app_t = 10 t."""
    from viscontact.sweep import SERIES, SUMMARIES

    t = np.asarray(t, dtype=float)
    return {"error": "", "warnings": [], "run_time": 1.0, "t_gross_sliding": 0.0, "complete": 1,
            **{n: 1.0 for n in SUMMARIES}, "t": t, **{f"{n}_t": 10 * t for n in SERIES}}


@pytest.mark.parametrize("slow, warned", [([0.0, 2.0, 4.0], True),   # every other time of the axis
                                          ([0.0, 1.0, 2.0], False)])  # shorter: NaN beyond, none interpolated
def test_runs_interpolated_onto_the_union_time_axis_are_listed_and_warned_once(tmp_path, slow, warned):
    import warnings

    from viscontact.sweep.assemble import assemble

    the_plan = plan(write_sweep(tmp_path, parameters=f'"tangential.sliding_speed" = {SPEEDS}\n'))
    results = {0: _fake_result(slow), 1: _fake_result([0.0, 1.0, 2.0, 3.0, 4.0])}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ds = assemble(the_plan, results, transient=True)
    ours = [w for w in caught if issubclass(w.category, ViscontactWarning)]
    assert ds["t"].values.tolist() == [0.0, 1.0, 2.0, 3.0, 4.0] and "union" in ds.attrs["time_axis"]
    assert json.loads(ds.attrs["interpolated_runs"]) == ([f"tangential.sliding_speed={SPEEDS[0]}"] if warned else [])
    assert len(ours) == int(warned) and all(w.filename == __file__ for w in ours)
    if warned:
        assert "1 of 2 runs" in str(ours[0].message) and "interpolated linearly" in str(ours[0].message)
    np.testing.assert_allclose(ds["mu_app_t"].values[0], 10 * ds["t"].values if warned else [0, 10, 20, np.nan, np.nan])


# --- validation before any run -----------------------------------------------------------------------
@pytest.mark.parametrize("parameters, solver, key, words", [
    ('"tangential.sliding_sped" = [0.01]\n', "steady", "tangential.sliding_sped", "did you mean 'tangential.sliding_speed'"),
    ('"tangental.sliding_speed" = [0.01]\n', "steady", "tangental.sliding_speed", "did you mean 'tangential.sliding_speed'"),
    ('"tangential.sliding_speed" = []\n', "steady", "tangential.sliding_speed", "empty list"),
    ('"tangential.sliding_speed" = 0.01\n', "steady", "tangential.sliding_speed", "must be an array"),
    ('"tangential.sliding_speed" = [0.01, 0.01]\n', "steady", "tangential.sliding_speed", "listed twice"),
    ('"tangential.sliding_speed" = [0.01]\n', "stedy", "solver", "'steady', 'transient'"),
    ('"tangential.sliding_speed" = [0.01, -1.0]\n', "steady", "tangential.sliding_speed",
     "tangential.sliding_speed=-1"),
    ('"material.shear_modulus_long_term" = [2e6]\n', "steady", "material.shear_modulus_long_term", "<="),
    # what the solver refuses before its first step (viscontact.running.guards, ...): refused before any run
    ('"material.retardation_time" = [0.04, 0.002]\n', "transient", "tangential.steps_per_cell",
     "use tangential.steps_per_cell = 16 (time.dt = 0.00025 s) (in the run material.retardation_time=0.002)"),
    ('"normal.value" = [0.148, 1.0]\n', "steady", "grid.half_width", "(in the run normal.value=1)"),
    ('"tangential.sliding_speed" = [0.0471, 0]\n[overrides]\n"tangential.mode" = "none"\n"time.dt" = 0.001\n',
     "steady", "tangential.sliding_speed", "steady state, got 0.0 (in the run tangential.sliding_speed=0)"),
    # an axis the steady solver ignores (viscontact.solvers.steady.ignored_keys): every run would be the same
    ('"tangential.slip" = ["total", "incremental"]\n[overrides]\n"tangential.mode" = "partial_slip"\n'
     '"tangential.displacement_rate" = 0.01\n"tangential.friction_coefficient" = 0.3\n',
     "steady", "tangential.slip", "the steady solver ignores it (it is partial slip's stick condition"),
    ('"tangential.displacement_history" = [[[0.0, 0.0], [0.01, 1e-6]], [[0.0, 0.0], [0.01, 2e-6]]]\n[overrides]\n'
     '"tangential.mode" = "partial_slip"\n"tangential.friction_coefficient" = 0.3\n"time.dt" = 0.001\n',
     "steady", "tangential.displacement_history", "never slides, so the case has no steady sliding state"),
    ('"time.dt" = [0.001, 0.002]\n', "steady", "time.dt", "a steady state has no time steps"),
    ('"time.t_end" = [0.012, 0.02]\n', "steady", "time.t_end", "and it is held"),
    ('"tangential.friction_coefficient" = [0.1, 0.3]\n', "steady", "tangential.friction_coefficient",
     "'frictionless_sliding' has no friction"),
])
def test_bad_sweep_file_fails_before_any_run(tmp_path, monkeypatch, capsys, parameters, solver, key, words):
    import viscontact.sweep.execute as execute

    spec = write_sweep(tmp_path, solver=solver, parameters=parameters)
    monkeypatch.setattr(execute, "cluster_client", _forbidden)
    with pytest.raises(ParameterError) as info:
        sweep(spec, out=tmp_path / "sweep.nc")
    assert info.value.key == key and words in info.value.message
    started = time.perf_counter()
    assert cli.main(["sweep", str(spec), "--out", str(tmp_path / "sweep.nc")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"viscontact: error: {key}: ") and "Traceback" not in err
    assert time.perf_counter() - started < 5
    assert not (tmp_path / "sweep.nc").exists() and not runs_dir(tmp_path / "sweep.nc").exists()


@pytest.mark.parametrize("parameters, overrides", [
    ('"time.t_end" = [0.01, 0.02]\n', '"normal.history" = [[0.0, 0.1], [0.02, 0.148]]\n'),  # the load at t_end
    ('"tangential.friction_coefficient" = [0.1, 0.3]\n', '"tangential.mode" = "gross_sliding"\n'),
    # frictionless in one run only: the coefficient acts in the other
    ('"tangential.mode" = ["frictionless_sliding", "gross_sliding"]\n"tangential.friction_coefficient" = [0.1, 0.3]\n',
     ""),
])
def test_steady_sweep_keeps_the_keys_that_matter(tmp_path, parameters, overrides):
    the_plan = plan(write_sweep(tmp_path, solver="steady", parameters=parameters,
                                extra=f"[overrides]\n{overrides}" if overrides else ""))
    assert len(the_plan.runs) in (2, 4)


def test_steady_state_ignores_the_keys_it_says_it_ignores(tmp_path):
    """Every key of viscontact.solvers.steady.IGNORED_KEYS, changed, leaves every variable of a steady result
    (partial slip with friction and the subsurface stresses) bit for bit the same."""
    from viscontact.solvers.steady import IGNORED_KEYS

    changed = {"time.dt": 1e-3, "time.scheme": "constant", "tangential.steps_per_cell": 3,
               "tangential.displacement_rate": 0.05, "tangential.slip": "incremental", "output.every": 5,
               "output.subsurface_times": [0.001], "solver.coupling_tolerance": 1e-3,
               "solver.max_coupling_iterations": 3, "solver.mixed_precision": False, "solver.history": "direct"}
    assert set(changed) == set(IGNORED_KEYS)
    (tmp_path / "base.toml").write_text(BASE)
    case = load_case(tmp_path / "base.toml").with_overrides({
        "tangential.mode": "partial_slip", "tangential.friction_coefficient": 0.3,
        "tangential.displacement_rate": 0.01, "output.subsurface_depths": [1e-4, 3e-4]})
    reference = api.run_steady(case)
    for key, value in changed.items():
        other = api.run_steady(case.with_overrides({key: value}))
        xr.testing.assert_identical(other.drop_attrs(), reference.drop_attrs())


def test_plan_leaves_the_warnings_of_the_guards_to_the_runs(tmp_path):
    """A run the time-step guard only warns about (18.9 % at a retardation time of 12 ms) is planned,
    even where warnings are errors; the one it refuses (8 ms) is not."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        the_plan = plan(write_sweep(tmp_path, parameters='"material.retardation_time" = [0.04, 0.012]\n'))
    assert len(the_plan.runs) == 2
    with pytest.raises(ParameterError, match=r"misses the creep .* \(in the run material.retardation_time=0.008\)"):
        plan(write_sweep(tmp_path, parameters='"material.retardation_time" = [0.012, 0.008]\n'))


def test_missing_base_and_unknown_sweep_key(tmp_path, monkeypatch):
    spec = write_sweep(tmp_path, base="nowhere.toml")
    with pytest.raises(ParameterError, match="no such case file") as info:
        plan(spec)
    assert info.value.key == "base"
    (tmp_path / "s2.toml").write_text('base = "base.toml"\nsolvr = "steady"\n[parameters]\n"grid.n" = [16]\n')
    with pytest.raises(ParameterError, match="did you mean 'solver'"):
        load_sweep(tmp_path / "s2.toml")
    # base found relative to the CWD when it is not beside the sweep file
    sub = tmp_path / "sub"
    sub.mkdir()
    (sub / "sweep.toml").write_text('base = "base.toml"\n[parameters]\n"grid.n" = [16, 20]\n')
    monkeypatch.chdir(tmp_path)
    the_plan = plan(sub / "sweep.toml")
    assert the_plan.base_path == tmp_path / "base.toml" and len(the_plan.runs) == 2


def test_spec_object_and_dotted_tables(tmp_path):
    (tmp_path / "base.toml").write_text(BASE)
    spec = SweepSpec(base=tmp_path / "base.toml", parameters={"grid.n": [16, 20], "normal.value": [0.1, 0.15, 0.2]})
    the_plan = plan(spec, fixed={"solver.workers": 1})
    assert len(the_plan.runs) == 6 and spec.dims == ("grid__n", "normal__value")
    assert the_plan.runs[0].case.solver.workers == 1 and the_plan.runs[5].case.normal.value == 0.2
    # unquoted dotted keys in [parameters] are nested tables in TOML: read as dotted keys too
    (tmp_path / "s.toml").write_text('base = "base.toml"\n[parameters]\ntangential.sliding_speed = [0.01, 0.02]\n')
    assert list(load_sweep(tmp_path / "s.toml").parameters) == ["tangential.sliding_speed"]


def test_run_file_names():
    assert run_file_name({"tangential.sliding_speed": 0.002, "material.shear_modulus_long_term": 0.193e6}) == \
        "tangential.sliding_speed=0.002__material.shear_modulus_long_term=193000.nc"
    assert run_file_name({"grid.n": 64, "tangential.mode": "gross_sliding"}) == \
        "grid.n=64__tangential.mode=gross_sliding.nc"
    long = run_file_name({f"material.key{i}": 1.0 / 3.0 for i in range(20)})
    assert len(long) <= 203 and long.endswith(".nc")


def test_shipped_example_sweep_is_valid():
    root = Path(__file__).resolve().parents[2]
    the_plan = plan(root / "cases" / "sweeps" / "steady_mu_app_vs_speed.toml")
    assert the_plan.spec.solver == "steady" and len(the_plan.runs) == 24
    ratios = [1.93e6 / g for g in the_plan.spec.parameters["material.shear_modulus_long_term"]]
    np.testing.assert_allclose(sorted(ratios), [3, 5, 10])
    speeds = np.array(the_plan.spec.parameters["tangential.sliding_speed"])
    assert speeds.max() / speeds.min() == pytest.approx(100, rel=1e-3)


def test_plot_sweep_of_a_saved_file(tmp_path, transient_sweep):
    _, _, out, _ = transient_sweep
    ds = xr.open_dataset(out, engine="h5netcdf").load()
    paths = plot_sweep(ds, tmp_path)
    assert {p.name for p in paths} == {"sweep_mu_app.png", "sweep_peak_pressure.png", "sweep_contact_area.png"}
    assert json.loads(ds.attrs["swept_keys"]) == ["tangential.sliding_speed", "material.shear_modulus_long_term"]


# --- helpers ---------------------------------------------------------------------------------------
def _forbidden(*a, **k):
    raise AssertionError("a cluster was started before the sweep file was checked")


@pytest.mark.parametrize("device, workers, expected", [("gpu", None, 1), ("gpu", 3, 3), ("cpu", None, None)])
def test_a_local_cluster_for_gpu_runs_has_one_worker_unless_told(tmp_path, monkeypatch, device, workers, expected):
    """Runs with solver.device = "gpu" share the one CUDA device: the local cluster defaults to one
    worker process for them (not one per core, each with its own CUDA context); --workers still
    sets it; CPU runs keep the default (one per core). CuPy's presence is faked: no run starts."""
    import importlib.util

    from viscontact.sweep import execute

    real_find_spec = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: object() if name == "cupy" else real_find_spec(name, *a))
    asked = []

    def no_cluster(client, n):
        asked.append(n)
        raise RuntimeError("stop before any run")

    monkeypatch.setattr(execute, "cluster_client", no_cluster)
    spec = write_sweep(tmp_path, extra=f'[overrides]\n"solver.device" = "{device}"\n"grid.n" = 512\n')
    with pytest.raises(RuntimeError, match="stop before any run"), warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the CPU run's estimates at 512^2
        sweep(spec, workers=workers)
    assert asked == [expected]
