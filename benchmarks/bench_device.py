"""The array backends side by side: the transient on the CPU (numpy, pocketfft) and on a GPU (CuPy,
cuFFT) at large grids, alternated in one process.

    .venv/bin/python benchmarks/bench_device.py                       # 1024^2 and 2048^2, 8 steps
    .venv/bin/python benchmarks/bench_device.py --n 512 --steps 6 --cases creep

Cases (the seed material: Zener, G(0) = 1.93 MPa, G(0)/G(inf) = 10, 10 ms, nu = 0.3; sphere
R = 10 mm; through :func:`viscontact.solvers.transient.steps`, each step's record brought to the host):

``creep``   W = 0.15 N held on +-1.5 mm (``compare_tamaas.py``'s case), 0.2 ms steps;
``table1``  seed Table 1: frictionless sliding at v = 0.8 a0/tau on +-2.56 a0, W = 0.148 N, one cell
            per step (the support window and frame shifts);
``rough``   the shipped rough periodic case (``bench_rough.py``'s, its own material and surface) in gross
            sliding with its friction (mu_f = 0.5, nu = 0.3: the normal-tangential coupling iterated)
            from t = 0, one cell per step: the periodic grid, its float32 products and the wrapping
            frame on the device. At 4096^2 with ``--gpu-only`` (a CPU step there takes many seconds):

                .venv/bin/python benchmarks/bench_device.py --n 4096 --steps 6 --cases rough --gpu-only

``--scipy-lengths`` adds GPU rows with the CPU's window sides (a new cuFFT plan for every side a
creeping contact walks through) beside those on the device ladder. ``--host-cg`` adds GPU rows whose
constrained CG decides on the host every iteration (``check_every = 1``, as before the resident CG:
about sixteen reads of the device an iteration) beside the default (its scalars on the device, read
every :data:`~viscontact.numerics.arrays.DEVICE_CHECK_EVERY` iterations): the time per CG iteration
of each is the later step's time over its iterations.

Prints, per case, grid and backend: the first step (kernels, spectra, plans), the median of the
later steps, their speed-up over the CPU, the CG iterations, the largest pressure difference
against the CPU run (relative to the peak) and the memory: the process's peak resident set (CPU)
or CuPy's memory pool (GPU). Without CuPy or a CUDA device the GPU rows say so and the CPU rows are
printed alone. ``--gpu-only`` skips the CPU rows (speed-up and difference then "–").
"""
from __future__ import annotations

import argparse
import dataclasses
import platform
import resource
import time
import warnings

import numpy as np

from viscontact.numerics.arrays import CPU, ArrayBackend, cpu_fast_length, cupy_backend
from viscontact.numerics.grid import Grid
from viscontact.physics.materials import Material
from viscontact.problem.problem import NormalLoading, PiecewiseLinear, Problem, TangentialLoading, TimeStepping
from viscontact.bodies.compliance import compliance_of
from viscontact.solvers.transient import steps

A0, TAU, RADIUS = 588.7e-6, 0.01, 0.01
MATERIAL = Material.zener(1.93e6, 0.193e6, TAU, 0.3)


def problem(case: str, n: int, n_steps: int) -> Problem:
    if case == "rough":
        from bench_rough import rough_problem  # the shipped case's surface (SurfaceTopography)

        return rough_problem(n, n_steps, mode="gross_sliding")
    if case == "creep":
        grid, load, tangential, dt = Grid(n, 1.5e-3), 0.15, TangentialLoading(), 2e-4
    else:
        speed = 0.8 * A0 / TAU
        grid, load = Grid(n, 2.56 * A0), 0.148
        tangential, dt = TangentialLoading("frictionless_sliding", 0.0, 0.0, speed), grid.spacing / speed
    x, y = grid.mesh()
    return Problem(material=MATERIAL, grid=grid, gap=(x**2 + y**2) / (2 * RADIUS),
                   normal=NormalLoading("load", PiecewiseLinear.constant(load)), tangential=tangential,
                   time=TimeStepping((n_steps - 1) * dt, dt, "linear"), radius=RADIUS)


