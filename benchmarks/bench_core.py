"""Core benchmarks: prints a table of wall times, iteration counts and ratios measured in one run.

    .venv/bin/python benchmarks/bench_core.py            # full sizes (256^2), a few minutes
    .venv/bin/python benchmarks/bench_core.py --n 128    # quicker
    .venv/bin/python benchmarks/bench_core.py --skip history,case4,steady --repeats 3
                                                         # the transient targets: median (best) of 3

Rows
----
creep      creep indentation (seed material, W = 0.15 N held), n^2 x 200 steps: wall time, peak RSS.
history    the hereditary sum of the same run: recursive Prony update against the direct sum of seed
           Eq. 5 (both replaying the run's pressure history), time per run and ratio.
table1     seed Table 1, v = 0.8 a0/tau, +-2.56 a0, T = 4 tau (160 steps at n = 256), CG iterations.
steady     the steady solver at the same speed on the same grid (more in bench_steady.py).
case4      seed Table 3 case 4 (partial slip at 0.017 a0/tau, then sliding), to 1.5 tau: coupling iterations.
"""
from __future__ import annotations

import argparse
import platform
import resource
import time
import warnings

import numpy as np

from viscontact.numerics.grid import Grid
from viscontact.numerics.history import DirectHistory, PronyHistory
from viscontact.numerics.schemes import step_coefficients
from viscontact.physics.materials import Material
from viscontact.problem.problem import (NormalLoading, OutputSettings, PiecewiseLinear, Problem, TangentialLoading,
                                TimeStepping)
from viscontact.solvers.steady import solve_steady
from viscontact.running.loop import simulate

A0, TAU, R = 588.7e-6, 0.01, 0.01
MATERIAL = Material.zener(1.93e6, 0.193e6, TAU, 0.3)


def sphere(n: int, half_width: float, control: str, value: float, tangential: TangentialLoading,
           t_end: float, dt: float, every: int = 1) -> Problem:
    grid = Grid(n, half_width)
    x, y = grid.mesh()
    return Problem(material=MATERIAL, grid=grid, gap=(x**2 + y**2) / (2 * R),
                   normal=NormalLoading(control, PiecewiseLinear.constant(value)), tangential=tangential,
                   time=TimeStepping(t_end, dt), output=OutputSettings(every=every), radius=R)


def timed_run(problem: Problem) -> tuple[float, list]:
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        records = list(simulate(problem))
    return time.perf_counter() - start, records


def repeated_run(problem: Problem, repeats: int) -> tuple[str, list]:
    """``timed_run`` ``repeats`` times: ("median s (best s, of N)" or "wall s", the last run's records)."""
    walls = []
    for _ in range(repeats):
        wall, records = timed_run(problem)
        walls.append(wall)
    if repeats == 1:
        return f"{walls[0]:.1f} s", records
    return f"{np.median(walls):.2f} s (best {min(walls):.2f}, of {repeats})", records


