"""Periodic domain: influence coefficients of a uniformly loaded cell and the unpadded FFT engine.

The grid [-w, w)^2 (n x n cells of side dx = 2w/n) is one period of an infinitely repeated surface.
The periodic influence coefficient of the cell at the origin is the sum over its images,

    K_per(d) = sum_{L in 2w Z^2} K_cell(d + L),   K_cell(d) = int_cell G(d - x') dx'   (kernels.py),

which diverges for the even kernels (1/r) and converges only conditionally for the odd ones, so it
is defined by its Fourier series over the reciprocal lattice Q in (pi/w) Z^2, A = 4 w^2:

    K_per(d) = (1/A) sum_{Q != 0} G^(Q) F(Q) exp(i Q.d),   F(Q) = dx^2 sinc(Qx dx/2) sinc(Qy dx/2)

with the surface compliance of the half-space at unit shear modulus (Johnson, *Contact Mechanics*
1985, Secs. 3.2-3.3, Fourier transforms of Eqs. 3.19-3.20 and 3.86-3.87; forward transform
f^(Q) = int f exp(-i Q.x) dx; displacement u = K * traction / G):

    G^_zz = (1 - nu) / |Q|                 (stiffness G |Q| / (1 - nu) = E* |Q| / 2, E* = 2G/(1-nu))
    G^_xx = (1 - nu Qx^2 / Q^2) / |Q|
    G^_xz = (1 - 2 nu) i Qx / (2 Q^2) = -G^_zx.

F is the footprint of the uniformly loaded cell collocated at cell centres (one sinc per direction:
the displacement is taken at the centre of each cell as in kernels.py, not averaged over it, which
would give sinc^2). The sum over Q converges slowly (aliases decay like 1/|Q|^2), so it is split
exactly, Ewald-fashion, through the Gaussian (Mellin) representations of the three kernel shapes,
1/r, x^2/r^3 and x/r^2: with z = alpha r and P(a, z^2) the regularised lower incomplete gamma,

    1/r     = P(1/2, z^2)/r        + Q(1/2, z^2)/r       <->  2 pi erfc(b)/q + ...,
    x^2/r^3 = x^2 P(3/2, z^2)/r^3  + x^2 Q(3/2, z^2)/r^3 <->  2 pi [erfc(b) qy^2/q^3 - (2/sqrt(pi)) b exp(-b^2) qx^2/q^3] + ...,
    x/r^2   = x P(1, z^2)/r^2      + x Q(1, z^2)/r^2     <->  -2 pi i qx exp(-b^2)/q^2 + ...,   b = q / (2 alpha).

The first ("long") parts are smooth in real space and decay like a Gaussian in Fourier space: their
periodic sum is a Fourier series truncated at |Q| ~ 13 alpha (exact to ~1e-17, a few aliases of
the grid's band). The second ("short") parts decay like a Gaussian in real space: their cell
integral is the closed form of kernels.py minus a Gauss-Legendre quadrature of the smooth long part,
and their periodic sum is a direct sum over the offsets within ~6.5/alpha. With alpha = 1/dx both
parts cost O(n^2). Nothing is truncated above round-off; the result does not depend on alpha
(tested), which checks both halves against each other.

Conventions (the q = 0 mode). The mean displacement of a periodic half-space under a net load is
unbounded (the Q = 0 compliance is infinite), so every periodic kernel here has zero mean: the
displacements it returns have zero mean over the period. The approach delta_z is then measured from
the mean plane of the deformed surface: the gap is g = h0 + u - delta_z with mean(u) = 0, so
mean(g) = mean(h0) - delta_z. Under load control the total force on one period fixes the pressure and
delta_z is the multiplier of the force constraint (constrained_cg's). Under displacement control the
approach must stay below mean(h0): at delta_z = mean(h0) the contact is complete and its load is
undetermined (use load control for complete contact). Tangentially, a uniform shear is in the null
space of the xx kernel: under a prescribed delta_x (partial slip) only q_x = 0 out of contact fixes
the mean shear, and a contact covering the period is refused
(:func:`viscontact.solvers.contact_laws.check_not_full_contact`).
"""
from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType
from typing import ClassVar, Iterable, Mapping

import numpy as np
import scipy.fft

from viscontact.errors import ParameterError
from viscontact.numerics.convolution import Convolver, FourierPreconditioner, operand
from viscontact.numerics.fftbackends import fft_keywords
from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import COMPONENTS, rectangle_influence

#: screening parameter alpha of the Ewald split, in units of 1/dx
SCREENING = 1.0
#: both halves of the split are summed until their Gaussian factor is below exp(-EWALD_RANGE^2)
EWALD_RANGE = 6.5
_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(12)


