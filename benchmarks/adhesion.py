"""Cost of adhesion per time step: an adhesive approach-retraction against the same run without
``[adhesion]``, each in a fresh subprocess, alternated (plain, adhesive, plain, adhesive...) so that the
load of a shared machine falls on both alike.

    .venv/bin/python benchmarks/adhesion.py --n 128 256 --repeats 3

The case is the shipped ``adhesive_pdms_retraction.toml`` (a PDMS-like Zener sphere, R = 10 mm,
G(0) = 1.05 MPa, G(inf) = 0.35 MPa, tau = 0.1 s, nu = 0.5; w = 50 mJ/m^2, sigma_0 = 19 kPa; +-0.64 mm,
dt = 20 ms, 71 steps) at ``grid.n`` = each ``--n``, with one of two histories (``--history``):

``contact``   touch, press 4 um in 0.1 s, hold 0.5 s, pull back to 1 um in 0.8 s: both runs stay in
              contact throughout (the same history, the same contact problem but for the law);
``pull_off``  the shipped history, pulled back to -8 um (past the jump-off near -5 um); the plain run
              takes it clipped at 0 (a history below zero needs [adhesion]), so from t = 0.87 s on it
              has nothing to solve while the adhesive run pulls the contact off.

Each child times :func:`viscontact.solvers.transient.steps` alone (CPU time of the process, no
records kept) and writes the loads and CG iterations; the table gives medians per step and the
ratio adhesive / plain, and the adhesive run's most tensile load. ``--src`` puts a source tree first
on the path (A/B of two versions: run once per tree).
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HISTORIES = {
    "contact": ([[0.0, 0.0], [0.1, 4e-6], [0.6, 4e-6], [1.4, 1e-6]],) * 2,
    "pull_off": ([[0.0, 0.0], [0.1, 4e-6], [0.6, 4e-6], [1.4, -8e-6]],
                 [[0.0, 0.0], [0.1, 4e-6], [0.6, 4e-6], [0.6 + 0.8 / 3, 0.0], [1.4, 0.0]]),
}


def child(args: argparse.Namespace) -> None:
    import warnings

    from viscontact.io.case import Case
    from viscontact.io.shipped import shipped_case
    from viscontact.solvers import transient

    path = shipped_case("adhesive_pdms_retraction")
    adhesive_history, plain_history = HISTORIES[args.history]
    overrides: dict = {"grid.n": args.n}
    if args.adhesive:
        overrides["normal.history"] = adhesive_history
    else:
        overrides.update({"adhesion": None, "normal.history": plain_history})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        problem = Case.from_toml_text(path.read_text(), path.parent).with_overrides(overrides).to_problem()
        cpu, wall = time.process_time(), time.perf_counter()
        records = [record for _, record in transient.steps(problem)]
        cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
    Path(args.result).write_text(json.dumps({"cpu": cpu, "wall": wall, "steps": len(records),
                                             "loads": [r.load for r in records],
                                             "iterations": [r.iterations for r in records]}))


def run(args: argparse.Namespace, n: int, adhesive: bool, result: Path) -> dict:
    env = dict(os.environ)
    if args.src:
        env["PYTHONPATH"] = os.pathsep.join([str(Path(args.src).resolve()), env.get("PYTHONPATH", "")])
    cmd = [sys.executable, __file__, "--child", "--n", str(n), "--history", args.history, "--result", str(result)]
    subprocess.run(cmd + (["--adhesive"] if adhesive else []), env=env, check=True)
    return json.loads(result.read_text())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, nargs="+", default=[128, 256])
    ap.add_argument("--history", choices=sorted(HISTORIES), default="contact")
    ap.add_argument("--repeats", type=int, default=3, help="alternated rounds (default 3)")
    ap.add_argument("--src", default=None, help="a source tree (src folder) first on PYTHONPATH")
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--adhesive", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--result", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        args.n = args.n[0]
        child(args)
        return
    load = os.getloadavg()[0]
    print(f"# {args.history}, {args.repeats} alternated rounds, load {load:.1f}, {time.strftime('%Y-%m-%d %H:%M')}")
    print("| n | steps | plain [ms/step] | adhesive [ms/step] | **adhesive / plain** | CG it/step plain, adhesive "
          "| most tensile load [mN] |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for n in args.n:
            runs: dict[bool, list[dict]] = {False: [], True: []}
            for k in range(args.repeats):
                for adhesive in (False, True):
                    runs[adhesive].append(run(args, n, adhesive, Path(tmp) / f"{n}-{adhesive}-{k}.json"))
            per_step = {a: float(np.median([r["cpu"] / r["steps"] for r in rs])) for a, rs in runs.items()}
            its = {a: float(np.mean(rs[-1]["iterations"])) for a, rs in runs.items()}
            print(f"| {n} | {runs[True][-1]['steps']} | {1e3 * per_step[False]:.1f} | {1e3 * per_step[True]:.1f} | "
                  f"**{per_step[True] / per_step[False]:.2f}** | {its[False]:.1f}, {its[True]:.1f} | "
                  f"{1e3 * min(runs[True][-1]['loads']):.4f} |", flush=True)
    print(f"# load at the end {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
