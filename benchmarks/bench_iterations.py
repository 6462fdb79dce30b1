"""CG iterations per step and time per step of shipped cases, two source trees alternated, with the
difference of their results (issue 35: fewer iterations a step).

    .venv/bin/python benchmarks/bench_iterations.py --tree old=/work/main/src --tree new=src \\
        --case creep_indentation --case seed_table1_v0.8 --n 256 [--steps 40] [--repeats 2]
    .venv/bin/python benchmarks/bench_iterations.py --tree old=/tmp/old/src --tree new=src \\
        --case rough_periodic_sliding --n 512 --steps 100 --repeats 5 --set tangential.mode=frictionless_sliding

Each ``--tree NAME=PATH`` puts PATH first on ``PYTHONPATH`` (a ``src`` folder). Every run is a fresh
subprocess running the shipped case file (``src/viscontact/cases/CASE.toml`` of the first tree) at
``grid.n = N`` (and the ``--set KEY=VALUE`` overrides, as ``viscontact run --set``) through
:func:`viscontact.solvers.transient.steps` (no records kept, no files: the
solver alone), the trees alternated (A, B, A, B...) so that the load of a shared machine falls on
both alike. Printed per case: the CG iterations per step (mean over the run, the first step apart,
and the mean of the later half), the process CPU time per step (user + sys, median over the
rounds), the wall time, and against the first tree the largest relative differences over the run
of the pressure field (max |dp| / max p at each step), the load [N], the approach delta_z [m] and
mu_app.
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from compare_tamaas import peak_rss_mib, run_child


def child(case_file: str, n: int, steps: int | None, result: str, overrides: list[str]) -> None:
    import warnings

    from viscontact.cli.arguments import parse_overrides
    from viscontact.io.case import load_case
    from viscontact.solvers import transient

    changes = {"grid.n": n, "output.fields": [], **parse_overrides(overrides)}
    problem = load_case(case_file).with_overrides(changes).to_problem()
    iterations, scalars, pressures = [], [], []
    wall = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for state, record in transient.steps(problem):
            iterations.append(record.iterations)
            scalars.append((record.load, record.delta_z, record.mu_app))
            pressures.append(np.array(state.pressure, dtype=float))
            if steps is not None and len(iterations) >= steps:
                break
    wall = time.perf_counter() - wall
    np.savez(result, iterations=np.asarray(iterations), scalars=np.asarray(scalars),
             pressures=np.asarray(pressures), solve_wall=wall, own_rss_mib=peak_rss_mib())


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    """max |a - b| / max |b| over the run (0 where b is 0 throughout)."""
    scale = float(np.abs(b).max())
    return float(np.abs(a - b).max() / scale) if scale > 0 else 0.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tree", action="append", default=[], help="NAME=PATH (two or more)")
    ap.add_argument("--case", action="append", default=[], help="shipped case name (repeatable)")
    ap.add_argument("--n", type=int, default=256)
    ap.add_argument("--steps", type=int, default=None, help="steps (default: the whole case)")
    ap.add_argument("--repeats", type=int, default=1, help="alternated rounds (default 1)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a case-file override for every run (repeatable), as viscontact run --set")
    ap.add_argument("--child", nargs=4, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        case_file, n, steps, result = args.child
        child(case_file, int(n), None if steps == "all" else int(steps), result, args.set)
        return
    trees = [tuple(t.split("=", 1)) for t in args.tree]
    if len(trees) < 2 or not args.case:
        ap.error("give at least two --tree and one --case")
    cases_dir = Path(trees[0][1]) / "viscontact" / "cases"
    load = os.getloadavg()[0]
    print(f"# {time.strftime('%Y-%m-%d %H:%M')}, n = {args.n}, {args.repeats} round(s), load {load:.1f}")
    print("| case | tree | steps | CG it/step | first | later half | CPU/step [ms] | wall [s] | peak RSS [MiB] "
          "| max dp/p | max dW/W | max d(delta_z) | max d(mu_app) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for case in args.case:
            runs: dict[str, list[dict]] = {name: [] for name, _ in trees}
            for k in range(args.repeats):
                for name, path in trees:
                    result = Path(tmp) / f"{case}-{name}-{k}.npz"
                    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(Path(path).resolve()),
                                                                       str(Path(__file__).parent)]))
                    cmd = [sys.executable, __file__, "--child", str(cases_dir / f"{case}.toml"), str(args.n),
                           str(args.steps or "all"), str(result), *(f"--set={item}" for item in args.set)]
                    runs[name].append(run_child(cmd, result, f"bench_iterations: {case} on {name}", env))
            ref = runs[trees[0][0]][-1]
            for name, rs in runs.items():
                last = rs[-1]
                its = np.asarray(last["iterations"], dtype=float)
                steps = its.size
                cpu = float(np.median([r["cpu"] for r in rs])) / steps
                wall = float(np.median([r["wall"] for r in rs]))
                p, p_ref = last["pressures"], ref["pressures"]
                dp = max(float(np.abs(a - b).max() / np.abs(b).max()) for a, b in zip(p, p_ref) if np.abs(b).max() > 0)
                s, s_ref = last["scalars"], ref["scalars"]
                print(f"| {case} | {name} | {steps} | {its.mean():.2f} | {its[0]:.0f} | {its[steps // 2:].mean():.2f} | "
                      f"{1e3 * cpu:.1f} | {wall:.1f} | {float(last['own_rss_mib']):.0f} | {dp:.1e} | "
                      f"{_relative(s[:, 0], s_ref[:, 0]):.1e} | {_relative(s[:, 1], s_ref[:, 1]):.1e} | "
                      f"{_relative(s[:, 2], s_ref[:, 2]):.1e} |", flush=True)
    print(f"# load at the end {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
