"""Exact steady sliding on a periodic domain (viscontact.solvers.steady_periodic).

* Full-contact sinusoid h0 cos(kx) under the mean pressure p_mean: the displacement is prescribed
  (u = delta - gap), so p^(k) = u^(k) G*(-kv) / K^(k) and F_T / A = -mean(p du/dx) give

      mu_app = k^2 h0^2 / (2 p_mean) Im[ -G*(-kv) / ((1 - nu) - i mu_f (1 - 2 nu) / 2) ],

  which for frictionless sliding (mu_f = 0) is k^2 h0^2 E''(kv) / (4 p_mean), E* = 2 G* / (1 - nu):
  the issue's formula, factors confirmed by this derivation (docs/numerics.md). The discrete
  result differs by the cell footprint in K^ and the central difference in du/dx, both O((k dx)^2):
  the observed order must be 2 and the error at 64 cells per wavelength below 0.2 %.
* An elastic material has no hysteresis: the steady state at any speed is the elastic contact
  (Polonsky-Keer on the same periodic operator) and mu_app vanishes (round-off).
* A Zener solid at speeds where every mode's k_x v tau is 1e-6 responds with its long-term
  modulus: the elastic contact with G(inf) to ~1e-5; at k_x v tau >= 1e6 with G(0), for a surface
  without k_x = 0 modes (those are static at any speed).
"""
from __future__ import annotations

import numpy as np
import pytest

from viscontact.errors import ParameterError
from viscontact.numerics.grid import Grid
from viscontact.physics.materials import Material
from viscontact.physics.periodic import PeriodicConvolver
from viscontact.solvers.steady_periodic import solve_periodic_steady
from viscontact.problem.topography import gap_from_heights, self_affine_heights
from vc_testing import observed_order, periodic_elastic_contact

NU = 0.3
ZENER = Material.zener(1.93e6, 1.93e5, 0.01, NU)


@pytest.mark.parametrize("friction", [0.0, 0.5])
@pytest.mark.parametrize("k_v_lambda", [0.3, 3.0])
def test_full_contact_sinusoid_hysteresis_friction(friction, k_v_lambda):
    wavelength, h0, p_mean = 1e-3, 1e-6, 2e5
    k = 2 * np.pi / wavelength
    speed = k_v_lambda / (k * 0.01)
    g_star = ZENER.storage_modulus(-k * speed) + 1j * ZENER.loss_modulus(-k * speed)
    exact = k**2 * h0**2 / (2 * p_mean) * np.imag(-g_star / ((1 - NU) - 0.5j * friction * (1 - 2 * NU)))
    if friction == 0:
        e_loss = 2 * ZENER.loss_modulus(k * speed) / (1 - NU)
        assert exact == pytest.approx(k**2 * h0**2 * e_loss / (4 * p_mean), rel=1e-12)
    sizes = np.array([16, 32, 64])
    errors = []
    for n in sizes:
        grid = Grid(int(n), wavelength / 2)
        x, _ = grid.mesh()
        gap = h0 * (1 - np.cos(k * x))
        conv = PeriodicConvolver.for_grid(grid, NU, components=("zz", "zx"))
        state = solve_periodic_steady(conv, ZENER, grid, gap, speed=speed, control="load",
                                      value=p_mean * wavelength**2, friction=friction)
        assert state.contact_area == pytest.approx(wavelength**2)       # full contact
        assert state.delta_z == pytest.approx(gap.mean(), rel=1e-9)     # zero-mean displacement
        assert state.load == pytest.approx(p_mean * wavelength**2, rel=1e-12)
        errors.append(abs(state.mu_app / exact - 1))
    assert observed_order(1.0 / sizes, errors) == pytest.approx(2.0, abs=0.1)
    assert errors[-1] < 2e-3


def _rough_case(n: int = 32):
    grid = Grid(n, 0.25e-3)
    gap = gap_from_heights(self_affine_heights(grid, hurst=0.8, rms_slope=0.1, short_cutoff=8 * grid.spacing,
                                               seed=2))
    return grid, gap, 0.03 * 0.1 * (2 * grid.half_width) ** 2  # load [N] per unit E*


