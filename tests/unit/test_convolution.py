"""DC-FFT (Liu, Wang & Liu 2000) against the literal O(n^4) discrete convolution.

The zero-padded FFT product is algebraically identical to the aperiodic sum, so the two agree to
round-off: tolerance 1e-12 relative to the largest displacement (FFT round-off is ~1e-15 times
log n). A periodic (non-padded) convolution or a wrong wrap-around layout of the kernel would be
off by O(1) near the edges, which the random fields (non-zero everywhere) expose.
"""
from __future__ import annotations

import numpy as np
import pytest

from viscontact.numerics.convolution import coupled_displacements, direct_convolution
from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import COMPONENTS, half_space_convolver, influence_coefficients

N = 12
GRID = Grid(N, 0.5e-3)


@pytest.fixture(scope="module")
def setup():
    nu = 0.3
    return half_space_convolver(GRID, nu, workers=1), influence_coefficients(GRID, nu)


def _close(a: np.ndarray, b: np.ndarray, tol: float = 1e-12) -> None:
    assert np.max(np.abs(a - b)) <= tol * np.max(np.abs(b)), np.max(np.abs(a - b)) / np.max(np.abs(b))


@pytest.mark.parametrize("component", COMPONENTS)
def test_dcfft_matches_direct_sum(setup, component):
    conv, ics = setup
    rng = np.random.default_rng(7)
    for _ in range(3):
        field = rng.standard_normal((N, N))
        _close(conv.apply(component, field), direct_convolution(ics[component], field))
    # a single off-centre point load reproduces the kernel column by column
    field = np.zeros((N, N))
    field[2, 9] = 1.0
    _close(conv.apply(component, field), direct_convolution(ics[component], field))


def test_direct_sum_of_a_point_load_is_the_influence_coefficient(setup):
    """Independent of the FFT: u_i = IC(x_i - x_j) for a unit traction at cell j."""
    _, ics = setup
    field = np.zeros((N, N))
    jy, jx = 4, 7
    field[jy, jx] = 1.0
    out = direct_convolution(ics["xz"], field)
    for iy, ix in [(4, 7), (0, 0), (11, 11), (4, 0), (9, 7)]:
        assert out[iy, ix] == ics["xz"][(iy - jy) % (2 * N), (ix - jx) % (2 * N)]


def test_combine_and_coupled_displacements(setup):
    conv, ics = setup
    rng = np.random.default_rng(3)
    p = rng.uniform(0, 1, (N, N))
    q = rng.standard_normal((N, N))
    combined = conv.combine([("zz", 2.0, p), ("zx", -0.5, q)])
    _close(combined, 2.0 * direct_convolution(ics["zz"], p) - 0.5 * direct_convolution(ics["zx"], q))
    u_z, u_x = coupled_displacements(conv, p, q)
    _close(u_z, direct_convolution(ics["zz"], p) + direct_convolution(ics["zx"], q))
    _close(u_x, direct_convolution(ics["xz"], p) + direct_convolution(ics["xx"], q))
    u_z_only, none = coupled_displacements(conv, p, None, need_x=False)
    assert none is None
    _close(u_z_only, direct_convolution(ics["zz"], p))


def test_odd_grid_size():
    grid = Grid(7, 1.0)
    conv = half_space_convolver(grid, 0.0, workers=1)
    ics = influence_coefficients(grid, 0.0)
    field = np.random.default_rng(0).standard_normal((7, 7))
    for c in COMPONENTS:
        _close(conv.apply(c, field), direct_convolution(ics[c], field))
