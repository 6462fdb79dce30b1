"""DC-FFT: linear (non-periodic) convolution of grid tractions with influence coefficients.

Liu, Wang & Liu (2000), "A versatile method of discrete convolution and FFT (DC-FFT) for contact
analyses", Wear 243. The n x n traction is zero-padded to 2n x 2n, the kernel is laid out on the
2n x 2n offset grid in wrap-around order, and the product of their real FFTs gives the exact
aperiodic discrete convolution. Kernel spectra are computed once per grid and reused.

On a line grid (one row of n cells, plane strain) the same code is the 1-D DC-FFT: the (1, n) field
is padded to (1, 2n) only, the kernel lies on the 2n offsets along x, and the transforms are
one-dimensional (:func:`~viscontact.numerics.fftbackends.padded_rows`). Shapes below are written for
the square grid; read (rows, n) for (n, n) and (padded rows, 2n) for (2n, 2n).
"""
from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from dataclasses import field as dataclass_field
from types import ModuleType
from typing import ClassVar, Iterable, Mapping

import numpy as np
import scipy.fft

from viscontact.numerics.fftbackends import DCFFTTransforms, ZeroBlockTransforms, fft_keywords, padded_rows


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
        FFT worker threads (-1: all cores above 512^2 cells, one below: :func:`~viscontact.numerics.fftbackends.fft_threads`).
    kernels
        Real-space kernels, centred (see :meth:`apply_sparse`).
    xp, fft
        Array namespace and FFT backend (``numpy`` and ``scipy.fft``; any module with the same
        ``rfft2``/``irfft2`` signatures, e.g. ``cupyx.scipy.fft`` with ``cupy``).
    transforms
        The DC-FFT transforms of the fields (:mod:`viscontact.numerics.fftbackends`): by default the
        zero-block transforms with ``fft`` and ``workers``, which skip the zero half of the padded
        input and the discarded half of the output (the kernel spectra above are full 2-D
        transforms, made once).

    ``apply`` and ``combine`` take ``single=True`` for the product in single precision (float32
    fields, complex64 spectra made from ``spectra`` on first use): half the transform time, with a
    relative error of about 1e-7 of the result's scale. That is for increments of a field whose
    product is otherwise kept in double (:func:`~viscontact.numerics.constrained.constrained_cg`'s search
    directions): the error is then relative to the increment, not to the solution.
    """

    n: int
    spectra: Mapping[str, np.ndarray]
    workers: int = -1
    kernels: Mapping[str, np.ndarray] | None = None
    xp: ModuleType = np
    fft: ModuleType = scipy.fft
    transforms: DCFFTTransforms | None = dataclass_field(default=None, compare=False, repr=False)
    #: complex64 copies of ``spectra`` made by the first single-precision product of each kernel
    single_spectra: dict[str, np.ndarray] = dataclass_field(default_factory=dict, compare=False, repr=False)
    rows: int | None = None
    #: non-zeros up to which :meth:`apply_sparse` costs less than one double-precision product: a padded
    #: product transforms four times the grid, a direct sum two passes over it a point (measured at
    #: 256^2 and 512^2, with the window sides between: 24 points cost 0.5-0.6 of a product,
    #: ``benchmarks/sparse_products.py``)
    sparse_limit: ClassVar[int] = 48

    def __post_init__(self) -> None:
        if self.rows is None:
            object.__setattr__(self, "rows", self.n)
        if self.transforms is None:
            object.__setattr__(self, "transforms", ZeroBlockTransforms(self.n, self.workers, self.fft, rows=self.rows))

    @property
    def shape(self) -> tuple[int, int]:
        """Shape (rows, n) of the fields."""
        return (self.rows, self.n)

    @classmethod
    def from_kernels(cls, n: int, kernels: Mapping[str, np.ndarray], workers: int = -1, *,
                     xp: ModuleType = np, fft: ModuleType = scipy.fft,
                     transforms: DCFFTTransforms | None = None) -> "Convolver":
        """Spectra of kernels given on the (2n, 2n) offset grid, numpy arrays or fields of ``xp`` (moved
        there first; the kernels are kept for :meth:`apply_sparse`). Kernels of one row (1, 2n) make
        the convolver of a line grid."""
        kernels = {k: xp.asarray(v) for k, v in kernels.items()}
        rows = n if next(iter(kernels.values())).shape[0] > 1 else 1
        centred = {k: xp.roll(v, (rows - 1, n - 1), axis=(0, 1)) for k, v in kernels.items()}
        threads = fft_keywords(fft, workers, 2 * padded_rows(rows) * n)
        return cls(n, {k: fft.rfft2(v, **threads) for k, v in kernels.items()}, workers, centred, xp, fft, transforms,
                   rows=rows)

    def apply_sparse(self, name: str, field: np.ndarray, factor: float = 1.0) -> np.ndarray:
        """Same as :meth:`apply` (times ``factor``) for a field with few non-zeros, by direct sum of
        kernel blocks (cheaper than a transform for up to a few dozen points). ``kernels`` are stored
        centred: offset (i - r) sits at index i - r + n - 1, so the block of a source (r, c) is a plain
        slice. The factor scales the source values, and each block is scaled in a work array reused
        over the sources: two passes over the grid a source, no temporaries. The sources are found
        in a boolean mask (a float field's ``nonzero`` scans 15-20 times slower: at 512^2 1.3 ms,
        half a product, against 0.06 ms)."""
        n, m, xp = self.n, self.rows, self.xp
        flat = xp.flatnonzero(field != 0)
        kernel = self.kernels[name]
        out = xp.zeros((m, n))
        if not len(flat):
            return out
        rows, cols = xp.divmod(flat, n)
        scaled = xp.empty((m, n))
        for r, c, value in zip(rows.tolist(), cols.tolist(), (factor * field[rows, cols]).tolist()):
            out += xp.multiply(kernel[m - 1 - r: 2 * m - 1 - r, n - 1 - c: 2 * n - 1 - c], value, out=scaled)
        return out

    def window_kernels(self, m: int, names: Iterable[str]) -> dict[str, np.ndarray]:
        """The kernels ``names`` on the (2m, 2m) offset grid (wrap-around order) of an m x m window of
        this n x n grid, m < n: translation invariance makes the offsets -(m-1)..m-1 a window needs a
        crop of the centred kernels (offset d at index d + n - 1); the one unused offset (+-m) holds
        the kernel at -m."""
        n = self.n
        if not 0 < m < n:
            raise ValueError(f"window side must be in 1..{n - 1}, got {m}")
        return {k: self.xp.roll(self.kernels[k][n - 1 - m: n - 1 + m, n - 1 - m: n - 1 + m], (m, m), axis=(0, 1))
                for k in names}

    def spectrum(self, field: np.ndarray) -> np.ndarray:
        """Real FFT (2n, n+1) of ``field`` (n, n) zero-padded to (2n, 2n)."""
        return self.transforms.forward(field)

    def inverse(self, spectrum: np.ndarray) -> np.ndarray:
        """The (n, n) physical block of the inverse transform of a (2n, n+1) spectrum (which it
        may overwrite: pass a temporary)."""
        return self.transforms.inverse(spectrum)

    def kernel_spectrum(self, name: str, single: bool = False) -> np.ndarray:
        """The spectrum of kernel ``name``: ``spectra[name]``, or its complex64 copy (kept) when
        ``single``."""
        if not single:
            return self.spectra[name]
        if name not in self.single_spectra:
            self.single_spectra[name] = self.spectra[name].astype(np.complex64)
        return self.single_spectra[name]

    def apply(self, name: str, field: np.ndarray, *, single: bool = False) -> np.ndarray:
        """sum_j K_name(x_i - x_j) field_j [m per unit modulus]; in float32 when ``single`` (class
        docstring)."""
        return self.transforms.convolve(self.kernel_spectrum(name, single), operand(field, single))

    def combine(self, terms: Iterable[tuple[str, float, np.ndarray]], *, single: bool = False) -> np.ndarray:
        """sum over terms of factor * (K_name * field), with one inverse transform (in float32 when
        ``single``: class docstring).

        ``terms`` holds (kernel name, scalar factor, field); each distinct field is transformed once
        (a body of several kernels applies them all to the same traction). Fields that are entirely
        zero are skipped; so are kernels missing from ``spectra`` (e.g. the coupling ones when nu = 0.5).
        """
        acc = None
        transforms: dict[int, np.ndarray] = {}
        for name, factor, field in terms:
            if factor == 0 or name not in self.spectra or not self.xp.any(field):
                continue
            if id(field) not in transforms:
                transforms[id(field)] = self.spectrum(operand(field, single))
            contrib = (factor * self.kernel_spectrum(name, single)) * transforms[id(field)]
            acc = contrib if acc is None else acc + contrib
        if acc is None:
            return self.xp.zeros(self.shape)
        return self.inverse(acc)

    def displacements(self, terms: Iterable[tuple[str, str, np.ndarray]],
                      outputs: Iterable[str]) -> dict[str, np.ndarray]:
        """sum over terms of K_name * field, per output component, each distinct field transformed once.

        ``terms`` holds (output component, kernel name, field), accumulated in the given order;
        fields that are entirely zero and kernels missing from ``spectra`` are skipped. Returns
        one (n, n) array per name in ``outputs`` (zeros where no term contributes).
        """
        terms = [(out, name, field) for out, name, field in terms if name in self.spectra]
        uses = Counter(id(field) for _, _, field in terms)
        transforms: dict[int, np.ndarray | None] = {}
        acc: dict[str, np.ndarray] = {}
        for out, name, field in terms:
            key = id(field)
            if key not in transforms:
                transforms[key] = self.spectrum(field) if self.xp.any(field) else None
            if transforms[key] is None:
                continue
            if out not in acc and uses[key] == 1:  # the transform serves this term only: scaled in place
                acc[out] = transforms[key]
                acc[out] *= self.spectra[name]
            else:
                contrib = self.spectra[name] * transforms[key]
                if out in acc:
                    acc[out] += contrib
                else:
                    acc[out] = contrib
        return {o: self.inverse(acc[o]) if o in acc else self.xp.zeros(self.shape) for o in outputs}


def operand(field: np.ndarray, single: bool) -> np.ndarray:
    """``field`` as a transform takes it: float32 for a single-precision product, else as it is."""
    return field.astype(np.float32, copy=False) if single else field


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
    at unit modulus (:meth:`Convolver.displacements`); ``u_x`` is None when not needed."""
    terms = [("z", "zz", normal)]
    if shear is not None:
        terms += [("z", "zx", shear), ("x", "xz", normal), ("x", "xx", shear)]
    else:
        terms += [("x", "xz", normal)]
    u = conv.displacements(terms, ("z", "x") if need_x else ("z",))
    return u["z"], u.get("x")


