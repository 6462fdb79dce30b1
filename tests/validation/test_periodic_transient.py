"""The transient on a periodic domain: moving frame wrapping around, against exact references.

* Full-contact sinusoid h0 cos(kx), frictionless and gross sliding: the transient tends to the
  exact periodic steady state (viscontact.solvers.steady_periodic, no history truncation) as the time step
  dt = dx / v shrinks with the grid, at second order (the linear scheme), and so to
  mu_app = k^2 h0^2 E''(kv) / (4 p_mean) (0.06 % at 64 cells per wavelength).
* Ridges along x (a gap that depends on y only): sliding along x changes nothing, so with the
  frame wrapping around the material (nothing dropped at the trailing edge) the sliding transient
  is the indentation transient, step by step (solver tolerance).
* An elastic half-space: the first step is the elastic periodic contact.
* Partial slip in full contact: a uniform shear is in the null space of the periodic half-space's
  tangential operator, so delta_x cannot fix the friction force; refused in one line. A layer
  bonded to a rigid base pins it (q = G delta_x / h) and runs.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from viscontact.solvers import transient
from viscontact.errors import ParameterError
from viscontact.numerics.grid import Grid
from viscontact.physics.materials import Material
from viscontact.problem.problem import (PHASE_PARTIAL_SLIP, LayerSettings, NormalLoading, OutputSettings, PiecewiseLinear,
                                Problem, SolverSettings, TangentialLoading, TimeStepping)
from viscontact.solvers.steady import solve_steady
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


def _slip(load: PiecewiseLinear, layer: LayerSettings | None = None, n: int = 16) -> Problem:
    """Partial slip (mu_f = 0.3, delta_x = 1e-6 m/s t) of the sinusoid h0 (1 - cos kx) on an elastic
    nu = 0.5 body (no normal/tangential coupling), G = 1 MPa; ``load`` in units of the full-contact
    load p* L^2, p* = E* k h0 / 2."""
    grid = Grid(n, WAVELENGTH / 2, periodic=True)
    x, _ = grid.mesh()
    g = 1e6
    full = 2 * g / (1 - 0.5) * K * H0 / 2 * WAVELENGTH**2
    speed = 1e-2
    dt = grid.spacing / speed / 4
    return Problem(material=Material.elastic(g, 0.5), grid=grid, gap=H0 * (1 - np.cos(K * x)),
                   normal=NormalLoading("load", PiecewiseLinear(load.times, tuple(full * v for v in load.values))),
                   tangential=TangentialLoading("partial_slip", 0.3, 1e-6, speed, 4),
                   time=TimeStepping(8 * dt, dt, "linear"), solver=SolverSettings(tolerance=1e-10),
                   output=OutputSettings(1, ("pressure", "shear_x")), layer=layer)


def test_partial_slip_in_full_periodic_contact_is_refused():
    """Three times the full-contact load: it returned Q = 0 at every delta_x (on an earlier solver
    mu_f min p everywhere, Q/W = 0.2003 at delta_x = 5e-14 m): a uniform shear moves the periodic
    half-space by an undetermined mean, so nothing fixes Q. Refused at the step whose contact
    covers the period, the steps before done; at 0.95 of that load (87.5 % in contact) q = 0 out of
    contact pins the mean and Q builds up with delta_x (Q / mu_f W = 0, 0.069, 0.099, ...)."""
    problem = _slip(PiecewiseLinear.constant(3.0))
    with pytest.raises(ParameterError, match="whole period") as refused:
        _records(problem)
    assert refused.value.key == "tangential.mode" and "gross_sliding" in refused.value.message
    dt = problem.time.dt
    ramp = _slip(PiecewiseLinear((0.0, 2 * dt, 3 * dt, 8 * dt), (0.5, 0.5, 3.0, 3.0)))
    done = []
    with pytest.raises(ParameterError, match="whole period"):
        for _, record in transient.steps(ramp):
            done.append(record)
    assert len(done) == 3 and done[-1].contact_fraction < 1  # t = 3 dt is full
    partial = _records(_slip(PiecewiseLinear.constant(0.95)))
    ratios = [r.friction_force / (0.3 * r.load) for r in partial]
    assert all(0.8 < r.contact_fraction < 1 and r.phase == PHASE_PARTIAL_SLIP for r in partial)
    assert ratios[0] == 0 and np.all(np.diff(ratios) > 0) and ratios[-1] < 0.5


def test_partial_slip_in_full_contact_on_a_layer_bonded_to_a_rigid_base():
    """A bonded layer on a rigid base has a uniform shear compliance h/G: the full stick contact
    carries q = G delta_x / h everywhere (not refused)."""
    h = 2e-4
    problem = _slip(PiecewiseLinear.constant(3.0), LayerSettings(h))
    records = _records(problem)
    for r in records:
        assert r.contact_fraction == 1.0 and r.stick_ratio == 1.0
        np.testing.assert_allclose(r.shear_x, 1e6 * r.delta_x / h, rtol=1e-6, atol=1e-9)
    assert records[-1].friction_force > 0