def history_replay(pressures: list[np.ndarray], dt: float) -> tuple[float, float, float]:
    """Time the recursive and the direct hereditary sums over the same pressure history; also return
    their largest relative difference in the history traction."""
    n = pressures[0].shape[0]
    first = step_coefficients(MATERIAL.creep, dt, "constant", True)
    regular = step_coefficients(MATERIAL.creep, dt, "constant", False)
    rec, direct = PronyHistory.zeros(1, n), DirectHistory(n)
    t_rec = t_dir = 0.0
    diff = 0.0
    for k, p in enumerate(pressures):
        coef = first if k == 0 else regular
        t0 = time.perf_counter()
        r1 = rec.known(coef, k * dt)
        rec = rec.advanced(p, coef, k * dt)
        t1 = time.perf_counter()
        r2 = direct.known(coef, k * dt)
        direct = direct.advanced(p, coef, k * dt)
        t2 = time.perf_counter()
        t_rec += t1 - t0
        t_dir += t2 - t1
        scale = max(np.abs(r2).max(), 1e-300)
        diff = max(diff, float(np.abs(r1 - r2).max() / scale))
    return t_rec, t_dir, diff


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=256, help="cells per side (default 256)")
    ap.add_argument("--skip", default="", help="comma-separated rows to skip")
    ap.add_argument("--repeats", type=int, default=1,
                    help="runs of the creep and table1 rows in this process: their median and best wall time")
    args = ap.parse_args()
    n, skip = args.n, set(filter(None, args.skip.split(",")))
    rows = []
    print(f"# viscontact core benchmark, n = {n}, {platform.processor() or platform.machine()}, "
          f"{platform.python_version()}, {time.strftime('%Y-%m-%d')}")

    if "creep" not in skip or "history" not in skip:
        pb = sphere(n, 1.5e-3, "load", 0.15, TangentialLoading(), 0.04, 2e-4)
        wall, recs = repeated_run(pb, args.repeats)
        rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        its = np.mean([r.iterations for r in recs])
        rows.append(("creep", f"{n}^2 x {len(recs)} steps", wall, f"{its:.1f} CG it/step",
                     f"peak RSS {rss:.0f} MiB"))
        if "history" not in skip:
            t_rec, t_dir, diff = history_replay([r.pressure for r in recs], pb.time.dt)
            rows.append(("history", f"{len(recs)} steps", f"recursive {t_rec:.2f} s", f"direct {t_dir:.2f} s",
                         f"ratio {t_dir / t_rec:.0f}x, max rel diff {diff:.1e}"))

    v = 0.8 * A0 / TAU
    hw = 2.56 * A0
    if "table1" not in skip:
        dt = 2 * hw / n / v
        pb = sphere(n, hw, "load", 0.148, TangentialLoading("frictionless_sliding", 0.0, 0.0, v), 4 * TAU, dt)
        wall, recs = repeated_run(pb, args.repeats)
        its = [r.iterations for r in recs]
        rows.append(("table1", f"{n}^2 x {len(recs)} steps", wall,
                     f"{np.mean(its):.1f} CG it/step (max {max(its)})", f"mu_app(4 tau) {recs[-1].mu_app:.4f}"))
    if "steady" not in skip:
        pb = sphere(n, hw, "load", 0.148, TangentialLoading("frictionless_sliding", 0.0, 0.0, v), 4 * TAU,
                    2 * hw / n / v)
        start = time.perf_counter()
        rec = solve_steady(pb)
        wall = time.perf_counter() - start
        rows.append(("steady", f"{n}^2, 1 speed", f"{wall:.1f} s", f"{rec.iterations} GMRES it",
                     f"mu_app {rec.mu_app:.4f}"))
    if "case4" not in skip:
        v4 = 1.2 * A0 / TAU
        hw4 = 3.07 * A0
        pb = sphere(n, hw4, "displacement", 34.45e-6,
                    TangentialLoading("partial_slip", 0.3, 0.017 * A0 / TAU, v4), 1.5 * TAU, 2 * hw4 / n / v4)
        wall, recs = timed_run(pb)
        partial = [r for r in recs if r.phase == 1]
        sliding = [r for r in recs if r.phase == 2]
        onset = sliding[0].t / TAU if sliding else float("nan")
        rows.append(("case4", f"{n}^2 x {len(recs)} steps", f"{wall:.1f} s",
                     f"coupling it/step {np.mean([r.coupling_iterations for r in partial]):.1f} (partial), "
                     f"{np.mean([r.coupling_iterations for r in sliding]):.1f} (sliding)",
                     f"gross sliding at {onset:.3f} tau"))

    widths = [max(len(str(r[i])) for r in rows) for i in range(5)]
    for r in rows:
        print(" | ".join(str(c).ljust(w) for c, w in zip(r, widths)))


if __name__ == "__main__":
    main()