def half_space_compliance(qx: np.ndarray, qy: np.ndarray, poisson_ratio: float,
                          components: Iterable[str] = COMPONENTS) -> dict[str, np.ndarray]:
    """Fourier-space surface compliance G^(q) [m per (Pa m^2)] at unit shear modulus, for wave
    vectors (qx, qy) [rad/m], q != 0 (Johnson 1985; see the module docstring). The value at q = 0
    is returned as 0 (zero-mean convention)."""
    return _spectral(qx, qy, poisson_ratio, np.inf, components)


def _spectral(qx: np.ndarray, qy: np.ndarray, nu: float, alpha: float,
              components: Iterable[str]) -> dict[str, np.ndarray]:
    """Long-range part of G^ with screening ``alpha`` [1/m] (alpha = inf: the whole of it)."""
    qx, qy = np.broadcast_arrays(np.asarray(qx, dtype=float), np.asarray(qy, dtype=float))
    q2 = qx**2 + qy**2
    zero = q2 == 0
    q2s = np.where(zero, 1.0, q2)
    q = np.sqrt(q2s)
    b = q / (2.0 * alpha)
    from scipy.special import erfc  # imported where used: scipy.special weighs several MiB, periodic grids only

    screen_even = erfc(b)          # of 1/r
    gauss = np.exp(-b * b)         # of x/r^2
    cos2 = qx**2 / q2s
    out: dict[str, np.ndarray] = {}
    for c in components:
        if c == "zz":
            v = (1 - nu) * screen_even / q
        elif c == "xx":
            v = (screen_even * (1 - nu * cos2) - (2 * nu / np.sqrt(np.pi)) * cos2 * b * gauss) / q
        elif c in ("xz", "zx"):
            v = (1 if c == "xz" else -1) * (1 - 2 * nu) * 1j * qx * gauss / (2 * q2s)
        else:
            raise ValueError(f"unknown kernel component {c!r}; expected one of {COMPONENTS}")
        out[c] = np.where(zero, 0.0, v)
    return out


def _long_point_force(x: np.ndarray, y: np.ndarray, nu: float, alpha: float,
                      components: Iterable[str]) -> dict[str, np.ndarray]:
    """Real-space long-range part of the point-force displacements [m per N] at G = 1 Pa: the
    kernels of :func:`viscontact.physics.kernels.point_force_displacement` times P(a, alpha^2 r^2); smooth."""
    r2 = x**2 + y**2
    r2s = np.where(r2 > 0, r2, 1.0)
    r = np.sqrt(r2s)
    z2 = alpha**2 * r2
    # P(1/2, z^2)/r -> 2 alpha / sqrt(pi) at r = 0; the other two vanish there
    from scipy.special import gammainc  # imported where used (see _spectral)

    inv_r = np.where(r2 > 0, gammainc(0.5, z2) / r, 2 * alpha / np.sqrt(np.pi))
    x2_r3 = np.where(r2 > 0, x**2 * gammainc(1.5, z2) / (r * r2s), 0.0)
    x_r2 = np.where(r2 > 0, x * gammainc(1.0, z2) / r2s, 0.0)
    values = {"zz": (1 - nu) / (2 * np.pi) * inv_r,
              "xx": ((1 - nu) * inv_r + nu * x2_r3) / (2 * np.pi),
              "xz": -(1 - 2 * nu) / (4 * np.pi) * x_r2,
              "zx": (1 - 2 * nu) / (4 * np.pi) * x_r2}
    return {c: values[c] for c in components}


