"""The all-modes steady kernel (viscontact.physics.steady_kernels) against two independent truths.

1. Adaptive quadrature (scipy ``quad``, rtol 1e-13) of F(d) = int_0^inf exp(-xi/L)/L IC(d + xi) dxi
   at entries of the singular row dy = 0 next to the cell edge and elsewhere: the product
   integration is accurate to ~1e-8 of max |F| there (measured 1.5e-8 at L = 0.1..10 dx, a few
   1e-8 at L = 1e9 dx where quad itself is limited); tolerance 1e-7.
2. The per-mode kernels of ``kernels.history_kernels`` (a different quadrature: graded Gauss-Legendre
   and its own tail), summed over the modes: they agree to the per-mode code's own error, which
   against quad is up to 5.6e-6 of max |F| in the singular row (Gauss-Legendre up to the x log x
   point at the cell edge); tolerance 2e-5 of max |K|.
The limits L << dx (F -> IC) and L >> domain (F -> 0) hold to round-off.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import history_kernels, influence_coefficients, rectangle_influence
from viscontact.physics.steady_kernels import SteadyKernelBuilder, product_weights

GRID = Grid(12, 1e-3)
NU = 0.3
DX = GRID.spacing


@pytest.fixture(scope="module")
def builder() -> SteadyKernelBuilder:
    return SteadyKernelBuilder(GRID, NU, ("zz", "zx"))


def quad_history(d_cells: int, dy_cells: int, length: float, comp: str) -> float:
    h = DX / 2

    def integrand(xi: float) -> float:
        ic = rectangle_influence(np.array(d_cells * DX + xi), np.array(dy_cells * DX), h, h, NU, (comp,))[comp]
        return float(np.exp(-xi / length) / length * ic)

    edges = sorted(p for p in (h - d_cells * DX, -h - d_cells * DX) if p > 0)
    ends = edges + list(np.geomspace(20 * DX, 60 * length + 20 * DX, 12))
    total, start = 0.0, 0.0
    for end in ends:
        if end > start:
            total += quad(integrand, start, end, epsabs=0.0, epsrel=1e-13, limit=400)[0]
            start = end
    return total


def column(d_cells: int) -> int:
    return d_cells if d_cells >= 0 else d_cells + 2 * GRID.n


ENTRIES = [(-1, 0), (0, 0), (GRID.n - 1, 2)]  # (d, dy) in cells: the two next to the cell edge, the last
MORE_ENTRIES = [(d, dy) for d in (-3, -1, 0, 1, GRID.n - 1) for dy in (0, 2)]


@pytest.mark.parametrize("ratio, entries", [(1.0, ENTRIES),
                                            *[pytest.param(r, MORE_ENTRIES, marks=pytest.mark.slow)
                                              for r in (0.1, 1.0, 10.0, 1e4)]])
def test_against_adaptive_quadrature(builder: SteadyKernelBuilder, ratio: float, entries: list) -> None:
    length = ratio * DX
    mine = builder.history([1.0], [length])
    for comp in ("zz", "zx"):
        scale = np.abs(mine[comp]).max()
        for d_cells, dy_cells in entries:
            exact = quad_history(d_cells, dy_cells, length, comp)
            assert mine[comp][dy_cells, column(d_cells)] == pytest.approx(exact, abs=1e-7 * scale), \
                (comp, d_cells, dy_cells)


def test_many_modes_against_the_per_mode_kernels(builder: SteadyKernelBuilder) -> None:
    amplitudes = np.array([1.0, 0.5, 2.0, 0.3, 0.7, 1.1])
    lengths = DX * np.array([1e-9, 0.03, 0.7, 6.0, 300.0, 1e7])
    mine = builder.history(amplitudes, lengths)
    for comp in ("zz", "zx"):
        reference = sum(a * history_kernels(GRID, NU, L, (comp,))[comp] for a, L in zip(amplitudes, lengths))
        np.testing.assert_allclose(mine[comp], reference, rtol=0, atol=2e-5 * np.abs(reference).max())


def test_limits_are_exact(builder: SteadyKernelBuilder) -> None:
    ic = influence_coefficients(GRID, NU)
    tiny = builder.history([1.0], [1e-12 * DX])
    huge = builder.history([1.0], [1e12 * DX])
    for comp in ("zz", "zx"):
        np.testing.assert_allclose(tiny[comp], ic[comp], rtol=0, atol=1e-11 * np.abs(ic[comp]).max())
        assert np.abs(huge[comp]).max() < 1e-9 * np.abs(ic[comp]).max()


def test_effective_kernel_adds_the_instantaneous_part(builder: SteadyKernelBuilder) -> None:
    ic = influence_coefficients(GRID, NU)
    hist = builder.history([2e-7, 1e-7], [0.05 * 0.01, 0.05 * 0.1])
    eff = builder.effective(3e-7, [2e-7, 1e-7], [0.01, 0.1], 0.05)
    for comp in ("zz", "zx"):
        np.testing.assert_allclose(eff[comp], 3e-7 * ic[comp] + hist[comp], rtol=1e-14, atol=0)


@pytest.mark.parametrize("length", [1e-9, 0.01, 1.0, 1e3])
def test_product_weights_integrate_the_exponential_against_polynomials(length: float) -> None:
    """sum_q c_q x_q^k = int_a^b exp(-x/L)/L x^k dx (exact for the degree-6 interpolant)."""
    a, b = 0.2, 0.7
    c = product_weights(a, b, 6, np.array([length]))[0]
    nodes = a + (b - a) * 0.5 * (1 - np.cos(np.pi * np.arange(7) / 6))
    for k in range(7):
        exact = quad(lambda x: np.exp(-x / length) / length * x**k, a, b, epsabs=0, epsrel=1e-13,
                     points=[a + length * 2.0**j for j in range(-4, 6) if a + length * 2.0**j < b] or None,
                     limit=200)[0]
        assert c @ nodes**k == pytest.approx(exact, rel=1e-11, abs=1e-300)
