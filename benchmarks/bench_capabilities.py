"""What each capability costs per time step against the plain run of the same contact.

    .venv/bin/python benchmarks/bench_capabilities.py [--n 128 --n 256] [--line-n 4096] [--repeats 2]

Pairs of transient runs, each in a fresh subprocess, the two of a pair alternated (plain, capability,
plain, capability...) so that the load of a shared machine falls on both alike:

``rolling``    the shipped ``rolling_polymer_roller`` (a ball braking at creepage -0.5 % on a Zener
               rubber, friction 0.5: stick-slip rolling, the tangential problem solved every step,
               u_x convected) against the same ball in frictionless sliding at the rolling speed;
``line``       the shipped ``polymer_roller_line_contact`` (plane strain) on ``--line-n`` cells: its
               partial slip into gross sliding, and rolling with traction (creepage -0.5 %), against
               frictionless sliding of the same cylinder (one cell a step).

Adhesion has its own pair, ``benchmarks/adhesion.py`` (two histories: in contact throughout, and
through the pull-off).

Each child times :func:`viscontact.solvers.transient.steps` (process CPU time, no records kept) and
reports the steps, the CG iterations and how many of its normal solves ran on a support window (a
window's solve is one whose box check passed: ``windowed_cg``'s ``product``). Printed: medians per
step and the ratio capability / plain. The same seams serve them all: the support windows (3-D
DC-FFT grids), streaming and checkpoints (``viscontact run``), and the device (``solver.device =
"gpu"``: the emulated device of ``tests/unit/test_array_seam.py`` runs each of these modes bit for
bit as numpy).
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

ROLLING_SPEED = 0.0526  # m/s, the shipped rolling case's
ROLLING_HALF_WIDTH = 2.4e-3  # m
#: steps of each run: cells rolled or slid (one a step)
STEPS_3D, STEPS_LINE = 120, 400


def _overrides(kind: str, n: int) -> tuple[str, dict]:
    """(shipped case, overrides) of one run."""
    steps = {"grid.n": n, "time.t_end": (STEPS_3D - 0.5) * 2 * ROLLING_HALF_WIDTH / n / ROLLING_SPEED}
    if kind == "rolling":
        return "rolling_polymer_roller", steps
    if kind == "rolling_plain":
        return "rolling_polymer_roller", {**steps, "tangential.mode": "frictionless_sliding",
                                          "tangential.sliding_speed": ROLLING_SPEED, "tangential.rolling_speed": None,
                                          "tangential.creepage": None, "tangential.friction_coefficient": None}
    line = {"grid.n": n}
    if kind == "line_partial_slip":  # the shipped run: indentation, partial slip, gross sliding (12 tau)
        return "polymer_roller_line_contact", line
    dx = 2 * 8.0e-3 / n  # the shipped half-width
    if kind == "line_rolling":
        return "polymer_roller_line_contact", {**line, "tangential.mode": "rolling", "tangential.rolling_speed": 0.5,
                                               "tangential.creepage": -5e-3, "tangential.displacement_rate": None,
                                               "tangential.slip": None, "tangential.sliding_speed": None,
                                               "time.t_end": (STEPS_LINE - 0.5) * dx / 0.5}
    if kind == "line_plain":
        return "polymer_roller_line_contact", {**line, "tangential.mode": "frictionless_sliding",
                                               "tangential.displacement_rate": None, "tangential.slip": None,
                                               "tangential.friction_coefficient": None,
                                               "time.t_end": (STEPS_LINE - 0.5) * dx / 0.5}
    raise ValueError(kind)


def child(kind: str, n: int) -> None:
    import warnings

    from viscontact.io.case import load_case
    from viscontact.io.shipped import shipped_case
    from viscontact.solvers import contact_laws, transient

    name, changes = _overrides(kind, n)
    problem = load_case(shipped_case(name)).with_overrides({**changes, "output.fields": []}).to_problem()
    windowed = [0, 0]
    original = contact_laws.windowed_cg

    def counted(*args, **kwargs):
        sol = original(*args, **kwargs)
        windowed[0] += 1
        windowed[1] += sol.product is not None
        return sol

    contact_laws.windowed_cg = counted  # the normal solves of the transient
    cpu = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        iterations = [record.iterations for _, record in transient.steps(problem)]
    cpu = time.process_time() - cpu
    print(json.dumps({"steps": len(iterations), "cpu": cpu, "iterations": sum(iterations) / max(len(iterations), 1),
                      "solves": windowed[0], "windowed": windowed[1]}))


def run(kind: str, n: int) -> dict:
    out = subprocess.run([sys.executable, __file__, "--child", kind, str(n)], capture_output=True, text=True,
                         check=True, env={**os.environ})
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, action="append", help="3-D grid sides (default 128 and 256)")
    ap.add_argument("--line-n", type=int, default=4096)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        child(args.child[0], int(args.child[1]))
        return
    pairs = [("rolling", n) for n in (args.n or [128, 256])]
    pairs += [("line_partial_slip", args.line_n), ("line_rolling", args.line_n)]
    print(f"# {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at the start")
    print("| capability | grid | steps | CPU/step plain [ms] | CPU/step capability [ms] | ratio | CG it/step plain → "
          "capability | normal solves on a window (capability) |")
    print("|---|---|---|---|---|---|---|---|")
    for kind, n in pairs:
        plain_kind = "line_plain" if kind.startswith("line") else f"{kind}_plain"
        plain, capability = [], []
        for _ in range(args.repeats):
            plain.append(run(plain_kind, n))
            capability.append(run(kind, n))
        p = statistics.median(r["cpu"] / r["steps"] for r in plain) * 1e3
        c = statistics.median(r["cpu"] / r["steps"] for r in capability) * 1e3
        last = capability[-1]
        grid = f"{n} cells" if kind.startswith("line") else f"{n}²"
        print(f"| {kind} | {grid} | {plain[-1]['steps']} / {last['steps']} | {p:.2f} | {c:.2f} | {c / p:.2f}× | "
              f"{plain[-1]['iterations']:.2f} → {last['iterations']:.2f} | {last['windowed']} of {last['solves']} |")
    print(f"# load average {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
