"""DC-FFT: linear (non-periodic) convolution of grid tractions with influence coefficients.

Liu, Wang & Liu (2000), "A versatile method of discrete convolution and FFT (DC-FFT) for contact
analyses", Wear 243. The n x n traction is zero-padded to 2n x 2n, the kernel is laid out on the
2n x 2n offset grid in wrap-around order, and the product of their real FFTs gives the exact
aperiodic discrete convolution. Kernel spectra are computed once per grid and reused.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, Mapping

import numpy as np
import scipy.fft

from .grid import Grid
from .kernels import influence_coefficients


@dataclass(frozen=True)
class Convolver:
    """Applies influence coefficients by DC-FFT.

    Attributes
    ----------
    n
        Cells per side of the grid.
    spectra
        Real-FFT spectra (2n, n+1) of the kernels, by name (``zz``, ``xx``, ``xz``, ``zx``, or any
        other kernel such as the steady-state effective ones).
    workers
        ``scipy.fft`` worker threads (-1: all cores).
    """

    n: int
    spectra: Mapping[str, np.ndarray]
    workers: int = -1
    kernels: Mapping[str, np.ndarray] | None = None  # real-space, centred (see apply_sparse)

    @classmethod
    def from_kernels(cls, n: int, kernels: Mapping[str, np.ndarray], workers: int = -1) -> "Convolver":
        """Spectra of kernels given on the (2n, 2n) offset grid (the kernels are kept for
        :meth:`apply_sparse`)."""
        centred = {k: np.roll(v, (n - 1, n - 1), axis=(0, 1)) for k, v in kernels.items()}
        return cls(n, {k: scipy.fft.rfft2(v, workers=workers) for k, v in kernels.items()}, workers, centred)

    def apply_sparse(self, name: str, field: np.ndarray) -> np.ndarray:
        """Same as :meth:`apply` for a field with few non-zeros, by direct sum of kernel blocks
        (cheaper than a transform for up to ~50 points). ``kernels`` are stored centred: offset
        (i - r) sits at index i - r + n - 1, so the block of a source (r, c) is a plain slice."""
        n = self.n
        rows, cols = np.nonzero(field)
        kernel = self.kernels[name]
        out = np.zeros((n, n))
        for r, c in zip(rows, cols):
            out += field[r, c] * kernel[n - 1 - r: 2 * n - 1 - r, n - 1 - c: 2 * n - 1 - c]
        return out

    @classmethod
    def for_grid(cls, grid: Grid, poisson_ratio: float, workers: int = -1,
                 components: Iterable[str] = ("zz", "xx", "xz", "zx")) -> "Convolver":
        """Convolver of the half-space influence coefficients at unit shear modulus."""
        ics = influence_coefficients(grid, poisson_ratio)
        return cls.from_kernels(grid.n, {c: ics[c] for c in components}, workers)

    def spectrum(self, field: np.ndarray) -> np.ndarray:
        """Real FFT of ``field`` (n, n) zero-padded to (2n, 2n)."""
        return scipy.fft.rfft2(field, s=(2 * self.n, 2 * self.n), workers=self.workers)

    def inverse(self, spectrum: np.ndarray) -> np.ndarray:
        """The (n, n) physical block of the inverse transform of a (2n, n+1) spectrum (which it
        may overwrite: pass a temporary)."""
        out = scipy.fft.irfft2(spectrum, s=(2 * self.n, 2 * self.n), workers=self.workers, overwrite_x=True)
        return out[: self.n, : self.n]

    def apply(self, name: str, field: np.ndarray) -> np.ndarray:
        """sum_j K_name(x_i - x_j) field_j [m per unit modulus]."""
        return self.inverse(self.spectra[name] * self.spectrum(field))

    def combine(self, terms: Iterable[tuple[str, float, np.ndarray]]) -> np.ndarray:
        """sum over terms of factor * (K_name * field), with one inverse transform.

        ``terms`` holds (kernel name, scalar factor, field). Fields that are entirely zero are
        skipped; so are kernels missing from ``spectra`` (e.g. the coupling ones when nu = 0.5).
        """
        acc = None
        for name, factor, field in terms:
            if factor == 0 or name not in self.spectra or not np.any(field):
                continue
            contrib = (factor * self.spectra[name]) * self.spectrum(field)
            acc = contrib if acc is None else acc + contrib
        if acc is None:
            return np.zeros((self.n, self.n))
        return self.inverse(acc)


def direct_convolution(kernel: np.ndarray, field: np.ndarray) -> np.ndarray:
    """Reference O(n^4) sum u_i = sum_j K(x_i - x_j) f_j with ``kernel`` on the offset grid."""
    n = field.shape[0]
    out = np.zeros_like(field, dtype=float)
    for jy in range(n):
        for jx in range(n):
            if field[jy, jx] == 0:
                continue
            iy = (np.arange(n)[:, None] - jy) % (2 * n)
            ix = (np.arange(n)[None, :] - jx) % (2 * n)
            out += kernel[iy, ix] * field[jy, jx]
    return out


def coupled_displacements(conv: Convolver, normal: np.ndarray, shear: np.ndarray | None,
                          need_x: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
    """(u_z, u_x) of normal and shear (x) tractions through the semi-coupled kernels (seed Eq. 6),
    at unit modulus. Each traction is transformed once; ``u_x`` is None when not needed."""
    p_hat = conv.spectrum(normal)
    q_hat = conv.spectrum(shear) if shear is not None and np.any(shear) else None
    uz_hat = conv.spectra["zz"] * p_hat
    if q_hat is not None and "zx" in conv.spectra:
        uz_hat = uz_hat + conv.spectra["zx"] * q_hat
    u_z = conv.inverse(uz_hat)
    if not need_x:
        return u_z, None
    ux_hat = conv.spectra["xz"] * p_hat if "xz" in conv.spectra else np.zeros_like(p_hat)
    if q_hat is not None:
        ux_hat = ux_hat + conv.spectra["xx"] * q_hat
    return u_z, conv.inverse(ux_hat)


@dataclass(frozen=True)
class FourierPreconditioner:
    """Approximate inverse of a convolution operator: r -> F^-1[F[r] / K^] on the periodic n x n grid.

    K^ is the spectrum of the kernel wrapped periodically on the n x n grid (its symmetric part), so
    applying it costs a quarter of a DC-FFT convolution. It is the classical Fourier preconditioner of
    boundary-element contact solvers: the half-space operator is diagonal in Fourier space,
    |k|^-1 up to a constant, and the preconditioned system has a bounded condition number.
    """

    inverse_symbol: np.ndarray
    workers: int = -1

    @classmethod
    def for_kernel(cls, kernel: np.ndarray, factor: float = 1.0, workers: int = -1) -> "FourierPreconditioner":
        """From a kernel on the (2n, 2n) DC-FFT offset grid, times the scalar ``factor``."""
        n = kernel.shape[0] // 2
        idx = np.arange(n)
        idx = np.where(idx <= n // 2, idx, idx + n)  # offsets 0..n/2, then -(n/2-1)..-1
        wrapped = kernel[np.ix_(idx, idx)]
        symbol = factor * np.abs(scipy.fft.rfft2(wrapped, workers=workers).real)
        symbol = np.maximum(symbol, symbol.max() * 1e-12)
        return cls(1.0 / symbol, workers)

    def __call__(self, residual: np.ndarray) -> np.ndarray:
        n = residual.shape
        return scipy.fft.irfft2(self.inverse_symbol * scipy.fft.rfft2(residual, workers=self.workers), s=n,
                                workers=self.workers)
