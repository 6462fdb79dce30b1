"""Closed-form influence coefficients of a uniformly loaded rectangle (viscontact.physics.kernels).

Reference: adaptive 2-D quadrature (``scipy.integrate.dblquad``, epsrel 1e-11) of the
Boussinesq-Cerruti point-force solutions over the rectangle, at field points off the loaded cell,
where the integrand is smooth. Tolerance 1e-6 relative: the quadrature is good to ~1e-10 there, so
any error in a corner primitive, a sign or a factor (1 - nu), nu, (1 - 2 nu) fails by orders of
magnitude. The self-influence (field point inside the cell, singular integrand) is checked against
the classical closed form int int_square 1/r dA = 8 h asinh(1) at the centre of a square of side 2h.
A non-square rectangle is used so that x and y cannot be swapped unnoticed.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import dblquad

from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import (
    COMPONENTS,
    influence_coefficients,
    point_force_displacement,
    rectangle_influence,
)

HX, HY = 0.7, 0.4  # half-sides of the test rectangle (any length unit: the ICs scale with length)
FIELD_POINTS = [(3.0, 0.5), (-2.0, 1.7), (0.3, 2.5), (5.0, -4.0), (-0.9, -0.2), (1.2, 0.0)]
POISSON = [0.0, 0.25, 0.3, 0.5]


def quadrature(x: float, y: float, nu: float, component: str) -> float:
    def f(yp: float, xp: float) -> float:
        return float(point_force_displacement(x - xp, y - yp, nu)[component])
    value, _ = dblquad(f, -HX, HX, -HY, HY, epsabs=0.0, epsrel=1e-11)
    return value


@pytest.mark.parametrize("nu", POISSON)
def test_rectangle_matches_quadrature_of_point_forces(nu):
    for x, y in FIELD_POINTS:
        closed = rectangle_influence(np.array(x), np.array(y), HX, HY, nu)
        for c in COMPONENTS:
            ref = quadrature(x, y, nu, c)
            if nu == 0.5 and c in ("xz", "zx"):
                assert ref == 0.0 and float(closed[c]) == 0.0
                continue
            assert float(closed[c]) == pytest.approx(ref, rel=1e-6), (c, x, y)


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_self_influence_at_the_centre_of_a_square(nu):
    """int int 1/r = 8 h asinh(1) over [-h, h]^2; by symmetry int int x^2/r^3 is half of it and
    the odd cross terms vanish."""
    h = 0.37
    ic = rectangle_influence(np.array(0.0), np.array(0.0), h, h, nu)
    inv_r = 8 * h * np.arcsinh(1.0)
    assert float(ic["zz"]) == pytest.approx((1 - nu) / (2 * np.pi) * inv_r, rel=1e-13)
    assert float(ic["xx"]) == pytest.approx(((1 - nu) + nu / 2) / (2 * np.pi) * inv_r, rel=1e-13)
    assert float(ic["xz"]) == 0.0 and float(ic["zx"]) == 0.0


@pytest.mark.parametrize("nu", [0.0, 0.3])
def test_reciprocity_and_symmetry(nu):
    rng = np.random.default_rng(1)
    x, y = rng.uniform(-6, 6, (2, 200))
    ic = rectangle_influence(x, y, HX, HY, nu)
    flip_x = rectangle_influence(-x, y, HX, HY, nu)
    flip_y = rectangle_influence(x, -y, HX, HY, nu)
    opposite = rectangle_influence(-x, -y, HX, HY, nu)
    # Betti: the u_x of a normal load equals the u_z of a shear load at the mirrored point
    np.testing.assert_allclose(ic["xz"], opposite["zx"], rtol=1e-13, atol=1e-15)
    for c in ("zz", "xx"):  # even in x and y
        np.testing.assert_allclose(flip_x[c], ic[c], rtol=1e-13)
        np.testing.assert_allclose(flip_y[c], ic[c], rtol=1e-13)
    for c in ("xz", "zx"):  # odd in x, even in y
        np.testing.assert_allclose(flip_x[c], -ic[c], rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(flip_y[c], ic[c], rtol=1e-12, atol=1e-15)
    # a normal load pulls surface points towards it (u_x < 0 for x > 0, nu < 0.5)
    assert np.all(ic["xz"][x > HX] < 0)
    # the shear load displaces more along x than across (nu x^2/r^3 term)
    along = rectangle_influence(np.array(4.0), np.array(0.0), HX, HX, nu)["xx"]
    across = rectangle_influence(np.array(0.0), np.array(4.0), HX, HX, nu)["xx"]
    assert (along > across) if nu > 0 else (along == pytest.approx(across, rel=1e-13))


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_far_field_is_point_force_times_area(nu):
    """At distance r the rectangle acts as a point force of size 4 HX HY; the next term is
    O((h/r)^2), so the relative error must fall by ~100 from r = 10 h to r = 100 h."""
    area = 4 * HX * HY
    errors = []
    for scale in (10.0, 100.0):
        x, y = scale * 0.8, scale * 0.6  # |(x, y)| = scale
        ic = rectangle_influence(np.array(x), np.array(y), HX, HY, nu)
        pf = point_force_displacement(np.array(x), np.array(y), nu)
        err = max(abs(float(ic[c]) / (area * float(pf[c])) - 1) for c in COMPONENTS if float(pf[c]) != 0)
        errors.append(err)
    assert errors[1] < 1e-4
    assert errors[0] / errors[1] == pytest.approx(100, rel=0.05)


def test_influence_coefficients_on_the_offset_grid():
    grid = Grid(8, 1.0e-3)
    ics = influence_coefficients(grid, 0.3)
    off = grid.offsets()
    h = grid.spacing / 2
    for c in COMPONENTS:
        assert ics[c].shape == (16, 16)
        assert np.all(ics[c][8, :] == 0) and np.all(ics[c][:, 8] == 0)
        for iy, ix in [(0, 0), (0, 3), (2, 1), (13, 5), (15, 15), (7, 9)]:
            expected = float(rectangle_influence(np.array(off[ix]), np.array(off[iy]), h, h, 0.3)[c])
            assert ics[c][iy, ix] == pytest.approx(expected, rel=1e-14, abs=1e-30), (c, iy, ix)
    # layout [y, x]: IC_xz is odd along x (axis 1), even along y (axis 0)
    assert ics["xz"][0, 1] < 0 and ics["xz"][0, 15] == pytest.approx(-ics["xz"][0, 1], rel=1e-14)
    assert ics["xz"][1, 0] == 0.0