@dataclass(frozen=True)
class FourierPreconditioner:
    """Approximate inverse of a convolution operator: r -> F^-1[F[r] / K^] on the periodic n x n grid.

    K^ is the spectrum of the kernel wrapped periodically on the n x n grid (its symmetric part), so
    applying it costs a quarter of a DC-FFT convolution (threads: :func:`~viscontact.numerics.fftbackends.fft_threads`).
    It is the classical Fourier preconditioner of boundary-element contact solvers: the half-space operator is diagonal in Fourier space,
    ``|k|^-1`` up to a constant, and the preconditioned system has a bounded condition number.
    """

    inverse_symbol: np.ndarray
    workers: int = -1
    fft: ModuleType = scipy.fft

    @classmethod
    def for_kernel(cls, kernel: np.ndarray, factor: float = 1.0, workers: int = -1, *,
                   fft: ModuleType = scipy.fft) -> "FourierPreconditioner":
        """From a kernel on the (2n, 2n) DC-FFT offset grid (a field of ``fft``'s library), times the
        scalar ``factor``; a kernel of one row (1, 2n), that of a line grid."""
        n = kernel.shape[1] // 2
        half = n // 2 + 1  # offsets 0..n/2, then -(n/2-1)..-1 (at n + n/2 + 1 .. 2n - 1)
        wrapped = np.concatenate((kernel[:half], kernel[n + half:]), axis=0) if kernel.shape[0] > 1 else kernel
        wrapped = np.concatenate((wrapped[:, :half], wrapped[:, n + half:]), axis=1)
        symbol = factor * np.abs(fft.rfft2(wrapped, **fft_keywords(fft, workers, wrapped.size)).real)
        symbol = np.maximum(symbol, symbol.max() * 1e-12)
        return cls(1.0 / symbol, workers, fft)

    def single(self) -> "FourierPreconditioner":
        """The same preconditioner in single precision (float32 transforms: half the time; a
        preconditioner needs no more than a few digits)."""
        return FourierPreconditioner(self.inverse_symbol.astype(np.float32), self.workers, self.fft)

    def __call__(self, residual: np.ndarray) -> np.ndarray:
        """F^-1[F[residual] / K^] (in float32 when ``inverse_symbol`` is: :meth:`single`)."""
        threads = fft_keywords(self.fft, self.workers, residual.size)
        if self.inverse_symbol.dtype == np.float32:  # the single-precision preconditioner
            residual = residual.astype(np.float32, copy=False)
        spectrum = self.fft.rfft2(residual, **threads)
        spectrum *= self.inverse_symbol
        return self.fft.irfft2(spectrum, s=residual.shape, overwrite_x=True, **threads)
