"""The transient on a periodic domain: moving frame wrapping around, against exact references.

* Full-contact sinusoid h0 cos(kx), frictionless and gross sliding: the transient tends to the
  exact periodic steady state (viscontact.steady_periodic, no history truncation) as the time step
  dt = dx / v shrinks with the grid, at second order (the linear scheme), and so to
  mu_app = k^2 h0^2 E''(kv) / (4 p_mean) (0.06 % at 64 cells per wavelength).
* Ridges along x (a gap that depends on y only): sliding along x changes nothing, so with the
  frame wrapping around the material (nothing dropped at the trailing edge) the sliding transient
  is the indentation transient, step by step (solver tolerance).
* An elastic half-space: the first step is the elastic periodic contact.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from viscontact import transient
from viscontact.errors import ParameterError
from viscontact.grid import Grid
from viscontact.materials import Material
from viscontact.problem import (NormalLoading, OutputSettings, PiecewiseLinear, Problem, SolverSettings,
                                TangentialLoading, TimeStepping)
from viscontact.steady import solve_steady
from vc_testing import observed_order, periodic_elastic_contact

NU = 0.3
ZENER = Material.zener(1.93e6, 1.93e5, 0.01, NU)
WAVELENGTH, H0, P_MEAN = 1e-3, 1e-6, 2e5
K = 2 * np.pi / WAVELENGTH


def _problem(grid: Grid, gap: np.ndarray, mode: str, speed: float, t_end: float, *, friction: float = 0.0,
             material: Material = ZENER, control: str = "load", value: float | None = None) -> Problem:
    value = P_MEAN * (2 * grid.half_width) ** 2 if value is None else value
    dt = grid.spacing / speed if speed > 0 else 1e-3
    return Problem(material=material, grid=grid, gap=gap, normal=NormalLoading(control, PiecewiseLinear.constant(value)),
                   tangential=TangentialLoading(mode, friction, 0.0, speed), time=TimeStepping(t_end, dt, "linear"),
                   solver=SolverSettings(tolerance=1e-10), output=OutputSettings(1, ("pressure",)))


def _records(problem: Problem) -> list:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # coarse time steps on the coarsest grids
        return [r for _, r in transient.steps(problem)]


@pytest.mark.parametrize("friction", [0.0, 0.5])
def test_sinusoid_transient_tends_to_the_exact_steady_state(friction):
    speed = 1 / (K * ZENER.tau[0] * ZENER.shear_modulus_instantaneous / ZENER.shear_modulus_long_term)
    mode = "gross_sliding" if friction else "frictionless_sliding"
    sizes = np.array([16, 32, 64])
    errors = []
    for n in sizes:
        grid = Grid(int(n), WAVELENGTH / 2, periodic=True)
        x, _ = grid.mesh()
        problem = _problem(grid, H0 * (1 - np.cos(K * x)), mode, speed, 0.1, friction=friction)
        records = _records(problem)
        steady = solve_steady(problem)
        assert records[-1].contact_fraction == 1.0 and steady.contact_fraction == 1.0
        errors.append(abs(records[-1].mu_app / steady.mu_app - 1))
    assert observed_order(1.0 / sizes, errors) == pytest.approx(2.0, abs=0.15)
    assert errors[-1] < 1e-3
    if friction == 0:
        e_loss = 2 * ZENER.loss_modulus(K * speed) / (1 - NU)
        exact = K**2 * H0**2 * e_loss / (4 * P_MEAN)
        assert records[-1].mu_app == pytest.approx(exact, rel=2e-3)


def test_ridges_along_the_sliding_direction_slide_as_they_indent():
    grid = Grid(16, 0.5e-3, periodic=True)
    _, y = grid.mesh()
    gap = H0 * (1 - np.cos(K * y))  # partial contact: from 14 % (G(0)) towards 50 % (G(inf)) of the period
    load = 0.05 * np.pi * 2 * ZENER.shear_modulus_instantaneous / (1 - NU) * H0 / WAVELENGTH * WAVELENGTH**2
    speed = 0.02
    sliding = _records(_problem(grid, gap, "frictionless_sliding", speed, 0.06, value=load))
    resting = _records(Problem(material=ZENER, grid=grid, gap=gap,
                               normal=NormalLoading("load", PiecewiseLinear.constant(load)),
                               time=TimeStepping(0.06, grid.spacing / speed, "linear"),
                               solver=SolverSettings(tolerance=1e-10), output=OutputSettings(1, ("pressure",))))
    assert len(sliding) == len(resting) > 10
    assert 0 < sliding[-1].contact_fraction < 1
    assert resting[-1].contact_fraction > 1.2 * resting[0].contact_fraction  # it creeps
    for a, b in zip(sliding, resting):
        assert np.abs(a.pressure - b.pressure).max() <= 1e-7 * b.pressure.max()
        assert abs(a.mu_app) < 1e-9


def test_elastic_first_step_and_displacement_control_guard():
    grid = Grid(32, 0.5e-3, periodic=True)
    x, y = grid.mesh()
    gap = H0 * (1 - np.cos(K * x)) + 0.5 * H0 * (1 - np.cos(2 * K * y))
    g = 1e6
    load = 0.05 * 2 * g / (1 - NU) * H0 / WAVELENGTH * WAVELENGTH**2
    elastic = Material.elastic(g, NU)
    record = _records(_problem(grid, gap, "none", 0.0, 1e-3, material=elastic, value=load))[0]
    p_ref, delta_ref, _, _ = periodic_elastic_contact(grid, gap, g, NU, load)
    assert 0 < record.contact_fraction < 1
    assert np.abs(record.pressure - p_ref).max() <= 1e-6 * p_ref.max()
    assert record.delta_z == pytest.approx(delta_ref, rel=1e-6)
    # the same contact under displacement control, at the approach found
    by_approach = _records(_problem(grid, gap, "none", 0.0, 1e-3, material=elastic, control="displacement",
                                    value=record.delta_z))[0]
    assert by_approach.load == pytest.approx(load, rel=1e-6)
    with pytest.raises(ParameterError, match="mean gap"):
        transient.init(_problem(grid, gap, "none", 0.0, 1e-3, material=elastic, control="displacement",
                                value=gap.mean()))
