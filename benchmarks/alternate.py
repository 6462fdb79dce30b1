"""A/B timing of the transient solver: two source trees (or two environments) alternated in fresh
subprocesses, for measuring a change on a shared machine.

    .venv/bin/python benchmarks/alternate.py --tree base=/tmp/base/src --tree new=src --n 256 --repeats 3
    .venv/bin/python benchmarks/alternate.py --tree plain=src --tree tuned=src:VISCONTACT_MALLOC=off

Each ``--tree NAME=PATH[:VAR=VALUE,...]`` puts PATH first on ``PYTHONPATH`` (a ``src`` folder, e.g.
from ``git archive``) and sets the given environment variables (``ALTERNATE_WORKERS=1``: ``solver.workers`` of the run,
default -1). The runs alternate (A, B, A, B...),
so the load of the machine falls on both alike; the table gives medians of the process CPU time
(user + sys, from ``os.wait4``: less sensitive to the load than the wall time), the sys time, the
wall time and the child's own peak RSS (VmHWM), and the ratios against the first tree. The final
pressures of every tree are compared with the first's (max difference / peak).

Cases (``--case``), both the seed material (Zener, G(0) = 1.93 MPa, G(0)/G(inf) = 10, 10 ms, nu = 0.3),
sphere R = 10 mm, default time scheme (linear), through :func:`viscontact.solvers.transient.steps` (no records kept: the solver alone):

``creep``   W = 0.15 N held, +-1.5 mm, 0.2 ms steps (``compare_tamaas.py``'s case), ``--steps`` steps;
``table1``  seed Table 1: frictionless sliding at v = 0.8 a0/tau, +-2.56 a0, W = 0.148 N, one cell
            per step, T = 4 tau (161 steps at n = 256) unless ``--steps``.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from compare_tamaas import peak_rss_mib, run_child

A0, TAU, RADIUS = 588.7e-6, 0.01, 0.01


def problem(case: str, n: int, steps: int | None):
    import viscontact as vc

    material = vc.Material.zener(1.93e6, 0.193e6, TAU, 0.3)
    if case == "creep":
        half_width, dt = 1.5e-3, 2e-4
        tangential, load = vc.TangentialLoading(), 0.15
        t_end = ((steps or 201) - 1) * dt
    else:
        v = 0.8 * A0 / TAU
        half_width = 2.56 * A0
        dt = 2 * half_width / n / v
        tangential, load = vc.TangentialLoading("frictionless_sliding", 0.0, 0.0, v), 0.148
        t_end = (steps - 1) * dt if steps else 4 * TAU
    grid = vc.Grid(n, half_width)
    x, y = grid.mesh()
    return vc.Problem(material=material, grid=grid, gap=(x**2 + y**2) / (2 * RADIUS),
                      normal=vc.NormalLoading("load", vc.PiecewiseLinear.constant(load)), tangential=tangential,
                      time=vc.TimeStepping(t_end, dt), radius=RADIUS,
                      solver=vc.SolverSettings(workers=int(os.environ.get("ALTERNATE_WORKERS", "-1"))))


def child(args: argparse.Namespace) -> None:
    import warnings

    from viscontact.solvers import transient

    pb = problem(args.case, args.n, args.steps)
    wall = time.perf_counter()
    iterations = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for state, record in transient.steps(pb):
            iterations.append(record.iterations)
    wall = time.perf_counter() - wall
    np.savez(args.result, pressure=state.pressure, iterations=np.asarray(iterations), solve_wall=wall,
             own_rss_mib=peak_rss_mib())


def run_tree(spec: tuple[str, str, dict], args: argparse.Namespace, workdir: Path, k: int) -> dict:
    name, path, extra = spec
    result = workdir / f"{name}-{k}.npz"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(Path(path).resolve()), str(Path(__file__).parent)]))
    env.update(extra)
    cmd = [sys.executable, __file__, "--child", "--case", args.case, "--n", str(args.n), "--result", str(result)]
    if args.steps:
        cmd += ["--steps", str(args.steps)]
    return run_child(cmd, result, f"alternate: tree {name}", env)


def parse_tree(text: str) -> tuple[str, str, dict]:
    name, _, rest = text.partition("=")
    path, _, env = rest.partition(":")
    extra = dict(item.split("=", 1) for item in env.split(",") if item)
    return name, path, extra


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tree", action="append", default=[], help="NAME=PATH[:VAR=VALUE,...] (two or more)")
    ap.add_argument("--case", choices=("creep", "table1"), default="creep")
    ap.add_argument("--n", type=int, default=256)
    ap.add_argument("--steps", type=int, default=None, help="time steps (default: 201 creep, 4 tau table1)")
    ap.add_argument("--repeats", type=int, default=2, help="alternated rounds (default 2)")
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--result", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        child(args)
        return
    trees = [parse_tree(t) for t in args.tree]
    if len(trees) < 2:
        ap.error("give at least two --tree")
    load = os.getloadavg()[0]
    runs: dict[str, list[dict]] = {t[0]: [] for t in trees}
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(args.repeats):
            for spec in trees:
                r = run_tree(spec, args, Path(tmp), k)
                runs[spec[0]].append(r)
                print(f"# round {k} {spec[0]}: cpu {r['cpu']:.2f} s (sys {r['sys']:.2f}), wall {r['wall']:.1f} s, "
                      f"{float(r['own_rss_mib']):.0f} MiB, load {os.getloadavg()[0]:.1f}", flush=True)
    base = trees[0][0]
    med = {name: {key: float(np.median([float(r[key]) for r in rs]))
                  for key in ("cpu", "sys", "wall", "solve_wall", "own_rss_mib", "faults")} for name, rs in runs.items()}
    ref = runs[base][-1]["pressure"]
    print(f"# {args.case}, n = {args.n}, {len(runs[base][-1]['iterations'])} steps, {args.repeats} rounds, "
          f"load {load:.1f} -> {os.getloadavg()[0]:.1f}, {time.strftime('%Y-%m-%d %H:%M')}")
    print("| tree | CPU [s] | sys [s] | wall [s] | solve wall [s] | peak RSS [MiB] | minor faults | CG it/step "
          f"| CPU {base}/tree | wall {base}/tree | max dp / peak |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for name, rs in runs.items():
        m = med[name]
        diff = float(np.abs(rs[-1]["pressure"] - ref).max() / np.abs(ref).max())
        its = np.asarray(rs[-1]["iterations"], dtype=float)
        print(f"| {name} | {m['cpu']:.2f} | {m['sys']:.2f} | {m['wall']:.1f} | {m['solve_wall']:.1f} | "
              f"{m['own_rss_mib']:.0f} | {m['faults']:.0f} | {its.mean():.2f} | "
              f"{med[base]['cpu'] / m['cpu']:.3f} | {med[base]['wall'] / m['wall']:.3f} | {diff:.1e} |")
    print(json.dumps({name: [{k: float(r[k]) for k in ("cpu", "sys", "wall")} for r in rs] for name, rs in runs.items()}))


if __name__ == "__main__":
    main()