def run(pb: Problem, backend: ArrayBackend, synchronize) -> dict:
    """Times of every step (the record of each on the host), iterations, final pressure."""
    start = time.perf_counter()
    compliance = compliance_of(pb, backend=backend)
    stamps, iterations, record = [], [], None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the wake warning of a run stopped after a few steps
        for _, record in steps(pb, compliance=compliance):
            synchronize()
            stamps.append(time.perf_counter())
            iterations.append(record.iterations)
    per_step = np.diff([start] + stamps)
    return {"first": per_step[0], "step": float(np.median(per_step[1:])), "iterations": float(np.mean(iterations)),
            "pressure": record.pressure}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, nargs="+", default=[1024, 2048])
    parser.add_argument("--steps", type=int, default=8)
    parser.add_argument("--cases", default="creep,table1")
    parser.add_argument("--scipy-lengths", action="store_true",
                        help="also run the GPU with the CPU's window sides (scipy.fft.next_fast_len) instead of "
                             "the device ladder (viscontact.numerics.arrays.device_fast_length)")
    parser.add_argument("--gpu-only", action="store_true",
                        help="no CPU rows (grids where a CPU step takes too long); needs a CUDA device")
    parser.add_argument("--host-cg", action="store_true",
                        help="also run the GPU with the CG's decisions on the host every iteration (check_every = 1)")
    args = parser.parse_args()

    try:
        gpu = cupy_backend()
        import cupy

        pool = cupy.get_default_memory_pool()
        device = cupy.cuda.runtime.getDeviceProperties(cupy.cuda.Device().id)["name"].decode()

        def sync() -> None:
            cupy.cuda.Device().synchronize()
    except ImportError as exc:
        gpu, device = None, f"none ({exc})"
    print(f"# {platform.machine()} {platform.processor() or ''}, GPU: {device}, {time.strftime('%Y-%m-%d %H:%M')}")
    print("| case | grid x steps | backend | first step [s] | later step [ms] | speed-up | CG it/step | ms per CG "
          "iteration | max dp / peak | memory [MiB] |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for case in args.cases.split(","):
        for n in args.n:
            pb = problem(case, n, args.steps)
            cpu = None
            if not (args.gpu_only and gpu is not None):
                cpu = run(pb, CPU, lambda: None)
                rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
                print(f"| {case} | {n}² × {args.steps} | cpu | {cpu['first']:.2f} | {1e3 * cpu['step']:.1f} | 1 | "
                      f"{cpu['iterations']:.1f} | {1e3 * cpu['step'] / cpu['iterations']:.2f} | 0 | "
                      f"{rss:.0f} (process peak) |")
            if gpu is None:
                print(f"| {case} | {n}² × {args.steps} | gpu | no CUDA device | | | | | | |")
                continue
            rows = [("gpu", gpu)]
            if args.scipy_lengths:  # the windows of the CPU: a new cuFFT plan for every new side
                rows.append(("gpu, scipy lengths", dataclasses.replace(gpu, fast_length=cpu_fast_length)))
            if args.host_cg:  # the CG's decisions on the host, a read of the device each
                rows.append(("gpu, host CG", dataclasses.replace(gpu, check_every=1)))
            for label, backend in rows:
                pool.free_all_blocks()
                ours = run(pb, backend, sync)
                if cpu is None:
                    diff = speedup = "–"
                else:
                    diff = f"{float(np.max(np.abs(ours['pressure'] - cpu['pressure']))) / np.max(cpu['pressure']):.1e}"
                    speedup = f"{cpu['step'] / ours['step']:.1f}"
                print(f"| {case} | {n}² × {args.steps} | {label} | {ours['first']:.2f} | {1e3 * ours['step']:.1f} | "
                      f"{speedup} | {ours['iterations']:.1f} | "
                      f"{1e3 * ours['step'] / ours['iterations']:.2f} | {diff} | "
                      f"{pool.total_bytes() / 2**20:.0f} (CuPy pool) |")


if __name__ == "__main__":
    main()
