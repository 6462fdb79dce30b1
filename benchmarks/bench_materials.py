"""Many-term materials: cost against the number of Prony terms. Prints a table.

    .venv/bin/python benchmarks/bench_materials.py              # 128^2 steady kernels, 256^2 transient
    .venv/bin/python benchmarks/bench_materials.py --quick      # 64^2 / 128^2

Materials: M terms with relaxation times log-spaced over 1e-8 ... 1e3 s, equal moduli, G(0) =
1.93 MPa, G(inf) = G(0)/10, nu = 0.3 (M = 1 is the seed's Zener material's moduli).

Rows
----
kernel/per-mode  the steady effective kernel built mode by mode (``kernels.history_kernels``), one speed.
kernel/one-pass  the same kernel from ``steady_kernels.SteadyKernelBuilder`` (first speed: with its
                 IC node values; next speeds: without), and its largest difference to the per-mode one.
curve            mu_app against speed: 30 speeds over 8 decades, 30-term material, n^2 (steady
                 solver, ``steady.speed_sweep``: one kernel builder, each speed warm-started), split
                 into phases: setup (the compliance: influence coefficients, FFT plans), kernels
                 (``HalfSpace.steady_convolver``: the effective kernels and their spectra; the first
                 speed, which also evaluates the builder's IC nodes, apart) and solve (the rest: the
                 active-set / GMRES solve of each speed, its preconditioner and the record).
transient        gross sliding (mu_f = 0.3, coupled), linear scheme, n^2, 8 steps: the time to the
                 first record (setup and first step) and the median time of each further step, M = 1
                 and M = 30 measured alternately in one process; and the hereditary update alone
                 (``PronyHistory.known`` + ``advanced``, one component) per step.
"""
from __future__ import annotations

import argparse
import os
import platform
import time
import warnings
from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np

from viscontact import steady
from viscontact.numerics.grid import Grid
from viscontact.numerics.history import PronyHistory
from viscontact.physics.kernels import history_kernels
from viscontact.physics.materials import Material
from viscontact.problem.problem import (NormalLoading, OutputSettings, PiecewiseLinear, Problem, TangentialLoading,
                                TimeStepping)
from viscontact.numerics.schemes import step_coefficients
from viscontact.physics.steady_kernels import SteadyKernelBuilder
from viscontact.bodies.half_space import HalfSpace
from viscontact.solvers.transient import steps

G0, NU, R = 1.93e6, 0.3, 0.01


def material(terms: int) -> Material:
    g_inf = G0 / 10
    return Material.prony(g_inf, np.full(terms, (G0 - g_inf) / terms), np.geomspace(1e-8, 1e3, terms)
                          if terms > 1 else [1e-3], NU)


def sliding(mat: Material, n: int, steps: int, mode: str = "gross_sliding", friction: float = 0.3) -> Problem:
    grid = Grid(n, 1.5e-3)
    x, y = grid.mesh()
    speed = 0.05
    dt = grid.spacing / speed
    return Problem(material=mat, grid=grid, gap=(x**2 + y**2) / (2 * R),
                   normal=NormalLoading("load", PiecewiseLinear.constant(0.15)),
                   tangential=TangentialLoading(mode, friction, 0.0, speed),
                   time=TimeStepping(steps * dt, dt, "linear"), output=OutputSettings(every=1000, fields=()),
                   radius=R)


