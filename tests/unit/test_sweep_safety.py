"""Sweeps never replace what they must not, and notice changed input files (issue 14 item 5).

Everything here is decided before a cluster starts: the tests forbid starting one."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from test_sweep import BASE  # tests/unit is on sys.path

from viscontact import cli
from viscontact.sweep import plan, runs_dir


@pytest.fixture
def no_cluster(monkeypatch):
    import viscontact.sweep.execute as execute

    def refuse(*args):
        raise AssertionError("a cluster was started")

    monkeypatch.setattr(execute, "cluster_client", refuse)


def _sweep_file(folder: Path, base_text: str = BASE, solver: str = "steady") -> Path:
    """Two speeds of ``base_text``. With a height file or topography in place of the sphere, the
    steady solver refuses the grid of BASE (its steady contact at G(inf) does not fit); the
    transient one (t_end = 0.012 s) accepts it."""
    (folder / "base.toml").write_text(base_text)
    path = folder / "sweep.toml"
    path.write_text(f'base = "base.toml"\nsolver = "{solver}"\n[parameters]\n'
                    '"tangential.sliding_speed" = [0.05, 0.1]\n')
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
    spec = _sweep_file(tmp_path, base, "transient")
    before = [run.fingerprint for run in plan(spec).runs]
    assert [run.fingerprint for run in plan(spec).runs] == before  # the same files: reused
    np.save(heights, (xx**2 + yy**2) / 0.03)  # another indenter, same file name
    after = [run.fingerprint for run in plan(spec).runs]
    assert all(a != b for a, b in zip(after, before))


# --- every file a case reads: in the fingerprint, never an output (red team, files items 2 and 4) -----
SIDE, N = 2 * 1.507e-3, 16  # the BASE grid: 16 x 16 cells of [-1.507, 1.507] mm


def _write_prony(path: Path, g1: float) -> None:
    path.write_text(f"tau,g\ninf,0.193e6\n0.004,{g1!r}\n")


def _write_topography(path: Path, radius: float) -> None:
    """Heights (z up) of a sphere cap of ``radius`` [m] on the BASE grid, as SurfaceTopography writes them."""
    st = pytest.importorskip("SurfaceTopography")
    x = -SIDE / 2 + (np.arange(N) + 0.5) * SIDE / N
    st.Topography(-(x[:, None] ** 2 + x[None, :] ** 2) / (2 * radius), (SIDE, SIDE), unit="m").to_netcdf(str(path))


#: base cases that read a file, the file's name and how to write two versions of it
READERS = {
    "material.file": (BASE.replace('type = "zener"', 'type = "prony"\nfile = "pm.csv"').replace(
        "shear_modulus_instantaneous = 1930000.0\nshear_modulus_long_term = 193000.0\nretardation_time = 0.04\n", ""),
        "pm.csv", lambda path, version: _write_prony(path, (1.737e6, 0.8e6)[version])),
    "indenter.file": (BASE.replace('shape = "sphere"\nradius = 0.01', 'shape = "topography"\nfile = "topo.nc"'),
                      "topo.nc", lambda path, version: _write_topography(path, (0.01, 0.015)[version])),
}


def test_every_key_naming_a_file_is_an_input_file():
    from viscontact.io.case import FILE_KEYS, case_keys

    assert set(FILE_KEYS) == {key for key in case_keys() if key.rsplit(".", 1)[-1] == "file"} == set(READERS)


@pytest.mark.parametrize("key", list(READERS))
def test_a_changed_input_file_makes_its_runs_stale(tmp_path, key):
    """Red team item 2: a new Prony table (or topography) under the same name was reused as if unchanged."""
    base, name, write = READERS[key]
    assert base != BASE
    write(tmp_path / name, 0)
    spec = _sweep_file(tmp_path, base, "transient")
    the_plan = plan(spec)
    assert the_plan.runs[0].case.input_files() == {key: tmp_path / name}
    assert tmp_path / name in the_plan.input_files()
    before = [run.fingerprint for run in the_plan.runs]
    assert [run.fingerprint for run in plan(spec).runs] == before  # the same files: reused
    write(tmp_path / name, 1)  # another material or indenter, same file name
    after = [run.fingerprint for run in plan(spec).runs]
    assert all(a != b for a, b in zip(after, before))


@pytest.mark.parametrize("command", ["run", "steady", "sweep"])
def test_force_never_replaces_a_netcdf_topography_the_case_reads(tmp_path, capsys, no_cluster, command):
    """Red team item 4: a netCDF topography looks like a result file; ``--force`` replaced it."""
    base, name, write = READERS["indenter.file"]
    topography = tmp_path / name
    write(topography, 0)
    spec = _sweep_file(tmp_path, base, "transient")
    before = topography.read_bytes()
    source = spec if command == "sweep" else tmp_path / "base.toml"
    assert cli.main([command, str(source), "--out", str(topography), "--force", "--quiet"]) == 2
    err = _errors(capsys)
    assert len(err) == 1 and f"is the input file {topography}" in err[0]
    assert topography.read_bytes() == before


def test_a_foreign_file_where_a_run_file_goes_is_refused_before_any_run(tmp_path, capsys, no_cluster):
    """A run file is replaced only when it is a result (it used to be a failed run, after computing)."""
    spec = _sweep_file(tmp_path)
    out = tmp_path / "sweep.nc"
    notes = runs_dir(out) / plan(spec).runs[1].name
    notes.parent.mkdir()
    notes.write_text("my notes")
    assert cli.main(["sweep", str(spec), "--out", str(out), "--quiet"]) == 2
    err = _errors(capsys)
    assert len(err) == 1 and str(notes) in err[0] and "not a netCDF result file" in err[0]
    assert notes.read_text() == "my notes" and not out.exists()


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
