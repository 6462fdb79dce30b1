"""Sweeps never replace what they must not, and notice changed input files (issue 14 item 5).

Everything here is decided before a cluster starts: the tests forbid starting one."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from test_sweep import BASE  # tests/unit is on sys.path

from viscontact import cli
from viscontact.sweep import plan


@pytest.fixture
def no_cluster(monkeypatch):
    import viscontact.sweep.execute as execute

    def refuse(*args):
        raise AssertionError("a cluster was started")

    monkeypatch.setattr(execute, "cluster_client", refuse)


def _sweep_file(folder: Path, base_text: str = BASE) -> Path:
    (folder / "base.toml").write_text(base_text)
    path = folder / "sweep.toml"
    path.write_text('base = "base.toml"\nsolver = "steady"\n[parameters]\n"tangential.sliding_speed" = [0.05, 0.1]\n')
    return path


def _errors(capsys) -> list[str]:
    return [line for line in capsys.readouterr().err.splitlines() if line.strip()]


def test_existing_result_is_not_replaced_without_force(tmp_path, capsys, no_cluster):
    spec = _sweep_file(tmp_path)
    out = tmp_path / "sweep.nc"
    xr.Dataset({"a": ("t", [1.0])}, attrs={"kind": "sweep", "sweep": "another sweep"}).to_netcdf(out)
    before = out.read_bytes()
    assert cli.main(["sweep", str(spec), "--out", str(out), "--quiet"]) == 2
    err = _errors(capsys)
    assert len(err) == 1 and "--force" in err[0] and str(out) in err[0]
    assert out.read_bytes() == before


@pytest.mark.parametrize("target", ["sweep.toml", "base.toml"])
def test_the_sweep_file_and_its_base_case_are_never_replaced(tmp_path, capsys, no_cluster, target):
    spec = _sweep_file(tmp_path)
    before = (tmp_path / target).read_bytes()
    link = tmp_path / "link.nc"  # a result must be named *.nc: the input file is reached through a link
    link.symlink_to(tmp_path / target)
    assert cli.main(["sweep", str(spec), "--out", str(link), "--force", "--quiet"]) == 2
    err = _errors(capsys)
    assert len(err) == 1 and "input file" in err[0]
    assert (tmp_path / target).read_bytes() == before


def test_a_changed_height_file_makes_its_runs_stale(tmp_path):
    x = -1.507e-3 + (np.arange(16) + 0.5) * 2 * 1.507e-3 / 16
    xx, yy = np.meshgrid(x, x)
    heights = tmp_path / "h.npy"
    np.save(heights, (xx**2 + yy**2) / 0.02)
    base = BASE.replace('shape = "sphere"\nradius = 0.01', 'shape = "surface"\nfile = "h.npy"')
    assert base != BASE
    spec = _sweep_file(tmp_path, base)
    before = [run.fingerprint for run in plan(spec).runs]
    assert [run.fingerprint for run in plan(spec).runs] == before  # the same files: reused
    np.save(heights, (xx**2 + yy**2) / 0.03)  # another indenter, same file name
    after = [run.fingerprint for run in plan(spec).runs]
    assert all(a != b for a, b in zip(after, before))


def test_a_sweep_whose_output_another_process_writes_is_refused(tmp_path, capsys, no_cluster):
    """Two sweeps on the same SWEEP.nc would replace each other's run files and result: the second
    is refused in one line naming the process, before any run (output_files.output_lock)."""
    import os
    import subprocess
    import sys

    from test_output_safety import HOLD_LOCK

    spec, out = _sweep_file(tmp_path), tmp_path / "sweep.nc"
    holder = subprocess.Popen([sys.executable, "-c", HOLD_LOCK, str(out)], stdout=subprocess.PIPE, text=True,
                              env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)})
    try:
        assert holder.stdout.readline().strip() == "locked"
        assert cli.main(["sweep", str(spec), "--out", str(out), "--force", "--quiet"]) == 2
        err = _errors(capsys)
        assert len(err) == 1 and f"another viscontact process (pid {holder.pid})" in err[0] and str(out) in err[0]
        assert not out.exists() and not (tmp_path / "sweep.runs").exists()
    finally:
        holder.kill()
        holder.wait()
