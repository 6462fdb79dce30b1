"""Large grids (issue 15 item 4), the solver alone: CPU time per step and peak memory of a few
transient steps at n^2, sliding and periodic rough (``bench_scale.py`` times the streamed
``viscontact run`` of the sliding case with its result file and the dry-run estimates).

    .venv/bin/python benchmarks/bench_solver_scale.py --n 1024 --steps 6

Rows, each in a fresh subprocess (its own peak RSS, VmHWM):

``sliding``  the seed's Table 1 frictionless sliding (``alternate.py``'s ``table1`` case: Zener seed
             material, v = 0.8 a0/tau, +-2.56 a0, one cell per step), padded DC-FFT;
``rough``    the shipped periodic rough case in frictionless sliding (``bench_rough.py``'s), unpadded
             periodic FFTs.

Printed: the set-up (kernels, preconditioners) wall and CPU time, the first step (t = 0, from
nothing) and the mean of the later steps in wall and process CPU time (all FFT threads), CG
iterations, and the peak RSS. No records are kept (``transient.steps``), so the memory is the
solver's: what the streamed result file adds is small per step.
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np
from compare_tamaas import peak_rss_mib, run_child


def _cpu() -> float:
    t = os.times()
    return t.user + t.system


def child(case: str, n: int, steps: int, result: str) -> None:
    from viscontact.solvers import transient
    from viscontact.bodies.compliance import compliance_of

    if case == "sliding":
        from alternate import problem as sliding_problem
        problem = sliding_problem("table1", n, steps)
    else:
        from bench_rough import rough_problem
        problem = rough_problem(n, steps)
    wall, cpu = time.perf_counter(), _cpu()
    compliance = compliance_of(problem)
    marks = [(time.perf_counter() - wall, _cpu() - cpu)]
    iterations = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for _, record in transient.steps(problem, compliance=compliance):
            marks.append((time.perf_counter() - wall, _cpu() - cpu))
            iterations.append(record.iterations)
    np.savez(result, marks=np.asarray(marks), iterations=np.asarray(iterations), own_rss_mib=peak_rss_mib())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=1024)
    ap.add_argument("--steps", type=int, default=6)
    ap.add_argument("--only", choices=("sliding", "rough"))
    ap.add_argument("--child", help=argparse.SUPPRESS)
    ap.add_argument("--result", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        child(args.child, args.n, args.steps, args.result)
        return
    load = os.getloadavg()[0]
    print("| case | n^2 x steps | set-up wall / CPU [s] | first step wall / CPU [s] | later steps wall / CPU "
          "[s/step] | CG it/step (first) | peak RSS [MiB] |")
    print("|---|---|---|---|---|---|---|")
    for case in ([args.only] if args.only else ["sliding", "rough"]):
        with tempfile.TemporaryDirectory() as tmp:
            result = Path(tmp) / "r.npz"
            cmd = [sys.executable, __file__, "--child", case, "--n", str(args.n), "--steps", str(args.steps),
                   "--result", str(result)]
            out = run_child(cmd, result, f"bench_solver_scale: {case}")
        marks, its = out["marks"], out["iterations"]
        later = np.diff(marks[1:], axis=0).mean(axis=0)
        first = marks[1] - marks[0]
        print(f"| {case} | {args.n}^2 x {len(its)} | {marks[0][0]:.1f} / {marks[0][1]:.1f} | "
              f"{first[0]:.1f} / {first[1]:.1f} | {later[0]:.2f} / {later[1]:.2f} | {its[1:].mean():.1f} ({its[0]}) | "
              f"{float(out['own_rss_mib']):.0f} |", flush=True)
    print(f"# load average {load:.1f} -> {os.getloadavg()[0]:.1f}, {time.strftime('%Y-%m-%d %H:%M')}")


if __name__ == "__main__":
    main()
