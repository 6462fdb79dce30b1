"""Periodic line contacts (``grid.periodic = true``, ``grid.dimension = 1``, plane strain) against
independent truth, through the case file and the transient and steady solvers.

* Westergaard (1939; Johnson, *Contact Mechanics*, §13.2): a rigid wavy profile h (1 - cos(2 pi x/lambda))
  on an elastic half-space under the mean pressure p_mean per period. In full contact
  (p_mean >= p* = pi E* h / lambda) the pressure is p_mean + p* cos(2 pi x/lambda); the discrete
  pressure differs by the cell footprint of the collocated strips, (k dx)^2/24 of p* to leading order
  (k = 2 pi/lambda), which the test checks and halves dx to see fall 4x. In partial contact the
  contact is |x| < a with p_mean = p* sin^2(pi a/lambda): |a_num - a| <= 0.75 dx (half a cell of
  counting plus the edge's sub-cell error).
* A long period tends to the isolated line contact: a cylinder on a period of 10 a and 40 a against
  Hertz's line contact (the images' pressure falls with the period), and the steady sliding state on
  a standard linear solid on a period of 40 a against the isolated (DC-FFT) steady state.
"""
import os

import numpy as np
import pytest

from viscontact.io.case import Case
from viscontact.physics.reference import hertz_line_from_load
from viscontact.running.loop import simulate
from viscontact.solvers.steady import solve_steady

G, NU = 1.0e6, 0.3
E_STAR = 2 * G / (1 - NU)
WAVELENGTH, AMPLITUDE = 1e-3, 1e-6
P_STAR = np.pi * E_STAR * AMPLITUDE / WAVELENGTH


def _wavy(tmp_path, n: int, p_mean: float):
    x = -WAVELENGTH / 2 + (np.arange(n) + 0.5) * WAVELENGTH / n
    path = os.path.join(tmp_path, f"wave{n}.npy")
    np.save(path, (AMPLITUDE * (1 - np.cos(2 * np.pi * x / WAVELENGTH)))[None, :])
    case = Case.from_dict({
        "title": "wavy line", "material": {"type": "elastic", "shear_modulus": G, "poisson_ratio": NU},
        "indenter": {"shape": "surface", "file": path},
        "grid": {"n": n, "half_width": WAVELENGTH / 2, "dimension": 1, "periodic": True},
        "normal": {"control": "load", "value": p_mean * WAVELENGTH}, "tangential": {"mode": "none"},
        "time": {"t_end": 1e-3, "dt": 1e-3}})
    problem = case.to_problem()
    return problem, list(simulate(problem))[-1]


def test_westergaard_full_contact_pressure(tmp_path):
    """p = p_mean + p* cos(2 pi x/lambda) at p_mean = 1.5 p*: the error is the footprint's (k dx)^2/24
    (measured 2.49e-5 p* at n = 256, 9.9e-5 at 128) and falls as dx^2."""
    errors = []
    for n in (128, 256):
        problem, rec = _wavy(tmp_path, n, 1.5 * P_STAR)
        x = problem.grid.x
        assert rec.load == pytest.approx(1.5 * P_STAR * WAVELENGTH, rel=1e-10)
        assert rec.contact_fraction == 1.0
        error = np.abs(rec.pressure[0] - (1.5 * P_STAR + P_STAR * np.cos(2 * np.pi * x / WAVELENGTH))).max() / P_STAR
        footprint = (2 * np.pi / n) ** 2 / 24
        assert 0.9 * footprint < error < 1.1 * footprint
        errors.append(error)
    assert errors[0] / errors[1] == pytest.approx(4.0, rel=0.02)


@pytest.mark.parametrize("a_over_lambda", [0.1, 0.2, 0.3, 0.4])
def test_westergaard_partial_contact_width(tmp_path, a_over_lambda):
    problem, rec = _wavy(tmp_path, 256, P_STAR * np.sin(np.pi * a_over_lambda) ** 2)
    p = rec.pressure[0]
    half_width = 0.5 * (p > 0).sum() * problem.grid.spacing
    assert abs(half_width - a_over_lambda * WAVELENGTH) <= 0.75 * problem.grid.spacing
    assert rec.load == pytest.approx(P_STAR * np.sin(np.pi * a_over_lambda) ** 2 * WAVELENGTH, rel=1e-10)


def _cylinder(n: int, half_width: float, periodic: bool, material: dict, tangential: dict) -> Case:
    return Case.from_dict({
        "title": "cylinder", "material": material, "indenter": {"shape": "cylinder", "radius": 0.01},
        "grid": {"n": n, "half_width": half_width, "dimension": 1, "periodic": periodic},
        "normal": {"control": "load", "value": 20.0}, "tangential": tangential,
        "time": {"t_end": 1e-3, "dt": 1e-3}})


def test_a_long_period_tends_to_hertz_line_contact():
    """A cylinder on a period of 10 a and 40 a (dx = a/25.6): the peak pressure 0.82 % above Hertz's
    at 10 a, 3.4e-4 at 40 a (the images' share falls with the period), the half-width within a cell."""
    hz = hertz_line_from_load(20.0, 0.01, G, NU, 1e-3)
    elastic = {"type": "elastic", "shear_modulus": G, "poisson_ratio": NU}
    errors = []
    for periods, n in ((10, 256), (40, 1024)):
        problem = _cylinder(n, periods * hz.radius / 2, True, elastic, {"mode": "none"}).to_problem()
        rec = list(simulate(problem))[-1]
        assert rec.load == pytest.approx(20.0, rel=1e-10)
        assert rec.contact_area / 2 == pytest.approx(hz.radius, abs=problem.grid.spacing)
        errors.append(rec.pressure.max() / hz.peak_pressure - 1)
    assert 0.004 < errors[0] < 0.012 and abs(errors[1]) < 1e-3


def test_periodic_steady_sliding_tends_to_the_isolated_steady_state():
    """Frictionless steady sliding of the cylinder on a standard linear solid at v tau / a = 1: on a
    period of 40 a, mu_app within 1 % of the isolated (DC-FFT) line contact's (measured 0.33 %), the
    same contact width."""
    a = hertz_line_from_load(20.0, 0.01, 1e6, 0.5, 1e-3).radius
    zener = {"type": "zener", "shear_modulus_instantaneous": 1e6, "shear_modulus_long_term": 1e5,
             "retardation_time": 0.01, "poisson_ratio": 0.5}
    sliding = {"mode": "frictionless_sliding", "sliding_speed": a / 0.01}
    isolated = solve_steady(_cylinder(1024, 20 * a, False, zener, sliding).to_problem())
    periodic = solve_steady(_cylinder(1024, 20 * a, True, zener, sliding).to_problem())
    assert periodic.load == pytest.approx(20.0, rel=1e-9)
    assert isolated.mu_app > 0.01
    assert periodic.mu_app == pytest.approx(isolated.mu_app, rel=0.01)
    assert periodic.contact_area == pytest.approx(isolated.contact_area, abs=2 * 40 * a / 1024)
