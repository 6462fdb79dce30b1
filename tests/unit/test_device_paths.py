"""The user's paths with ``solver.device = "gpu"``, on the emulated device.

``solver.device = "gpu"`` is made to mean the emulated device (tests/emulated_device.py: numpy behind
CuPy's rules, a host array leaking into the device path raises) with the GPU backend's window sides
(:func:`viscontact.numerics.arrays.device_fast_length`): :func:`viscontact.numerics.arrays.cupy_backend` returns it, and
the run's check that CuPy is installed (:func:`viscontact.numerics.arrays.array_backend`) finds it. The command line runs in this process
(``cli.main``), so the substitution holds there too.
"""
from __future__ import annotations

import dataclasses
import importlib.util
from pathlib import Path

import numpy as np
import pytest

import emulated_device
from viscontact import cli
from viscontact.numerics import arrays
from viscontact.errors import ParameterError
from viscontact.problem.problem import SolverSettings

ROOT = Path(__file__).resolve().parents[2]
CASES = ROOT / "cases"
GPU = ['--set', 'solver.device="gpu"']
CPU = ['--set', 'solver.device="cpu"']


@pytest.fixture
def gpu(monkeypatch):
    """``solver.device = "gpu"`` on the emulated device with the GPU's window sides (returned)."""
    backend = dataclasses.replace(emulated_device.BACKEND, fast_length=arrays.device_fast_length)
    monkeypatch.setattr(arrays, "cupy_backend", lambda: backend)
    find_spec = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a, **k: find_spec("numpy") if name == "cupy" else find_spec(name, *a, **k))
    return backend


# --- the reference hereditary sum: refused with the case, by --dry-run too -------------------------

@pytest.mark.parametrize("command", ["run", "dry-run", "steady"])
def test_the_reference_sum_on_a_gpu_is_one_line_before_anything_is_written(gpu, tmp_path, capsys, command):
    """``solver.history = "direct"`` with ``solver.device = "gpu"``: ``--dry-run`` said the case would
    run (only the run's compliance refused it); now every command refuses it with the case, one line
    naming the key, status 2, nothing written."""
    out = tmp_path / "r.nc"
    argv = (["steady", str(CASES / "seed_table1_v0.8.toml")] if command == "steady" else
            ["run", str(CASES / "creep_indentation.toml"), *(["--dry-run"] if command == "dry-run" else [])])
    assert cli.main([*argv, "--out", str(out), "--set", "grid.n=32", *GPU,
                     "--set", 'solver.history="direct"']) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert lines[-1].startswith("viscontact: error: solver.history: 'direct' (the reference sum) runs on the "
                                "CPU only"), lines
    assert not list(tmp_path.iterdir())
    with pytest.raises(ParameterError) as err:
        SolverSettings(device="gpu", history="direct")
    assert err.value.key == "solver.history"


# --- a checkpoint resumes on the other device ------------------------------------------------------

def _stopped_run(case, out: Path, after: int) -> None:
    """``viscontact run --checkpoint-every 3`` of ``case`` stopped after ``after`` steps (as by SIGINT)."""
    from viscontact.running import api
    from viscontact.errors import RunInterrupted

    done: list[int] = []
    with pytest.raises(RunInterrupted):
        api.run_to_file(case, out, checkpoint_every=3, progress=lambda k, total: done.append(k),
                        should_stop=lambda: "SIGINT" if len(done) >= after else None)


@pytest.mark.filterwarnings("ignore::viscontact.errors.ViscontactWarning")  # small grids on the "gpu", a wake
@pytest.mark.parametrize("devices", [("cpu", "gpu"), ("gpu", "cpu")])
@pytest.mark.parametrize("name, sets", [("seed_table1_v0.8", {"grid.n": 32, "tangential.steps_per_cell": 4}),
                                        ("fretting_zener", {"grid.n": 32}),
                                        ("adhesive_pdms_retraction", {"grid.n": 32})])
