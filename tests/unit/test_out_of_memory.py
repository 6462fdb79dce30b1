"""Running out of memory: refused before the first step where the estimate foresees it, one line and
status 2 where it happens mid-run, the steps done kept valid on disk.

* mid-run on the CPU (an allocation of step 3 raises numpy's ``MemoryError``) and on the emulated
  device (CuPy's ``OutOfMemoryError``, a ``MemoryError``): ``viscontact run`` prints one line naming
  what ran out and where the steps done are, exits 2, and the result holds exactly those steps, equal
  to an uninterrupted run's (``complete = 0``, ``stopped_by`` the error's type); the checkpoint written
  before resumes the run to the uninterrupted result;
* the device's free memory below the run's arrays (``Estimate.device_bytes``): refused before anything
  is written, one line naming ``grid.n``; ``--force`` runs it;
* a CuPy whose FFT fails (a stand-in CuPy in a subprocess: its device count is 1, its ``rfft2``
  raises as a missing cuFFT library does): one line naming ``solver.device`` and cuFFT, status 2,
  nothing written.
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from test_device_paths import gpu  # noqa: F401 - the fixture: solver.device = "gpu" on the emulated device

from viscontact import cli
from viscontact.io.case import load_case
from viscontact.numerics import arrays
from viscontact.running import resources
from viscontact.solvers import transient

ROOT = Path(__file__).resolve().parents[2]
CREEP = ROOT / "src" / "viscontact" / "cases" / "creep_indentation.toml"
SMALL = ["--set", "grid.n=32", "--set", "time.t_end=0.0015", "--quiet"]  # 7 steps


class OutOfMemoryError(MemoryError):
    """CuPy's ``cupy.cuda.memory.OutOfMemoryError`` (a ``MemoryError``), as it words itself."""

    def __init__(self, size: int) -> None:
        super().__init__(f"Out of memory allocating {size:,} bytes (allocated so far: 0 bytes).")


def _failing_at(monkeypatch, k: int, error: MemoryError) -> None:
    """Step ``k`` (0-based) raises ``error`` from an allocation inside it (its known displacement)."""
    step = transient.step

    def failing(problem, compliance, state, *args, **kwargs):
        if state.step + 1 == k:
            raise error
        return step(problem, compliance, state, *args, **kwargs)

    monkeypatch.setattr(transient, "step", failing)


@pytest.mark.usefixtures("gpu")
@pytest.mark.filterwarnings("ignore::viscontact.errors.ViscontactWarning")
@pytest.mark.parametrize("device", ["cpu", "gpu"])
def test_memory_error_mid_run_is_one_line_exit_2_with_the_steps_done_kept(device, monkeypatch, tmp_path, capsys):
    sets = [*SMALL, "--set", f'solver.device="{device}"']
    reference = tmp_path / "reference.nc"
    assert cli.main(["run", str(CREEP), "--out", str(reference), *sets]) == 0
    capsys.readouterr()
    error = MemoryError() if device == "cpu" else OutOfMemoryError(8 * 2**30)
    with monkeypatch.context() as patch:
        _failing_at(patch, 3, error)
        out = tmp_path / "r.nc"
        assert cli.main(["run", str(CREEP), "--out", str(out), "--checkpoint-every", "2", *sets]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("viscontact: error: out of memory"), err
    assert "grid.n" in err[0] and f"the 3 records done are in {out}" in err[0]
    if device == "gpu":
        assert "Out of memory allocating 8,589,934,592 bytes" in err[0]
    with xr.open_dataset(out, engine="h5netcdf") as ds, xr.open_dataset(reference, engine="h5netcdf") as ref:
        assert ds.attrs["complete"] == 0 and ds.attrs["stopped_by"] == type(error).__name__
        assert ds.sizes["t"] == 3
        assert np.array_equal(ds["pressure"].values, ref["pressure"].values[:3])
        assert np.array_equal(ds["load"].values, ref["load"].values[:3])
    # the checkpoint written before (after step 2) resumes the run to the uninterrupted result
    assert cli.main(["run", str(CREEP), "--out", str(out), "--resume", *sets]) == 0
    with xr.open_dataset(out, engine="h5netcdf") as ds, xr.open_dataset(reference, engine="h5netcdf") as ref:
        assert ds.attrs["complete"] == 1 and ds.sizes["t"] == ref.sizes["t"]
        assert np.array_equal(ds["pressure"].values, ref["pressure"].values)


@pytest.mark.usefixtures("gpu")
def test_device_memory_too_small_is_refused_before_the_first_step(monkeypatch, tmp_path, capsys):
    monkeypatch.setattr(arrays, "device_free_memory", lambda: 2**16)
    out = tmp_path / "r.nc"
    sets = [*SMALL, "--set", 'solver.device="gpu"']
    assert cli.main(["run", str(CREEP), "--out", str(out), *sets]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("viscontact: error: grid.n: the run may need about"), err
    assert "of GPU memory, 64 KiB is free on the device" in err[0] and "--force" in err[0]
    assert not list(tmp_path.iterdir())
    # its estimate: the solver's arrays, below the process's peak, above what 32^2 fields take
    problem = load_case(CREEP).with_overrides({"grid.n": 32, "solver.device": "gpu"}).to_problem()
    est = resources.estimate(problem, transform=1e-3)
    assert 16 * 8 * 32 * 32 < est.device_bytes < est.peak_memory_bytes - resources.BASE_MEMORY
    loud = [s for s in sets if s != "--quiet"]
    assert cli.main(["run", str(CREEP), "--out", str(out), "--force", *loud]) == 0
    assert "of GPU memory, 64 KiB is free on the device" in capsys.readouterr().err and out.exists()


def test_a_cupy_whose_fft_fails_is_one_line_and_exit_2(tmp_path):
    fake = tmp_path / "fake"
    (fake / "cupyx" / "scipy").mkdir(parents=True)
    (fake / "cupy").mkdir()
    (fake / "cupy" / "__init__.py").write_text(
        "import numpy\n"
        "class _Runtime:\n"
        "    @staticmethod\n"
        "    def getDeviceCount():\n"
        "        return 1\n"
        "class cuda:\n"
        "    runtime = _Runtime\n"
        "zeros = numpy.zeros\n")
    for package in ("cupyx", "cupyx/scipy"):
        (fake / package / "__init__.py").write_text("")
    (fake / "cupyx" / "scipy" / "fft.py").write_text(
        "def rfft2(x, *args, **kwargs):\n"
        "    raise RuntimeError('CuFFTError: libcufft.so.12: cannot open shared object file:\\n"
        "No such file or directory')\n")
    out_file = tmp_path / "r.nc"
    out = subprocess.run([sys.executable, "-m", "viscontact", "run", str(CREEP), "--out", str(out_file),
                          "--set", 'solver.device="gpu"', "--set", "grid.n=512"],
                         env={**os.environ, "PYTHONPATH": os.pathsep.join(
                             [str(fake), str(ROOT / "src"), os.environ.get("PYTHONPATH", "")])},
                         capture_output=True, text=True, timeout=120, check=False)
    lines = out.stderr.strip().splitlines()
    assert out.returncode == 2 and len(lines) == 1, out.stderr
    assert lines[0].startswith("viscontact: error: solver.device: 'gpu' needs CuPy and a CUDA device (CuPy's FFT "
                               "(cuFFT) does not work: CuFFTError: libcufft.so.12: cannot open shared object file: "
                               "No such file or directory)"), lines
    assert not out_file.exists() and not list(tmp_path.glob("r.nc*"))
