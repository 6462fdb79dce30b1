"""How good is the run time that ``viscontact run --dry-run`` prints? The shipped cases, each run as
``viscontact run`` does it (``run_to_file``, a fresh process), against the estimate of
:func:`viscontact.running.resources.estimate`.

    .venv/bin/python benchmarks/bench_estimate.py              # the cases at 128^2 (the small ones as shipped)
    .venv/bin/python benchmarks/bench_estimate.py --n 256      # the seed cases at 256^2
    .venv/bin/python benchmarks/bench_estimate.py --cases creep_indentation,seed_table3_case4

Columns: the case and its grid, steps and tangential mode; the estimate; the measured wall time of the
process (imports included), split into the start (imports, kernels, result layout: up to the first
step's end, less one step) and the steps (their median time); the transform pair timed for the estimate
(:func:`viscontact.running.resources.transform_seconds`); the measured step, less its mode's ``STEP_SECONDS``, in
transform pairs, which is what a mode's counts (``FULL_TRANSFORMS`` + ``WINDOW_TRANSFORMS`` x the window's share) should give; and measured / estimated.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: the shipped cases measured by default: True sets the case's grid to --n, False runs it as shipped
DEFAULT_CASES = {
    "creep_indentation": True, "relaxation_indentation": True, "coating_layer_creep": False,
    "creep_subsurface_stress": False, "pmma_master_curve": False, "pu_elastomer_master_curve": False,
    "rough_periodic_sliding": False, "seed_fig10_case1": True, "seed_fig10_case2": True, "seed_fig10_case3": True,
    "seed_table1_v0.8": True, "seed_table2_ratio10_displacement": False, "seed_table3_case1": False,
    "seed_table3_case2": False, "seed_table3_case3": False, "seed_table3_case4": False,
}


def child(case: str, n: int | None, out: str) -> None:
    """Run one case as ``viscontact run`` does and print its timings as JSON (the process's own)."""
    start = time.perf_counter()
    import warnings

    import numpy as np

    import viscontact as vc
    from viscontact.io.case import load_case

    imported = time.perf_counter()
    loaded = load_case(ROOT / "cases" / f"{case}.toml")
    if n is not None:
        loaded = loaded.with_overrides({"grid.n": n})
    problem = loaded.to_problem()
    stamps: list[float] = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        vc.run_to_file(loaded, out, progress=lambda done, total: stamps.append(time.perf_counter()))
    end = time.perf_counter()
    steps = np.diff(stamps)
    step = float(np.median(steps)) if steps.size else end - imported
    print(json.dumps({"imports": imported - start, "start": stamps[0] - imported - step, "step": step,
                      "steps": len(stamps), "wall": end - start, "n": problem.grid.n,
                      "mode": problem.tangential.mode}))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=128, help="grid of the cases run at a set size (default 128)")
    ap.add_argument("--cases", default="", help="comma-separated case names (default: the list in the script)")
    ap.add_argument("--child", nargs=3, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        case, n, out = args.child
        child(case, None if n == "-" else int(n), out)
        return

    from viscontact.io.case import load_case
    from viscontact.running.resources import STEP_SECONDS, estimate, transform_seconds

    names = args.cases.split(",") if args.cases else list(DEFAULT_CASES)
    print(f"# --dry-run's run time against viscontact run, {platform.processor() or platform.machine()}, "
          f"{os.cpu_count()} cores, Python {platform.python_version()}, {time.strftime('%Y-%m-%d %H:%M')}, "
          f"load {os.getloadavg()[0]:.1f}")
    print("| case | n | steps | mode | estimate [s] | measured [s] | start [s] | a step [ms] | pair [ms] | step in pairs | measured / estimate |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        for name in names:
            sized = DEFAULT_CASES.get(name, True)
            case = load_case(ROOT / "cases" / f"{name}.toml")
            if sized:
                case = case.with_overrides({"grid.n": args.n})
            problem = case.to_problem()
            pair = transform_seconds(problem)
            est = estimate(problem).seconds
            out = str(Path(folder) / f"{name}.nc")
            run = subprocess.run([sys.executable, __file__, "--child", name, str(args.n) if sized else "-", out],
                                 capture_output=True, text=True, check=True)
            m = json.loads(run.stdout.strip().splitlines()[-1])
            n = m["n"]
            print(f"| {name} | {n} | {m['steps']} | {m['mode']} | {est:.1f} | {m['wall']:.1f} | "
                  f"{m['imports'] + m['start']:.1f} | {1e3 * m['step']:.1f} | {1e3 * pair:.2f} | "
                  f"{(m['step'] - STEP_SECONDS[m['mode']]) / pair:.1f} | "
                  f"{m['wall'] / est:.2f} |", flush=True)
            os.remove(out)


if __name__ == "__main__":
    main()
