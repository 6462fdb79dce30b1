"""Candidate FFT backends for the DC-FFT convolution: time per transform pair, measured alternately.

    .venv/bin/python benchmarks/fft_backends.py --n 256            # needs the `bench` extra (pyFFTW)

One "pair" is what a CG iteration pays per application of the influence matrix: the real FFT of an
(n, n) traction zero-padded to (2n, 2n), a product with a kernel spectrum, and the inverse real FFT
of which only the (n, n) physical block is kept. Candidates:

``scipy``        ``scipy.fft.rfft2(s=(2n, 2n))`` / ``irfft2`` then a slice (today's ``Convolver``), workers 1 / 2
``numpy``        ``numpy.fft`` (pocketfft, one thread)
``fftw``         pyFFTW, planned (FFTW_MEASURE) 2-D real transforms on pre-allocated aligned buffers,
                 padding zeros kept in the input buffer (only the block is copied in), threads 1 / 2
``scipy-zb``     ``viscontact.numerics.fftbackends.ZeroBlockTransforms``: forward = real FFT of the n non-zero
                 rows (length 2n) then the complex FFT of length 2n down the n + 1 columns; inverse =
                 the complex inverse down the columns, then the inverse real FFT of the n kept rows
                 only (half of the row transforms both ways)
``fftw-zb``      ``viscontact.numerics.fftbackends.FFTWTransforms``: the same scheme, planned pyFFTW transforms on
                 pre-allocated buffers

Each candidate is checked against ``scipy`` (max relative difference printed) and timed over
``--reps`` pairs, all candidates in turn, ``--rounds`` times; the table gives the median wall and
CPU (process, all threads) time per pair and their ratios to today's ``scipy`` with 2 workers (the
CPU figure is the one that survives a loaded machine). The load average is printed with the table.
"""
from __future__ import annotations

import argparse
import os
import time
from typing import Callable

import numpy as np
import scipy.fft

from viscontact.numerics.fftbackends import FFTWTransforms, ZeroBlockTransforms


def scipy_pair(n: int, workers: int) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    def pair(field: np.ndarray, kernel_hat: np.ndarray) -> np.ndarray:
        spec = scipy.fft.rfft2(field, s=(2 * n, 2 * n), workers=workers)
        spec *= kernel_hat
        return scipy.fft.irfft2(spec, s=(2 * n, 2 * n), workers=workers, overwrite_x=True)[:n, :n]
    return pair


def numpy_pair(n: int) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    def pair(field: np.ndarray, kernel_hat: np.ndarray) -> np.ndarray:
        spec = np.fft.rfft2(field, s=(2 * n, 2 * n))
        spec *= kernel_hat
        return np.fft.irfft2(spec, s=(2 * n, 2 * n))[:n, :n]
    return pair


def module_pair(transforms) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    """A pair through :mod:`viscontact.numerics.fftbackends` (the zero-block transforms the solver uses)."""
    return lambda field, kernel_hat: transforms.convolve(kernel_hat, field)


def fftw_pair(n: int, threads: int) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    import pyfftw

    real = pyfftw.empty_aligned((2 * n, 2 * n), dtype="float64")
    spec = pyfftw.empty_aligned((2 * n, n + 1), dtype="complex128")
    forward = pyfftw.FFTW(real, spec, axes=(0, 1), direction="FFTW_FORWARD", flags=("FFTW_MEASURE",),
                          threads=threads)
    backward = pyfftw.FFTW(spec, real, axes=(0, 1), direction="FFTW_BACKWARD",
                           flags=("FFTW_MEASURE", "FFTW_DESTROY_INPUT"), threads=threads)
    real[:] = 0.0
    out = np.empty((n, n))

    def pair(field: np.ndarray, kernel_hat: np.ndarray) -> np.ndarray:
        real[n:, :] = 0.0
        real[:n, n:] = 0.0
        real[:n, :n] = field
        forward()
        np.multiply(spec, kernel_hat, out=spec)
        backward()  # normalised by pyFFTW (1 / (2n)^2)
        out[:] = real[:n, :n]
        return out
    return pair


def candidates(n: int) -> dict[str, Callable]:
    out = {"scipy w=2": scipy_pair(n, 2), "scipy w=1": scipy_pair(n, 1), "numpy": numpy_pair(n),
           "scipy-zb w=2": module_pair(ZeroBlockTransforms(n, 2)),
           "scipy-zb w=1": module_pair(ZeroBlockTransforms(n, 1))}
    try:
        import pyfftw  # noqa: F401
    except ImportError:
        print("pyFFTW missing (pip install -e '.[bench]'): its rows are skipped")
        return out
    out.update({"fftw t=2": fftw_pair(n, 2), "fftw t=1": fftw_pair(n, 1),
                "fftw-zb t=2": module_pair(FFTWTransforms(n, 2)), "fftw-zb t=1": module_pair(FFTWTransforms(n, 1))})
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=256)
    ap.add_argument("--reps", type=int, default=20, help="pairs per timing")
    ap.add_argument("--rounds", type=int, default=7, help="alternated rounds over all candidates")
    args = ap.parse_args()
    n = args.n
    rng = np.random.default_rng(0)
    field = np.zeros((n, n))
    field[n // 4: 3 * n // 4, n // 4: 3 * n // 4] = rng.random((n // 2, n // 2))
    kernel = rng.random((2 * n, 2 * n))
    kernel_hat = scipy.fft.rfft2(kernel)
    pairs = candidates(n)
    reference = scipy_pair(n, 1)(field, kernel_hat).copy()
    errors = {k: float(np.abs(f(field, kernel_hat) - reference).max() / np.abs(reference).max())
              for k, f in pairs.items()}
    times: dict[str, list[float]] = {k: [] for k in pairs}
    cpu: dict[str, list[float]] = {k: [] for k in pairs}
    load0 = os.getloadavg()[0]
    for _ in range(args.rounds):
        for name, pair in pairs.items():
            start, start_cpu = time.perf_counter(), time.process_time()
            for _ in range(args.reps):
                pair(field, kernel_hat)
            times[name].append((time.perf_counter() - start) / args.reps)
            cpu[name].append((time.process_time() - start_cpu) / args.reps)
    load1 = os.getloadavg()[0]
    base, base_cpu = float(np.median(times["scipy w=2"])), float(np.median(cpu["scipy w=2"]))
    print(f"# DC-FFT pair (rfft2 of (n, n) padded to (2n, 2n), product, irfft2 block), n = {n}, "
          f"{os.cpu_count()} cores, load average {load0:.2f} -> {load1:.2f}, {time.strftime('%Y-%m-%d %H:%M')}")
    print("| backend | wall ms/pair (median) | min | wall vs scipy w=2 | CPU ms/pair (median) | CPU vs scipy w=2 "
          "| max rel. diff |")
    print("|---|---|---|---|---|---|---|")
    for name, ts in times.items():
        med, med_cpu = float(np.median(ts)), float(np.median(cpu[name]))
        print(f"| {name} | {1e3 * med:.2f} | {1e3 * min(ts):.2f} | {base / med:.2f}x | {1e3 * med_cpu:.2f} "
              f"| {base_cpu / med_cpu:.2f}x | {errors[name]:.0e} |")


if __name__ == "__main__":
    main()