def test_elastic_material_steady_is_the_elastic_contact():
    grid, gap, load_per_modulus = _rough_case()
    g = 1.0e6
    load = load_per_modulus * 2 * g / (1 - NU)
    conv = PeriodicConvolver.for_grid(grid, NU, components=("zz",))
    p_ref, delta_ref, _, _ = periodic_elastic_contact(grid, gap, g, NU, load)
    state = solve_periodic_steady(conv, Material.elastic(g, NU), grid, gap, speed=0.1, control="load", value=load)
    assert 0.02 < (p_ref > 0).mean() < 0.5
    assert np.abs(state.pressure - p_ref).max() <= 1e-7 * p_ref.max()
    assert state.delta_z == pytest.approx(delta_ref, rel=1e-7)
    assert abs(state.mu_app) < 1e-12


def test_zener_slow_limit_is_the_long_term_elastic_contact():
    grid, gap, load_per_modulus = _rough_case()
    speed = 1e-6 / (np.pi / grid.spacing * ZENER.tau[0])  # k_x v tau <= 1e-6 for every mode
    load = load_per_modulus * 2 * ZENER.shear_modulus_long_term / (1 - NU)
    conv = PeriodicConvolver.for_grid(grid, NU, components=("zz",))
    p_ref, _, _, _ = periodic_elastic_contact(grid, gap, ZENER.shear_modulus_long_term, NU, load)
    state = solve_periodic_steady(conv, ZENER, grid, gap, speed=speed, control="load", value=load)
    assert np.abs(state.pressure - p_ref).max() <= 1e-5 * p_ref.max()
    assert 0 < state.mu_app < 1e-5


def test_zener_fast_limit_is_the_instantaneous_elastic_contact():
    """Modes with k_x = 0 are static whatever the speed; a surface varying along x only has none
    but the mean (which does not deform), so it sees G(0) when k_x v tau >= 1e6 for every mode."""
    grid = Grid(32, 0.5e-3)
    x, _ = grid.mesh()
    gap = 1e-6 * (1 - np.cos(2 * np.pi * x / 1e-3)) + 0.3e-6 * (1 - np.cos(6 * np.pi * x / 1e-3))
    speed = 1e6 / (2 * np.pi / 1e-3 * ZENER.tau[0])
    load = 0.3 * np.pi * 2 * ZENER.shear_modulus_instantaneous / (1 - NU) * 1e-6 / 1e-3 * 1e-6
    conv = PeriodicConvolver.for_grid(grid, NU, components=("zz",))
    p_ref, _, _, _ = periodic_elastic_contact(grid, gap, ZENER.shear_modulus_instantaneous, NU, load)
    state = solve_periodic_steady(conv, ZENER, grid, gap, speed=speed, control="load", value=load)
    assert 0 < (p_ref > 0).mean() < 1
    assert np.abs(state.pressure - p_ref).max() <= 1e-5 * p_ref.max()
    assert 0 < state.mu_app < 1e-5


def test_viscoelastic_rough_sliding_resists_motion_and_displacement_control():
    grid, gap, load_per_modulus = _rough_case()
    conv = PeriodicConvolver.for_grid(grid, NU, components=("zz",))
    speed = 1.0 / (np.pi / grid.spacing * ZENER.tau[0])  # the shortest wavelengths at their loss peak
    load = load_per_modulus * 2 * ZENER.shear_modulus_long_term / (1 - NU)
    by_load = solve_periodic_steady(conv, ZENER, grid, gap, speed=speed, control="load", value=load)
    assert by_load.mu_app > 1e-3
    # the same state under displacement control, at the approach the load-controlled one found
    by_approach = solve_periodic_steady(conv, ZENER, grid, gap, speed=speed, control="displacement",
                                        value=by_load.delta_z)
    assert by_approach.load == pytest.approx(load, rel=1e-7)
    assert np.abs(by_approach.pressure - by_load.pressure).max() <= 1e-7 * by_load.pressure.max()
    with pytest.raises(ParameterError, match="mean gap"):
        solve_periodic_steady(conv, ZENER, grid, gap, speed=speed, control="displacement", value=gap.mean())
