"""How good is the peak memory that ``viscontact run --dry-run`` prints? ``viscontact run`` (streamed,
the case's own output) of a few shipped cases at a few grids, each in a fresh process, its own peak
resident memory (VmHWM of /proc/self/status) against :func:`viscontact.running.resources.estimate`.

    .venv/bin/python benchmarks/bench_memory.py                          # 128^2 .. 1024^2, 6 steps
    .venv/bin/python benchmarks/bench_memory.py --sizes 512 --steps 6,41  # memory against the steps

Columns: the case, its grid and steps, the measured peak RSS, the estimate, and estimate / measured
(above 1: an upper bound, as it should be).
"""
from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CASES = ("creep_indentation", "seed_table1_v0.8", "rough_periodic_sliding")


def child(argv: list[str]) -> None:
    """``viscontact run`` with ``argv``, then this process's VmHWM and the estimate [bytes] on stdout's
    last line (the estimate made in the run's process, as ``viscontact run`` makes it: after the case's
    own imports)."""
    from viscontact import cli
    from viscontact.running import resources

    made = []
    check = resources.check_resources

    def spy(*args, **kwargs):
        made.append(check(*args, **kwargs))
        return made[-1]

    resources.check_resources = spy
    try:
        cli.main(argv)
    finally:
        with open("/proc/self/status") as fh:
            peak = next(int(line.split()[1]) for line in fh if line.startswith("VmHWM:"))
        print(peak * 1024, made[-1].peak_memory_bytes if made else 0, flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", default="128,256,512,1024", help="grids (comma-separated)")
    ap.add_argument("--steps", default="6", help="steps of each run (comma-separated: one row each)")
    ap.add_argument("--cases", default=",".join(CASES), help="shipped cases (comma-separated)")
    ap.add_argument("--child", nargs=argparse.REMAINDER, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child is not None:
        child(args.child)
        return

    from viscontact.running import api
    from viscontact.io.case import load_case

    print(f"# --dry-run's peak memory against viscontact run, {platform.processor() or platform.machine()}, "
          f"{os.cpu_count()} cores, {time.strftime('%Y-%m-%d %H:%M')}, load {os.getloadavg()[0]:.1f}")
    print("| case | n | steps | measured [MiB] | estimate [MiB] | estimate / measured |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        for name in args.cases.split(","):
            for n in map(int, args.sizes.split(",")):
                for steps in map(int, args.steps.split(",")):
                    path = ROOT / "cases" / f"{name}.toml"
                    case = load_case(path).with_overrides({"grid.n": n})
                    dt = api.prepare(case)[0].time.dt
                    t_end = (steps - 1) * dt
                    out = str(Path(folder) / "r.nc")
                    run = subprocess.run(
                        [sys.executable, __file__, "--child", "run", str(path), "--out", out, "--force", "--quiet",
                         "--set", f"grid.n={n}", "--set", f"time.t_end={t_end!r}", "--set", f"time.dt={dt!r}"],
                        capture_output=True, text=True)
                    if run.returncode:
                        sys.exit(run.stderr)
                    peak, est = map(int, run.stdout.strip().splitlines()[-1].split())
                    print(f"| {name} | {n} | {steps} | {peak / 2**20:.0f} | {est / 2**20:.0f} | "
                          f"{est / peak:.2f} |", flush=True)


if __name__ == "__main__":
    main()
