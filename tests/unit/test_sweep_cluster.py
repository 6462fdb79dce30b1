"""A sweep on an existing dask cluster (``viscontact sweep --scheduler``): a scheduler and a worker
started as separate processes on the loopback interface, as on a cluster (docs/cluster.md), give the
same sweep as the local cluster."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from test_sweep import write_sweep

pytestmark = pytest.mark.timeout(240)
DASK = Path(sys.executable).with_name("dask")


@pytest.fixture()
def scheduler(tmp_path):
    """The address of a dask scheduler with one worker, each its own process (loopback only)."""
    if not DASK.exists():
        pytest.skip("the dask command line is not installed")
    info = tmp_path / "scheduler.json"
    env = {**os.environ, "DASK_DISTRIBUTED__WORKER__DAEMON": "false"}
    procs = [subprocess.Popen([str(DASK), "scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                               "--scheduler-file", str(info)], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)]
    try:
        deadline = time.monotonic() + 60
        while not info.exists() or not info.read_text().strip():
            assert time.monotonic() < deadline and procs[0].poll() is None, "the scheduler did not start"
            time.sleep(0.1)
        address = json.loads(info.read_text())["address"]
        procs.append(subprocess.Popen([str(DASK), "worker", address, "--nworkers", "1", "--nthreads", "1",
                                       "--no-dashboard", "--host", "127.0.0.1"], env=env,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        yield address
    finally:
        for proc in reversed(procs):
            proc.terminate()
        for proc in reversed(procs):
            try:
                proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                proc.kill()


def test_a_sweep_on_an_existing_scheduler_equals_the_local_one(tmp_path, scheduler):
    """``viscontact sweep --scheduler ADDRESS``: the worker process writes the run files, the command
    assembles them; mu_app of every run equals that of the same sweep on a local cluster, and the
    second command reuses every run."""
    remote, local = tmp_path / "remote", tmp_path / "local"
    remote.mkdir(), local.mkdir()
    command = [sys.executable, "-m", "viscontact", "sweep"]
    out = subprocess.run([*command, str(write_sweep(remote)), "--out", str(remote / "sweep.nc"), "--scheduler",
                          scheduler], capture_output=True, text=True, timeout=200)
    assert out.returncode == 0, out.stderr
    assert "4 computed" in out.stdout, out.stdout
    assert len(list((remote / "sweep.runs").glob("*.nc"))) == 4
    distributed = pytest.importorskip("distributed")
    with distributed.Client(scheduler, timeout=30) as client:  # the runs were this scheduler's tasks
        prefixes = client.run_on_scheduler(lambda dask_scheduler: {
            name: sum(prefix.state_counts.values()) for name, prefix in dask_scheduler.task_prefixes.items()})
    assert prefixes.get("viscontact-sweep", 0) >= 4, prefixes
    again = subprocess.run([*command, str(remote / "sweep.toml"), "--out", str(remote / "sweep.nc"), "--scheduler",
                            scheduler], capture_output=True, text=True, timeout=200)
    assert again.returncode == 0 and "0 computed, 4 reused" in again.stdout, again.stdout + again.stderr
    here = subprocess.run([*command, str(write_sweep(local)), "--out", str(local / "sweep.nc"), "--workers", "1"],
                          capture_output=True, text=True, timeout=200)
    assert here.returncode == 0, here.stderr
    with xr.open_dataset(remote / "sweep.nc") as a, xr.open_dataset(local / "sweep.nc") as b:
        np.testing.assert_array_equal(a["mu_app"].values, b["mu_app"].values)