def periodic_influence_coefficients(grid: Grid, poisson_ratio: float, components: Iterable[str] = COMPONENTS,
                                    screening: float = SCREENING) -> dict[str, np.ndarray]:
    """Periodic influence coefficients on the n x n grid, indexed [y, x] in FFT wrap-around order
    (offset (j dx, i dx) at index (j mod n, i mod n)), at unit shear modulus, zero mean.

    Parameters
    ----------
    grid
        The grid; its domain [-w, w)^2 is one period.
    poisson_ratio
        nu.
    components
        Among ``zz``, ``xx``, ``xz``, ``zx`` (displacement, traction), signs as in kernels.py.
    screening
        Ewald parameter alpha dx (any value > 0 gives the same result to round-off).
    """
    components = tuple(components)
    if grid.dimension == 1:
        return line_periodic_influence_coefficients(grid, poisson_ratio, components)
    n, dx = grid.n, grid.spacing
    alpha = screening / dx
    # long part: Fourier series over all |Q| < ~2 alpha EWALD_RANGE, folded onto the grid's modes
    ky = 2 * np.pi * np.fft.fftfreq(n, dx)[:, None]
    kx = 2 * np.pi * np.fft.rfftfreq(n, dx)[None, :]
    aliases = int(np.ceil((2 * EWALD_RANGE * screening / np.pi - 1) / 2))
    spectra = {c: np.zeros((n, n // 2 + 1), dtype=complex) for c in components}
    for sy in range(-aliases, aliases + 1):
        qy = ky + 2 * np.pi * sy / dx
        for sx in range(-aliases, aliases + 1):
            qx = kx + 2 * np.pi * sx / dx
            footprint = np.sinc(qx * dx / (2 * np.pi)) * np.sinc(qy * dx / (2 * np.pi))
            for c, v in _spectral(qx, qy, poisson_ratio, alpha, components).items():
                spectra[c] += v * footprint
    kernels = {c: scipy.fft.irfft2(s, s=(n, n)) for c, s in spectra.items()}
    # short part: closed-form cell integral minus the quadrature of its long part, offsets < r_cut
    reach = int(np.ceil(EWALD_RANGE / screening + 1))
    i = np.arange(-reach, reach + 1)
    ix, iy = np.meshgrid(i, i, indexing="xy")
    near = ix**2 + iy**2 <= reach**2
    ix, iy = ix[near], iy[near]
    half = dx / 2
    closed = rectangle_influence(ix * dx, iy * dx, half, half, poisson_ratio, components)
    nodes, weights = half * _GL_NODES, half * _GL_WEIGHTS
    xs = (ix * dx)[:, None, None] - nodes[None, None, :]
    ys = (iy * dx)[:, None, None] - nodes[None, :, None]
    w2 = weights[:, None] * weights[None, :]
    smooth = _long_point_force(xs, ys, poisson_ratio, alpha, components)
    for c in components:
        short = closed[c] - np.einsum("kab,ab->k", smooth[c], w2)
        np.add.at(kernels[c], (iy % n, ix % n), short)
        kernels[c] -= kernels[c].mean()  # drop the Q = 0 term of the short part (zero-mean convention)
    return kernels


def line_periodic_influence_coefficients(grid: Grid, poisson_ratio: float,
                                         components: Iterable[str] = COMPONENTS) -> dict[str, np.ndarray]:
    """Periodic plane-strain influence coefficients on a line grid (``grid.dimension = 1``): shape
    (1, n) in FFT wrap-around order, at unit shear modulus, zero mean; each a uniformly loaded strip
    of width dx repeated with the period L = 2 half_width, the displacement taken at cell centres.

    A load uniform along y is plane strain, so the compliance of the line is the half-space's of the
    module docstring at Q = (k, 0): G^_zz = G^_xx = (1 - nu)/|k| (stiffness E* |k| / 2), G^_xz =
    -G^_zx = (1 - 2 nu) i k / (2 k^2) (Johnson 1985, Eqs. 2.18-2.19 transformed). The sum over the
    aliases q_s = k + 2 pi s/dx of G^(q_s) F(q_s), F(q) = 2 sin(q dx/2)/q, is in closed form: with
    t = k dx / (2 pi) in (0, 1/2] and sin(q_s dx/2) = (-1)^s sin(pi t),

        S_zz(k) = 2 (1 - nu) sin(pi t) (dx/2pi)^2 [beta(t) + beta(1 - t)],
        beta(x) = sum_{s>=0} (-1)^s/(x + s)^2 = [psi_1(x/2) - psi_1((x + 1)/2)]/4   (trigamma psi_1),
        S_xz(k) = (1 - 2 nu) i (dx^2/4) cot(pi t)       (sum_s (-1)^s/(t + s)^2 = pi^2 cos(pi t)/sin^2(pi t)),

    and the kernel is K_j = (1/L) sum_m S(k_m) exp(i k_m x_j) over k_m = 2 pi m / L, the q = 0 term
    dropped (zero-mean convention of the module docstring). In real space these are the periodic
    Flamant and Cerruti line loads, -((1 - nu)/pi) ln|2 sin(pi x/L)| and -((1 - 2 nu)/4)(sgn x - 2x/L)
    for |x| < L, integrated over a cell (tested against that quadrature)."""
    from scipy.special import polygamma  # imported where used (see _spectral)

    components = tuple(components)
    n, dx = grid.n, grid.spacing
    t = np.arange(1, n // 2 + 1) / n
    alternating = (polygamma(1, t / 2) - polygamma(1, (t + 1) / 2)
                   + polygamma(1, (1 - t) / 2) - polygamma(1, (2 - t) / 2)) / 4
    even = np.concatenate([[0.0], 2 * np.sin(np.pi * t) * (dx / (2 * np.pi))**2 * alternating])
    odd = np.concatenate([[0.0], (dx**2 / 4) / np.tan(np.pi * t)]) * 1j
    if n % 2 == 0:
        odd[-1] = 0.0  # the Nyquist mode of an odd kernel
    nu = poisson_ratio
    spectra = {"zz": (1 - nu) * even, "xx": (1 - nu) * even, "xz": (1 - 2 * nu) * odd, "zx": -(1 - 2 * nu) * odd}
    out = {}
    for c in components:
        if c not in spectra:
            raise ValueError(f"unknown kernel component {c!r}; expected one of {COMPONENTS}")
        out[c] = scipy.fft.irfft(spectra[c] / dx, n)[None, :]
    return out


def check_approach(approach: float, gap: np.ndarray, key: str = "normal.value") -> None:
    """Raise :class:`~viscontact.errors.ParameterError` unless the approach [m] is below the mean of
    the undeformed gap [m]: with zero-mean displacements, mean(g) = mean(h0) - delta_z > 0 (module
    docstring); at the mean gap the contact is complete and its load undetermined."""
    mean = float(gap.mean())
    if not approach < mean:
        raise ParameterError(key, f"approach {approach:.6g} m must be < the mean gap {mean:.6g} m on a periodic "
                             "domain (displacements have zero mean over the period: at the mean gap the contact is "
                             "complete and its load undetermined); use normal.control = 'load'")


@dataclass(frozen=True)
class PeriodicConvolver(Convolver):
    """Periodic (circular) convolution with the periodic influence coefficients: the same methods
    as :class:`~viscontact.numerics.convolution.Convolver` on unpadded n x n real FFTs. ``spectra`` have shape
    (n, n // 2 + 1); ``kernels`` hold the periodic kernels tiled and centred so that
    :meth:`apply_sparse` takes plain slices."""

    #: an unpadded product costs a quarter of a padded one: direct sums pay only up to a few points
    #: (512^2: a product 3.9 ms, 2.5 ms in float32, direct sums 0.61 ms for one point, 1.8 ms for four,
    #: 3.4 ms for eight; 256^2: 0.57 ms in float32, 0.35 ms for four points, 0.61 ms for eight;
    #: ``benchmarks/sparse_products.py``): up to about six points against the float32 product of a
    #: mixed-precision solve
    sparse_limit: ClassVar[int] = 6

    @classmethod
    def from_kernels(cls, n: int, kernels: Mapping[str, np.ndarray], workers: int = -1, *,
                     xp: ModuleType = np, fft: ModuleType = scipy.fft) -> "PeriodicConvolver":
        """From periodic kernels on the n x n grid in wrap-around order, numpy arrays or fields of ``xp``
        (moved there first)."""
        kernels = {k: xp.asarray(v) for k, v in kernels.items()}
        rows = next(iter(kernels.values())).shape[0]  # n, or 1 on a line grid
        centred = {k: xp.roll(xp.tile(v, (2 if rows > 1 else 1, 2)), (rows - 1, n - 1), axis=(0, 1))
                   for k, v in kernels.items()}
        threads = fft_keywords(fft, workers, rows * n)
        return cls(n, {k: fft.rfft2(v, **threads) for k, v in kernels.items()}, workers, centred, xp, fft, rows=rows)

    @classmethod
    def for_grid(cls, grid: Grid, poisson_ratio: float, workers: int = -1,
                 components: Iterable[str] = COMPONENTS, *, xp: ModuleType = np,
                 fft: ModuleType = scipy.fft) -> "PeriodicConvolver":
        """Convolver of the periodic half-space influence coefficients at unit shear modulus (array
        namespace ``xp``, FFT module ``fft``: :mod:`viscontact.numerics.arrays`)."""
        return cls.from_kernels(grid.n, periodic_influence_coefficients(grid, poisson_ratio, components), workers,
                                xp=xp, fft=fft)

    def spectrum(self, field: np.ndarray) -> np.ndarray:
        """Real FFT (n, n // 2 + 1) of ``field`` (n, n), no padding."""
        return self.fft.rfft2(field, **fft_keywords(self.fft, self.workers, field.size))

    def inverse(self, spectrum: np.ndarray) -> np.ndarray:
        """Inverse real FFT (n, n) of a (n, n // 2 + 1) spectrum (which it may overwrite)."""
        return self.fft.irfft2(spectrum, s=self.shape, overwrite_x=True,
                               **fft_keywords(self.fft, self.workers, self.rows * self.n))

    def apply(self, name: str, field: np.ndarray, *, single: bool = False) -> np.ndarray:
        """sum_j K_name(x_i - x_j) field_j over the period (unpadded transforms; float32 when ``single``)."""
        return self.inverse(self.kernel_spectrum(name, single) * self.spectrum(operand(field, single)))

    def preconditioner(self, name: str, factor: float = 1.0) -> FourierPreconditioner:
        """The exact inverse of ``factor`` x the (symmetric part of the) kernel ``name``: the periodic
        operator is diagonal in Fourier space. The undetermined q = 0 mode gets the symbol of the
        lowest non-zero mode."""
        symbol = factor * np.abs(self.spectra[name].real)
        symbol[0, 0] = symbol[0, 1]
        return FourierPreconditioner(1.0 / np.maximum(symbol, symbol.max() * 1e-12), self.workers, self.fft)
