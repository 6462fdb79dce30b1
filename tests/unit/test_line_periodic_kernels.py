"""Periodic line grids (``grid.periodic = true``, ``grid.dimension = 1``): the plane-strain periodic
kernels against the cell integral, by quadrature, of the periodic Flamant and Cerruti line loads
(independent of the closed-form alias sums of :func:`viscontact.physics.periodic.line_periodic_influence_coefficients`),
and their long-period limit, the isolated strip kernels of :mod:`viscontact.physics.kernels`."""
import numpy as np
import pytest
import scipy.integrate

from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import influence_coefficients
from viscontact.physics.periodic import PeriodicConvolver, periodic_influence_coefficients


def _quadrature_kernels(grid: Grid, nu: float) -> dict[str, np.ndarray]:
    """Cell integrals of -((1-nu)/pi) ln|2 sin(pi x/L)| and -((1-2nu)/4)(sgn x - 2x/L) (|x| < L, the
    periodic line loads at G = 1: Fourier series of (1-nu)/|k| and (1-2nu) i/(2k)), zero mean."""
    n, dx, period = grid.n, grid.spacing, 2 * grid.half_width
    zz, xz = np.zeros(n), np.zeros(n)
    for j in range(n):
        d = (j if j <= n // 2 else j - n) * dx  # the minimal image
        lo, hi = d - dx / 2, d + dx / 2
        pts = [0.0] if lo < 0 < hi else None
        zz[j] = -(1 - nu) / np.pi * scipy.integrate.quad(
            lambda s: np.log(abs(2 * np.sin(np.pi * s / period))), lo, hi, points=pts, limit=200)[0]
        xz[j] = -(1 - 2 * nu) / 4 * scipy.integrate.quad(
            lambda s: np.sign(s) - 2 * s / period, lo, hi, points=pts, limit=200)[0]
    return {"zz": zz - zz.mean(), "xz": xz - xz.mean()}


@pytest.mark.parametrize("n", [16, 33])
def test_periodic_line_kernels_match_the_periodic_line_loads(n):
    """zz = xx and xz = -zx against quadrature to 1e-10 of the largest value."""
    grid = Grid(n, 2e-3, periodic=True, dimension=1)
    nu = 0.3
    ic = periodic_influence_coefficients(grid, nu)
    ref = _quadrature_kernels(grid, nu)
    assert all(k.shape == (1, n) for k in ic.values())
    for c in ("zz", "xz"):
        scale = np.abs(ref[c]).max()
        np.testing.assert_allclose(ic[c][0], ref[c], rtol=0, atol=1e-10 * scale)
    np.testing.assert_allclose(ic["xx"], (ic["zz"]), rtol=0, atol=0)
    np.testing.assert_allclose(ic["zx"], -ic["xz"], rtol=0, atol=0)


def test_a_long_period_tends_to_the_isolated_strip_kernels():
    """Near the load, the periodic kernel of a period 64 x longer than the offsets differs from the
    isolated strip kernel by a constant (the datum) and O((x/L)^2) for zz, and for xz by the periodic
    sawtooth's slope, (1 - 2 nu) x / (2L): the differences of neighbouring offsets agree to 1e-3 of
    the kernel's own step."""
    n, nu = 1024, 0.25
    grid = Grid(n, 1.0, periodic=True, dimension=1)
    per = periodic_influence_coefficients(grid, nu)
    iso = influence_coefficients(Grid(n, 1.0, dimension=1), nu)
    near = np.arange(0, 8)
    dx, period = grid.spacing, 2 * grid.half_width
    for c, slope in (("zz", 0.0), ("xz", (1 - 2 * nu) / (2 * period))):
        d_per = np.diff(per[c][0, near])
        d_iso = np.diff(iso[c][0, near]) + slope * dx * dx
        np.testing.assert_allclose(d_per, d_iso, rtol=1e-3, atol=1e-3 * np.abs(d_iso).max())


def test_periodic_line_convolver_is_the_circular_sum():
    """PeriodicConvolver on a line: apply and apply_sparse are the circular sum of the kernel."""
    n = 12
    grid = Grid(n, 1e-3, periodic=True, dimension=1)
    conv = PeriodicConvolver.for_grid(grid, 0.3)
    rng = np.random.default_rng(3)
    field = np.zeros((1, n))
    field[0, [1, 5, 11]] = rng.random(3)
    k = periodic_influence_coefficients(grid, 0.3)["zz"][0]
    direct = np.array([[sum(k[(i - j) % n] * field[0, j] for j in range(n)) for i in range(n)]])
    np.testing.assert_allclose(conv.apply("zz", field), direct, rtol=0, atol=1e-14 * np.abs(direct).max())
    np.testing.assert_allclose(conv.apply_sparse("zz", field), direct, rtol=0, atol=1e-14 * np.abs(direct).max())
