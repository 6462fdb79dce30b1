"""The user's paths with ``solver.device = "gpu"``, on the emulated device.

``solver.device = "gpu"`` is made to mean the emulated device (tests/emulated_device.py: numpy behind
CuPy's rules, a host array leaking into the device path raises) with the GPU backend's window sides
(:func:`viscontact.arrays.device_fast_length`): :func:`viscontact.arrays.cupy_backend` returns it, and
``SolverSettings``' check that CuPy is installed finds it. The command line runs in this process
(``cli.main``), so the substitution holds there too.
"""
from __future__ import annotations

import dataclasses
import importlib.util
from pathlib import Path

import numpy as np
import pytest

import emulated_device
from viscontact import arrays, cli
from viscontact.errors import ParameterError
from viscontact.problem import SolverSettings

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
    run (only the run's substrate refused it); now every command refuses it with the case, one line
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
