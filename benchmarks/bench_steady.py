"""Steady-state solver benchmark: wall times and results, optionally against a baseline source tree,
measured alternately (baseline, this tree, baseline, ...) so that the load of a shared machine hits
both alike. Prints a table.

    .venv/bin/python benchmarks/bench_steady.py                       # this tree, n = 256 and the curve
    git archive main src | tar -x -C /tmp/base                        # a baseline tree (any commit)
    .venv/bin/python benchmarks/bench_steady.py --baseline /tmp/base/src --repeat 2

Rows
----
table1 v      ``viscontact.running.api.run_steady`` on ``cases/seed_table1_v{v}.toml`` at n^2 (default 256),
              in process (what ``viscontact steady`` does after its imports, without writing the file).
cli v0.8      the ``viscontact steady`` command on the v = 0.8 a0/tau case, wall time of the process
              (imports and the netCDF file included).
curve         mu_app against speed: 30 speeds over 8 decades, 30-term material, 128^2 (the
              ``bench_materials.py`` curve row: ``steady.speed_sweep``, each speed warm-started).
at 128^2      ``solve_steady`` at 128^2 on the Table 1 cases and on the v = 0.8 case at 0.04, 0.3, 3 and
              30 a0/tau and with gross sliding (mu_f = 0.3, coupled): only the results, for the
              before/after differences (mu_app, peak pressure, contact area, shift, approach).

Each measurement runs in its own process (``--worker``): the baseline with ``PYTHONPATH`` set to
its source tree. The CPU column is the process time of the solve (all threads), the last run of each
tree: on a loaded machine it is closer to what an idle one needs than the wall time.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
A0_PER_TAU = 588.7e-6 / 0.01  # the seed's speed unit a0/tau [m/s]
QUANTITIES = ("mu_app", "peak", "area", "shift", "delta")


def _summary(record) -> dict:
    return {"mu_app": record.mu_app, "peak": float(record.pressure.max()), "area": record.contact_area,
            "shift": record.contact_shift, "delta": record.delta_z, "iterations": record.iterations}


def worker(row: str, n: int) -> dict:
    """One measurement in this process: wall time [s] and the results."""
    import numpy as np

    from viscontact.running.api import prepare
    from viscontact.io.case import load_case
    from viscontact.solvers.steady import solve_steady, speed_sweep

    def problem(name: str, n_cells: int, **overrides):
        case = load_case(ROOT / "cases" / f"{name}.toml").with_overrides({"grid.n": n_cells, **overrides})
        return prepare(case, transient=False)[0]

    if row.startswith("table1"):
        pb = problem(f"seed_table1_v{row.split()[1]}", n)
        start, cpu = time.perf_counter(), time.process_time()
        rec = solve_steady(pb)
        return {"wall": time.perf_counter() - start, "cpu": time.process_time() - cpu, **_summary(rec)}
    if row == "cli":
        with tempfile.TemporaryDirectory() as tmp:
            start = time.perf_counter()
            command = [str(Path(sys.executable).parent / "viscontact"), "steady",
                       str(ROOT / "cases" / "seed_table1_v0.8.toml"), "--set", f"grid.n={n}",
                       "--out", str(Path(tmp) / "s.nc"), "--quiet"]
            subprocess.run(command, check=True, env=os.environ.copy(), capture_output=True)
            return {"wall": time.perf_counter() - start}
    if row == "curve":
        sys.path.insert(0, str(Path(__file__).parent))
        from bench_materials import material, sliding

        pb = sliding(material(30), 128, 1, "frictionless_sliding", 0.0)
        start, cpu = time.perf_counter(), time.process_time()
        records = speed_sweep(pb, np.geomspace(1e-6, 1e2, 30))
        wall = time.perf_counter() - start
        mu = np.array([r.mu_app for r in records])
        return {"wall": wall, "cpu": time.process_time() - cpu, "mu_app": float(mu.max()),
                "iterations": sum(r.iterations for r in records), "mu_curve": mu.tolist()}
    if row == "results":
        out = {}
        for v in ("0.4", "0.8", "1.2"):
            out[f"table1 v{v}"] = _summary(solve_steady(problem(f"seed_table1_v{v}", 128)))
        pb = problem("seed_table1_v0.8", 128)
        for factor in (0.04, 0.3, 3.0, 30.0):
            out[f"v = {factor} a0/tau"] = _summary(solve_steady(pb, factor * A0_PER_TAU))
        pb = problem("seed_table1_v0.8", 128, **{"tangential.mode": "gross_sliding",
                                                  "tangential.friction_coefficient": 0.3})
        out["gross sliding 0.3"] = _summary(solve_steady(pb))
        return out
    raise ValueError(row)


def measure(row: str, n: int, source: str | None) -> dict:
    env = os.environ.copy()
    if source:
        env["PYTHONPATH"] = source
    done = subprocess.run([sys.executable, __file__, "--worker", row, "--n", str(n)], env=env, check=True,
                          capture_output=True, text=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def _load() -> str:
    try:
        return " ".join(f"{x:.1f}" for x in os.getloadavg())
    except OSError:
        return "?"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=256, help="cells per side of the Table 1 rows (default 256)")
    ap.add_argument("--baseline", help="a viscontact source tree (the directory holding viscontact/) to compare")
    ap.add_argument("--repeat", type=int, default=1, help="alternations per row (default 1)")
    ap.add_argument("--rows", default="table1 0.4,table1 0.8,table1 1.2,cli,curve,results")
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.worker:
        print(json.dumps(worker(args.worker, args.n)))
        return
    print(f"# steady benchmark, {platform.machine()}, {os.cpu_count()} cores, python {platform.python_version()}, "
          f"{time.strftime('%Y-%m-%d %H:%M')}, load average {_load()}")
    trees = ([("baseline", args.baseline)] if args.baseline else []) + [("this tree", None)]
    print("| row | " + " | ".join(f"{name} wall [s]" for name, _ in trees) + " | CPU [s] | GMRES it | load before |")
    print("|---|" + "---|" * (len(trees) + 3))
    results = {}
    for row in filter(None, args.rows.split(",")):
        if row == "results":
            continue
        walls: dict[str, list[float]] = {name: [] for name, _ in trees}
        load = _load()
        for _ in range(args.repeat):
            for name, source in trees:
                res = measure(row, args.n, source)
                walls[name].append(res["wall"])
                results[(row, name)] = res
        its = " / ".join(str(results[(row, name)].get("iterations", "-")) for name, _ in trees)
        cpu = " / ".join(f"{results[(row, name)]['cpu']:.1f}" if "cpu" in results[(row, name)] else "-"
                         for name, _ in trees)
        cells = " | ".join(f"{statistics.median(w):.2f} ({', '.join(f'{x:.1f}' for x in w)})"
                           for w in walls.values())
        label = f"{row} ({args.n}^2)" if row.startswith(("table1", "cli")) else row
        print(f"| {label} | {cells} | {cpu} | {its} | {load} |", flush=True)
    if args.baseline and "curve" in args.rows:
        old, new = (results[("curve", name)]["mu_curve"] for name, _ in trees)
        diff = max(abs(a - b) / abs(a) for a, b in zip(old, new))
        print(f"\ncurve: largest relative difference in mu_app over the 30 speeds {diff:.1e}")
    if "results" in args.rows:
        per_tree = {name: measure("results", 128, source) for name, source in trees}
        print("\n## results at 128^2" + (": relative difference this tree - baseline" if args.baseline else ""))
        print("| case | " + " | ".join(QUANTITIES) + " | GMRES it |")
        print("|---|" + "---|" * (len(QUANTITIES) + 1))
        new = per_tree["this tree"]
        for case, res in new.items():
            if args.baseline:
                old = per_tree["baseline"][case]
                cells = [f"{(res[q] - old[q]) / abs(old[q]) if old[q] else res[q] - old[q]:.1e}" for q in QUANTITIES]
                its = f"{old['iterations']} -> {res['iterations']}"
            else:
                cells, its = [f"{res[q]:.6g}" for q in QUANTITIES], str(res["iterations"])
            print(f"| {case} | " + " | ".join(cells) + f" | {its} |")


if __name__ == "__main__":
    main()