def test_a_run_checkpointed_on_one_device_resumes_on_the_other(gpu, monkeypatch, tmp_path, capsys, devices,
                                                               name, sets):
    """``--resume`` with the other ``solver.device`` than the run that wrote the checkpoint was refused
    as "written for a different case or output settings" (the device was in the fingerprint), which
    left a run checkpointed on a GPU that is gone no way on. It resumes: sliding (the wake's columns
    on the host, the histories shifted), fretting (the incremental slip) and adhesion (the interaction
    zone; its pull-off attributes), on the emulation with
    the CPU's window sides equal to the uninterrupted CPU run bit for bit."""
    import xarray as xr

    from viscontact.running import api
    from viscontact.io.case import load_case
    from viscontact.io.shipped import shipped_case

    monkeypatch.setattr(arrays, "cupy_backend", lambda: emulated_device.BACKEND)  # numpy's windows: bit for bit
    case = load_case(shipped_case(name)).with_overrides(sets)
    first, then = devices
    api.run_to_file(case.with_overrides({"solver.device": "cpu"}), tmp_path / "whole.nc")
    out = tmp_path / "r.nc"
    _stopped_run(case.with_overrides({"solver.device": first}), out, 30)
    with np.load(api.checkpoint_path(out)) as saved:
        assert ("state.pressure.__device__" in saved.files) == (first == "gpu")
        assert name != "seed_table1_v0.8" or "state.wake.strips.0" in saved.files  # the wake is in it
    capsys.readouterr()
    assert cli.main(["run", str(shipped_case(name)), "--out", str(out), "--resume", "--quiet",
                     *[a for k, v in sets.items() for a in ("--set", f"{k}={v}")],
                     "--set", f'solver.device="{then}"']) == 0, capsys.readouterr().err
    assert not api.checkpoint_path(out).exists()
    with xr.open_dataset(tmp_path / "whole.nc") as whole, xr.open_dataset(out) as resumed:
        assert resumed.attrs["complete"] == 1 and resumed.sizes == whole.sizes and "resumed" in resumed.attrs["history"]
        for var in whole.data_vars:
            np.testing.assert_array_equal(resumed[var].values, whole[var].values, err_msg=var)
        if "pull_off_force" in whole.attrs:
            assert resumed.attrs["pull_off_force"] == whole.attrs["pull_off_force"] < 0


# --- the resource checks: the CPU run's estimates refuse no GPU run ---------------------------------

def test_the_cpu_runs_memory_and_time_estimates_only_warn_on_a_gpu(gpu, tmp_path, capsys, monkeypatch):
    """A GPU run was refused with the CPU run's run time ("would take about ...") and host memory,
    neither its own (the GPU is 5-11 times faster from 1024^2, its fields in device memory): the only
    way on was --force, which also drops the disk claim. With the device they warn, saying whose they
    are; the CPU run is still refused."""
    from viscontact.running import resources

    out = tmp_path / "r.nc"
    creep = [str(CASES / "creep_indentation.toml"), "--out", str(out), "--set", "grid.n=32"]
    monkeypatch.setattr(resources, "MAX_RUN_SECONDS", 1e-3)
    monkeypatch.setattr(resources, "available_memory", lambda: 2**10)
    assert cli.main(["run", *creep, "--dry-run", *CPU]) == 2
    assert "error: grid.n:" in capsys.readouterr().err
    assert cli.main(["run", *creep, "--dry-run", *GPU]) == 0
    err = capsys.readouterr().err
    for key in ("grid.n", "time.t_end"):
        assert f"warning: {key}:" in err and "the CPU run's estimate: solver.device = 'gpu' runs it" in err
    assert cli.main(["run", *creep, "--quiet", *GPU]) == 0 and out.exists()


# --- the settings describe, the run decides: a GPU case anywhere, its run refused where it cannot run ----

@pytest.fixture
def no_cupy(monkeypatch):
    """A machine without CuPy, whether or not this one has it."""
    find_spec = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a, **k: None if name == "cupy" else
                        find_spec(name, *a, **k))


def test_a_gpu_case_loads_validates_estimates_and_fingerprints_without_cupy(no_cupy):
    """``solver.device = "gpu"`` describes the run: on a machine without CuPy the case loads, becomes a
    problem that passes the guards and the solver's checks, is estimated and fingerprinted (a sweep's
    plan, a laptop's estimate); only the machine's check refuses it, naming the extra to install."""
    from viscontact.io.case import load_case
    from viscontact.io.checkpoint import problem_fingerprint
    from viscontact.running.preflight import check_machine, preflight
    from viscontact.running.resources import estimate

    case = load_case(CASES / "creep_indentation.toml").with_overrides({"solver.device": "gpu", "grid.n": 512})
    checked = preflight(case, machine=False)
    problem = checked.problem
    assert problem.solver.device == "gpu" and checked.text == case.text
    assert estimate(problem).result_bytes > 0
    cpu = dataclasses.replace(problem, solver=dataclasses.replace(problem.solver, device="cpu"))
    assert problem_fingerprint(problem) == problem_fingerprint(cpu)  # the device shapes no result
    with pytest.raises(ParameterError) as err:
        check_machine(problem)
    assert err.value.key == "solver.device" and "viscontact[gpu]" in err.value.message


@pytest.mark.parametrize("dry_run", [False, True])
def test_a_gpu_run_without_cupy_is_one_line_and_exit_2_before_anything_is_written(no_cupy, tmp_path, capsys, dry_run):
    """The refusal moved from the case's loading to the run's start: ``viscontact run`` and its
    ``--dry-run`` (the run would be refused on this machine) still stop with the one line naming the
    key and the extra, status 2, nothing written."""
    out = tmp_path / "r.nc"
    assert cli.main(["run", str(CASES / "creep_indentation.toml"), "--out", str(out), *GPU, "--set", "grid.n=512",
                     *(["--dry-run"] if dry_run else [])]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("viscontact: error: solver.device: 'gpu' needs the optional "
                                                   "package CuPy"), lines
    assert "viscontact[gpu]" in lines[0] and not list(tmp_path.iterdir())
