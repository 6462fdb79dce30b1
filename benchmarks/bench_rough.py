"""Rough periodic benchmark: prints a table of wall time and iterations per step.

    .venv/bin/python benchmarks/bench_rough.py             # 512^2 x 400 steps (issue 11's target)
    .venv/bin/python benchmarks/bench_rough.py --n 128     # quicker

The shipped case ``cases/rough_periodic_sliding.toml`` (Zener elastomer, G(0) = 1.93 MPa, periodic
self-affine surface H = 0.8, h'_rms = 0.1, period 1 mm, W = 10 mN) in frictionless sliding at
20 mm/s from t = 0, one cell of sliding per step, ``--steps`` steps. Rows: the kernel build (periodic
influence coefficients by the Ewald split, once per grid), the transient (time per step, constrained-CG
iterations per step), and the exact periodic steady state at the same speed for comparison of mu_app.
The system load average at the start and the end is printed: wall times on a loaded machine are
longer; the process CPU time (all FFT threads) is less sensitive to the load.

Two source trees alternated on this case: ``bench_iterations.py --case rough_periodic_sliding --set
tangential.mode=frictionless_sliding``.
"""
from __future__ import annotations

import argparse
import os
import platform
import time
import warnings
from pathlib import Path

import numpy as np

from viscontact.solvers import transient
from viscontact.io.case import load_case
from viscontact.physics.periodic import periodic_influence_coefficients
from viscontact.solvers.steady import solve_steady

CASE = Path(__file__).resolve().parents[1] / "cases" / "rough_periodic_sliding.toml"


def rough_problem(n: int, steps: int, mode: str = "frictionless_sliding"):
    """The shipped rough case at n^2 sliding from t = 0 in ``mode`` (``"gross_sliding"``: with its
    friction, mu_f = 0.5), one cell per step, ``steps`` steps."""
    case = load_case(CASE)
    dt = 2 * case.grid.half_width / n / case.tangential.sliding_speed
    return case.with_overrides({"grid.n": n, "tangential.mode": mode,
                                "time.t_end": (steps - 0.5) * dt, "output.fields": []}).to_problem()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=512, help="cells per side (default 512)")
    parser.add_argument("--steps", type=int, default=400, help="time steps (default 400)")
    parser.add_argument("--no-steady", action="store_true", help="skip the steady-state row")
    args = parser.parse_args()

    load_start = os.getloadavg()[0]
    problem = rough_problem(args.n, args.steps)

    start = time.perf_counter()
    periodic_influence_coefficients(problem.grid, problem.material.poisson_ratio, ("zz",))
    kernel_time = time.perf_counter() - start

    start, cpu_start = time.perf_counter(), time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        records = [r for _, r in transient.steps(problem)]
    run_time, cpu_time = time.perf_counter() - start, time.process_time() - cpu_start
    iterations = np.array([r.iterations for r in records])

    rows = [("kernel", f"periodic influence coefficients, {args.n}^2", f"{kernel_time:.2f} s", "-"),
            ("transient", f"{args.n}^2 x {len(records)} steps, frictionless sliding",
             f"{run_time:.1f} s ({1e3 * run_time / len(records):.0f} ms/step; CPU {cpu_time:.1f} s)",
             f"{iterations.mean():.1f} CG it/step (max {iterations.max()}, last 100: {iterations[-100:].mean():.1f})")]
    if not args.no_steady:
        start = time.perf_counter()
        steady = solve_steady(problem)
        rows.append(("steady", f"exact periodic steady state, {args.n}^2", f"{time.perf_counter() - start:.1f} s",
                     f"{steady.iterations} GMRES it"))
    print(f"# {platform.machine()} {os.cpu_count()} cores, python {platform.python_version()}, "
          f"load average {load_start:.1f} at the start, {os.getloadavg()[0]:.1f} at the end")
    print(f"# mu_app at the last step {records[-1].mu_app:.5g}"
          + ("" if args.no_steady else f", steady {steady.mu_app:.5g}")
          + f"; real contact fraction {records[-1].contact_fraction:.4f}, {records[-1].contact_patches} patches")
    print("| row | problem | wall time | iterations |")
    print("|---|---|---|---|")
    for row in rows:
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
