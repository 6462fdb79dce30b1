"""Steady rolling on a periodic grid (a row of spheres, one per period, rolling in +x).

The periodic steady rolling solver takes the exact periodic steady operators of the compliance (each
Fourier mode through the complex compliance at -k_x V) and the material difference u(x) - u(x + dx)
wrapping around the period. Checked against two independent truths:

* the periodic transient from standstill (a time-stepping algorithm: the moving frame wrapping
  around, the hereditary sum of the time scheme): elastic with nu = 0.3 (the normal-tangential
  coupling alternated in both), the same discretisation of the convection, so equal to the solvers'
  tolerance once steady (measured after five periods: pressure 2.8e-10 and q_x 6.7e-10 of the peak
  pressure, traction 4e-11, approach 6e-12; the transient's error falls ~1e3 times per period);
  viscoelastic (Zener, G(0)/G(inf) = 10, V tau = a, three periods), where the transient's time scheme differs from
  the steady operator's exact complex compliance by O(dt): measured traction 1.5 % / 0.27 %, rolling
  resistance 0.39 % / 0.014 % at 32^2 / 64^2 (nu = 0.3, linear scheme): the difference falls with
  the cell;
* the isolated (DC-FFT) steady rolling state, which the periodic one tends to as the period grows
  (the images' field over the contact falls as L^-3 for an elastic body with nu = 0.5): measured
  traction 1.2 %, 0.15 %, 0.019 % and the pressure 5.8e-3, 7.1e-4, 8.8e-5 of its peak for periods
  of 2, 4, 8 times the isolated domain [-2a, 2a]^2.
"""
from dataclasses import replace
from itertools import pairwise

import numpy as np
import pytest

from viscontact.numerics.grid import Grid
from viscontact.physics.materials import Material
from viscontact.physics.reference import hertz_from_load
from viscontact.problem.problem import TangentialLoading, TimeStepping
from viscontact.running.loop import simulate
from viscontact.solvers.steady_rolling import creepage_sweep, solve_steady_rolling

from vc_testing import SEED_G0, SEED_LOAD, SEED_RADIUS, sphere_problem

G, W, MU, XI = SEED_G0, SEED_LOAD, 0.3, -2e-3
HERTZ = hertz_from_load(W, SEED_RADIUS, G, 0.5)


def _rolling(material: Material, n: int, half_width: float, *, periodic: bool = True, speed: float = 0.1,
             periods: int = 0, scheme: str = "constant"):
    """A sphere rolling at ``speed`` [m/s] with the creepage XI on n x n cells of [-w, w]^2 (w:
    ``half_width`` [m]), periodic or not; its transient ``periods`` periods long (one cell per step)."""
    pb = sphere_problem(material, n, half_width, t_end=1.0, dt=1.0)
    grid = Grid(n, half_width, periodic=periodic)
    dx = grid.spacing
    steps = max(periods * n, 1)
    return replace(pb, grid=grid, tangential=TangentialLoading("rolling", MU, rolling_speed=speed, creepage=XI),
                   time=TimeStepping(steps * dx / speed, dx / speed, scheme))


def test_elastic_coupled_periodic_steady_rolling_is_the_long_time_transient():
    pb = _rolling(Material.elastic(G, 0.3), 32, 2 * HERTZ.radius, periods=5)
    last = list(simulate(pb))[-1]
    steady = solve_steady_rolling(pb)
    assert 0.3 < steady.stick_ratio < 0.9  # partial slip
    peak = steady.pressure.max()
    assert np.abs(last.pressure - steady.pressure).max() < 3e-9 * peak
    assert np.abs(last.shear_x - steady.shear_x).max() < 3e-9 * peak
    np.testing.assert_array_equal(last.stick, steady.stick)
    assert last.friction_force == pytest.approx(steady.friction_force, rel=1e-9)
    assert last.delta_z == pytest.approx(steady.delta_z, rel=1e-10)


def test_viscoelastic_periodic_transient_tends_to_the_steady_rolling_state():
    """Zener at V tau = a: three periods of the transient against the periodic steady state, at 32^2
    and 64^2 (measured in the module docstring): within 2 % / 0.5 % in the traction and falling."""
    tau = 0.01
    material = Material.zener(G, G / 10, tau, 0.3)
    errors = []
    for n in (32, 64):
        pb = _rolling(material, n, 3 * 10 ** (1 / 3) * HERTZ.radius, speed=HERTZ.radius / tau, periods=3,
                      scheme="linear")
        last = list(simulate(pb))[-1]
        steady = solve_steady_rolling(pb)
        errors.append(abs(last.friction_force / steady.friction_force - 1))
        assert last.hysteresis_force == pytest.approx(steady.hysteresis_force, rel=5e-3)
        assert last.delta_z == pytest.approx(steady.delta_z, rel=1e-3)
    assert errors[0] < 0.02 and errors[1] < 0.005 and errors[1] < errors[0] / 3, errors


def test_a_long_period_tends_to_the_isolated_steady_rolling_state():
    """Elastic, nu = 0.5: the central n x n cells of periods 2, 4, 8 times the isolated domain [-2a, 2a]^2
    (the same cells) against the isolated state: the errors fall as L^-3 (factor > 6 per doubling)."""
    material, n, w = Material.elastic(G, 0.5), 32, 2 * HERTZ.radius
    isolated = solve_steady_rolling(_rolling(material, n, w, periodic=False))
    traction, pressure = [], []
    for k in (2, 4, 8):
        state = solve_steady_rolling(_rolling(material, k * n, k * w))
        centre = slice((k - 1) * n // 2, (k + 1) * n // 2)
        assert state.pressure[centre, centre].sum() == pytest.approx(state.pressure.sum(), rel=1e-12)
        traction.append(abs(state.friction_force / isolated.friction_force - 1))
        pressure.append(np.abs(state.pressure[centre, centre] - isolated.pressure).max() / isolated.pressure.max())
    assert traction[-1] < 3e-4 and pressure[-1] < 1.5e-4, (traction, pressure)
    assert all(b < a / 6 for a, b in pairwise(traction)), traction
    assert all(b < a / 6 for a, b in pairwise(pressure)), pressure


def test_periodic_traction_saturates_and_is_odd_in_the_creepage():
    pb = _rolling(Material.elastic(G, 0.5), 32, 2 * HERTZ.radius)
    full = solve_steady_rolling(pb, creepage=0.1)
    assert full.friction_force == pytest.approx(-MU * full.load, rel=1e-9) and full.stick_ratio == 0.0
    small = creepage_sweep(pb, [-2e-3, 2e-3])
    assert 0 < small[0].friction_force < MU * W
    assert small[1].friction_force == pytest.approx(-small[0].friction_force, rel=1e-9)
