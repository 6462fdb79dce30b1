"""Wall time of a sweep on local dask clusters of 1, 2, ... worker processes.

Runs the example sweep ``cases/sweeps/steady_mu_app_vs_speed.toml`` (24 steady solves on a 64 x 64
grid) once in this process, one case after the other (no dask), then with :func:`viscontact.sweep.sweep`
on a ``LocalCluster`` of each worker count (one thread each, solver FFT workers = 1). The cluster's
start-up is timed apart from the sweep. Nothing is written (``out=None``), so nothing is reused.

    .venv/bin/python benchmarks/bench_sweep.py [--workers 1,2] [--sweep FILE] [--set grid.n=32]

Prints a table: workers, cluster start [s], sweep wall time [s], speed-up over one worker,
parallel efficiency, and the largest difference of mu_app from the serial run (must be 0).
"""
from __future__ import annotations

import argparse
import os
import platform
import time
import warnings
from pathlib import Path

import numpy as np
import tomllib

from viscontact.running import api
from viscontact.errors import ViscontactWarning
from viscontact.sweep import default_workers, load_sweep, local_cluster, plan, sweep

ROOT = Path(__file__).resolve().parents[1]
DEFAULT = ROOT / "cases" / "sweeps" / "steady_mu_app_vs_speed.toml"


def serial(the_plan) -> tuple[float, np.ndarray]:
    """All runs in this process, one after the other; (wall time, mu_app in plan order)."""
    started = time.perf_counter()
    solve = api.run_steady if the_plan.spec.solver == "steady" else api.run
    mu = [float(solve(run.case)["mu_app"][-1]) for run in the_plan.runs]
    return time.perf_counter() - started, np.array(mu)


def distributed(spec, workers: int) -> tuple[float, float, np.ndarray]:
    """(cluster start-up [s], sweep wall time [s], mu_app in plan order) on ``workers`` processes."""
    from distributed import Client

    started = time.perf_counter()
    with local_cluster(workers) as cluster, Client(cluster) as client:
        client.wait_for_workers(workers)
        startup = time.perf_counter() - started
        started = time.perf_counter()
        ds = sweep(spec, client=client)
        wall = time.perf_counter() - started
    return startup, wall, ds["mu_app"].values.reshape(-1)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sweep", default=str(DEFAULT), help="sweep file (default: the example sweep)")
    parser.add_argument("--workers", default="1,2", help="comma-separated worker counts (default 1,2)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="fix a case key for every run, e.g. --set grid.n=32 (repeatable)")
    parser.add_argument("--no-serial", action="store_true", help="skip the in-process serial run")
    args = parser.parse_args()
    counts = [int(w) for w in args.workers.split(",")]
    spec = load_sweep(args.sweep)
    fixed = {k: tomllib.loads(f"v = {v}")["v"] for k, _, v in (s.partition("=") for s in args.set)}
    spec = type(spec)(**{**spec.__dict__, "overrides": {**spec.overrides, **fixed}})
    the_plan = plan(spec, fixed={"solver.workers": 1})
    warnings.simplefilter("ignore", ViscontactWarning)

    print(f"# {Path(args.sweep).name}: {len(the_plan.runs)} {spec.solver} runs, grid n = "
          f"{the_plan.runs[0].case.grid.n}; {platform.processor() or platform.machine()}, "
          f"{default_workers()} cores available, load average {os.getloadavg()[0]:.1f}")
    reference = None
    if not args.no_serial:
        wall, reference = serial(the_plan)
        print(f"serial, in process (no dask): {wall:.1f} s ({wall / len(the_plan.runs):.2f} s per run)")
    print(f"{'workers':>7} {'start [s]':>9} {'sweep [s]':>9} {'speed-up':>8} {'efficiency':>10} {'max |dmu|':>10}")
    one = None
    for n in counts:
        startup, wall, mu = distributed(spec, n)
        one = one or (wall * n if n != 1 else wall)  # the 1-worker time (estimated if 1 is not run first)
        diff = float(np.nanmax(np.abs(mu - reference))) if reference is not None else float("nan")
        print(f"{n:>7} {startup:>9.1f} {wall:>9.1f} {one / wall:>8.2f} {one / wall / n:>10.2f} {diff:>10.1e}")


if __name__ == "__main__":
    main()
