"""Scale: seed Table 1 (frictionless sliding at v = 0.8 a0/tau, +-2.56 a0) at 1024^2 for a few steps,
streamed to a result file as ``viscontact run`` does.

    .venv/bin/python benchmarks/bench_scale.py                 # 1024^2, 6 steps (a few minutes)
    .venv/bin/python benchmarks/bench_scale.py --n 512 --steps 10

Prints the time of the first step (it includes building the kernels and their spectra), the time per
later step (median), the peak resident memory of the process, the size of the streamed file, and
the dry-run estimates of ``viscontact.running.resources`` (memory, and run time of the whole 4 tau run) to
compare with.
"""
from __future__ import annotations

import argparse
import platform
import resource
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

import viscontact as vc
from viscontact.running import api
from viscontact.running.resources import estimate

CASE = Path(__file__).resolve().parents[1] / "cases" / "seed_table1_v0.8.toml"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=1024)
    parser.add_argument("--steps", type=int, default=6)
    args = parser.parse_args()

    base = vc.load_case(CASE).with_overrides({"grid.n": args.n})
    full, _ = api.prepare(base)
    dt = full.time.dt
    case = base.with_overrides({"time.t_end": (args.steps - 1) * dt})
    problem, _ = api.prepare(case)
    stamps = [time.perf_counter()]
    with tempfile.TemporaryDirectory() as folder, warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the wake warning of a run stopped after a few steps
        out = Path(folder) / "scale.nc"
        written = api.run_to_file(case, out, progress=lambda done, total: stamps.append(time.perf_counter()))
        size = written.path.stat().st_size
    per_step = np.diff(stamps)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    est_short, est_full = estimate(problem), estimate(full)
    with open("/proc/loadavg") as fh:
        load = fh.read().split()[:3]
    print(f"machine: {platform.machine()}, {platform.python_version()}, numpy {np.__version__}, "
          f"load average {' '.join(load)}")
    print(f"{args.n}^2 frictionless sliding, {problem.time.n_steps} steps of {dt:.3g} s "
          f"(the whole 4 tau run: {full.time.n_steps} steps)")
    print(f"first step (kernels, spectra, first solve): {per_step[0]:.1f} s")
    if per_step.size > 1:
        print(f"later steps: median {np.median(per_step[1:]):.2f} s, min {per_step[1:].min():.2f} s, "
              f"max {per_step[1:].max():.2f} s per step")
    print(f"peak RSS: {peak / 2**20:.0f} MiB (estimate: {est_short.peak_memory_bytes / 2**20:.0f} MiB; "
          f"the whole run: {est_full.peak_memory_bytes / 2**20:.0f} MiB)")
    print(f"streamed result: {size / 2**20:.1f} MiB for {written.records} records")
    seconds = getattr(est_full, "seconds", None)
    if seconds:
        print(f"dry-run estimate of the whole run: {seconds / 60:.1f} min; measured rate x steps: "
              f"{np.median(per_step[1:]) * full.time.n_steps / 60:.1f} min")


if __name__ == "__main__":
    main()