def per_step(problem: Problem) -> tuple[float, float]:
    """Wall time [s] to the first step's record (setup: compliance, kernels, first solve) and the
    median time of the further steps (the per-step cost; the median rides out load spikes)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        stamps = [time.perf_counter()]
        for _ in steps(problem):
            stamps.append(time.perf_counter())
    return stamps[1] - stamps[0], float(np.median(np.diff(stamps[1:])))


def history_update(terms: int, n: int, steps: int = 20) -> float:
    mat = material(terms)
    coef = step_coefficients(mat.creep, 1e-3, "linear", False)
    hist = PronyHistory.zeros(mat.creep.amplitudes.size, n)
    p = np.random.default_rng(0).random((n, n))
    start = time.perf_counter()
    for k in range(steps):
        hist.known(coef, k * 1e-3)
        hist = hist.advanced(p, coef, k * 1e-3)
    return (time.perf_counter() - start) / steps


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--only", choices=["kernel", "curve", "transient"], help="one row group only")
    args = ap.parse_args()
    n_steady, n_transient = (64, 128) if args.quick else (128, 256)
    print(f"# {platform.node()} {platform.machine()} python {platform.python_version()} numpy {np.__version__}"
          f" {time.strftime('%Y-%m-%d %H:%M')}, load average {os.getloadavg()[0]:.1f}")

    if args.only in (None, "kernel"):
        kernel_rows(n_steady)
    if args.only in (None, "curve"):
        curve_row(n_steady)
    if args.only in (None, "transient"):
        transient_rows(n_transient)


@contextmanager
def call_times(owner: object, name: str) -> Iterator[list[float]]:
    """Wall time [s] of each call of ``owner.name`` (a class's method or a module's function) while
    the context is open: the attribute is wrapped, and restored on exit."""
    original = getattr(owner, name)
    times: list[float] = []

    def timed(*args, **kwargs):
        start = time.perf_counter()
        try:
            return original(*args, **kwargs)
        finally:
            times.append(time.perf_counter() - start)

    setattr(owner, name, timed)
    try:
        yield times
    finally:
        setattr(owner, name, original)


def curve_row(n: int) -> None:
    problem = sliding(material(30), n, 1, "frictionless_sliding", 0.0)
    speeds = np.geomspace(1e-6, 1e2, 30)
    with call_times(steady, "compliance_of") as setup, call_times(HalfSpace, "steady_convolver") as kernels:
        start = time.perf_counter()
        records = steady.speed_sweep(problem, speeds)
        wall = time.perf_counter() - start
    solve = wall - sum(setup) - sum(kernels)
    mu = np.array([r.mu_app for r in records])
    print(f"\n## mu_app curve: 30 speeds 1e-6 ... 1e2 m/s, 30 terms, {n}^2, frictionless")
    print(f"wall time {wall:.1f} s ({wall / 30:.2f} s per speed); mu_app max {mu.max():.4f} at "
          f"v = {speeds[int(np.argmax(mu))]:.2g} m/s; GMRES iterations {sum(r.iterations for r in records)}")
    print("| phase | total [s] | per speed [s] |")
    print("|---|---|---|")
    print(f"| setup (compliance) | {sum(setup):.2f} | - |")
    print(f"| kernels, first speed (with the IC nodes) | {kernels[0]:.2f} | - |")
    print(f"| kernels, next {len(kernels) - 1} speeds | {sum(kernels[1:]):.2f} | "
          f"{sum(kernels[1:]) / max(len(kernels) - 1, 1):.2f} |")
    print(f"| solve (active set, GMRES, record) | {solve:.2f} | {solve / len(speeds):.2f} |")


def kernel_rows(n_steady: int) -> None:
    grid = Grid(n_steady, 1.5e-3)
    speed = 0.05
    print(f"\n## steady effective kernel, {n_steady}^2, v = {speed} m/s, components zz, zx")
    print("| terms | per-mode [s] | one-pass, first speed [s] | one-pass, next speeds [s] | max diff / max K |")
    print("|---|---|---|---|---|")
    for terms in (1, 10, 20, 30):
        c = material(terms).creep
        builder = SteadyKernelBuilder(grid, NU, ("zz", "zx"))
        t0 = time.perf_counter()
        fast = builder.history(c.amplitudes, speed * c.retardation_times)
        t1 = time.perf_counter()
        builder.history(c.amplitudes, 3 * speed * c.retardation_times)
        t2 = time.perf_counter()
        if terms in (1, 20):
            slow = {k: 0.0 for k in ("zz", "zx")}
            for amp, lam in zip(c.amplitudes, c.retardation_times):
                one = history_kernels(grid, NU, speed * lam, ("zz", "zx"))
                for k in slow:
                    slow[k] = slow[k] + amp * one[k]
            t3 = time.perf_counter()
            diff = max(float(np.abs(fast[k] - slow[k]).max() / np.abs(slow[k]).max()) for k in slow)
            per_mode, diff_txt = f"{t3 - t2:.2f}", f"{diff:.1e}"
        else:
            per_mode, diff_txt = "-", "-"
        print(f"| {terms} | {per_mode} | {t1 - t0:.2f} | {t2 - t1:.2f} | {diff_txt} |")



def transient_rows(n_transient: int) -> None:
    print(f"\n## transient gross sliding, {n_transient}^2, linear scheme, 8 steps: seconds")
    print("| terms | setup + first step, runs 1/2/3 | per further step (median), runs 1/2/3 | "
          "hereditary update alone |")
    print("|---|---|---|---|")
    results: dict[int, list[tuple[float, float]]] = {1: [], 30: []}
    for _ in range(3):
        for terms in (1, 30):
            results[terms].append(per_step(sliding(material(terms), n_transient, 8)))
    for terms in (1, 30):
        setup = " / ".join(f"{s:.2f}" for s, _ in results[terms])
        step = " / ".join(f"{p:.3f}" for _, p in results[terms])
        print(f"| {terms} | {setup} | {step} | {history_update(terms, n_transient):.4f} |")
    ratio = min(p for _, p in results[30]) / min(p for _, p in results[1])
    print(f"\nper-step growth 1 -> 30 terms: {ratio:.2f}x (target < 1.5x)")


if __name__ == "__main__":
    main()
