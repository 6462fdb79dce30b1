"""The analytic indenter shapes against their closed forms (viscontact.physics.reference), through the
transient solver on an elastic and a Zener half-space. Sneddon's flat punch (the stiffness 2 a E* and
the pressure away from the rim) is tests/validation/test_flat_punch.py, as a gap and as the shape.

G = 1 MPa, nu = 0.3 (E* = 2.857 MPa) throughout. Tolerances and why (measured):

* Elliptical Hertz (Johnson, Sec. 4.2), R_x = 40 mm, R_y = 10 mm, W = 50 mN: a_x = 0.987 mm,
  a_y = 0.395 mm (e = 0.917), p0 = 61.3 kPa, delta = 20.0 um. The semi-axes from the pressure's second
  moments (<x^2> = a_x^2/5 for p0 sqrt(1 - (x/a_x)^2 - (y/a_y)^2)), a smooth measure that converges
  at second order (the contact's cell count is a lattice count). On a domain of 1.5 a_x, at
  n = 32, 64, 128 (a_y/dx = 4.3, 8.5, 17.1): a_y/a_x -0.73 %, -0.14 %, -0.006 %; p0 -0.60 %,
  -0.14 %, -0.04 %; delta -0.08 %, -0.010 %, -0.007 %. Asserted at n = 64: the ratio and p0 within
  0.5 %, delta within 0.1 %, and the ratio's and p0's errors falling 3x or more from n = 32.
* Sneddon's cone, alpha = 70.3 deg (a Berkovich tip's equivalent cone), under an approach with
  a/dx = 2 to 20: the load within 0.03 dx/a of W = (pi/2) E* a^2 cot(alpha) (measured 1.1 %, 0.8 %,
  0.46 %, 0.11 %, 0.045 %, 0.014 % at a/dx = 2, 3, 4, 8, 10, 20: at most 0.027 dx/a, the tip's
  logarithmic pressure averaged over its cells; viscontact.problem.shapes.CONE_LOAD_ERROR_PER_CELL);
  the contact radius from the pressure's second moment (<r^2> = a^2/3 for (E* cot(alpha)/2)
  arccosh(a/r)) within 0.02 dx/a (measured at most 0.017 dx/a, at a/dx = 3); the one from the contact
  area, a count of cells, within 0.25 dx/a at these depths (measured at most 0.19 dx/a; up to 0.35
  dx/a at other depths, tests/cases/test_shape_cases.py). Under load control the
  approach errs by half the load's relative error (W ~ delta^2).
* A finite roller (R = 10 mm, L = 2 mm, rounded ends of 0.4 mm, W = 50 mN) has no closed form; its
  middle section is in plane strain, Hertz's line contact for its own load per unit length W'(0)
  (the row y = 0: 1.185 W/L, the rounded ends carrying less): half-width (from the row's second
  moment, <x^2> = b^2/4) and peak within 1.5 % (measured -0.86 %, -0.96 %, -1.00 % and +0.84 %,
  +0.98 %, +1.03 % at b/dx = 9, 18, 36: a 1 % departure of the finite roller, L/b = 13, converged
  on the grid to 0.15 % from b/dx = 9 to 18).
* A flat punch on a Zener half-space under a held load: its contact is its face at every step, its
  pressure the same field, so its approach creeps exactly as the creep compliance,
  delta(t)/delta(0) = J(t)/J(0): measured 2.4e-13 over 5 retardation times with either time scheme
  (the hereditary integral of a constant traction is exact). Asserted to 1e-11.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from vc_testing import sphere_problem

from viscontact.physics import reference
from viscontact.physics.materials import Material
from viscontact.problem.problem import SolverSettings
from viscontact.problem.shapes import CONE_LOAD_ERROR_PER_CELL, Cone, Cylinder, Ellipsoid, FlatPunch, Shape
from viscontact.running import guards
from viscontact.running.loop import simulate

G, NU = 1e6, 0.3
E_STAR = 2 * G / (1 - NU)
ELASTIC = Material.elastic(G, NU)


def _records(shape: Shape, n: int, half_width: float, control: str, value: float, material: Material = ELASTIC,
             t_end: float = 0.0, dt: float = 1e-3, scheme: str = "linear"):
    """(problem, records) of ``shape`` pressed by ``value`` (N or m) on n x n cells of +-half_width [m],
    through the guards (as a case is run)."""
    pb = sphere_problem(material, n, half_width, control=control, value=value, t_end=t_end, dt=dt, scheme=scheme,
                        solver=SolverSettings(tolerance=1e-12))
    pb = replace(pb, radius=None, shape=shape, gap=shape.gap(pb.grid))
    guards.check_problem(pb)
    return pb, list(simulate(pb))


def _second_moments(pb, pressure) -> tuple[float, float]:
    """(<x^2>, <y^2>) [m^2] of a pressure field, weighted by the pressure."""
    x, y = pb.grid.mesh()
    return float((pressure * x**2).sum() / pressure.sum()), float((pressure * y**2).sum() / pressure.sum())


# --- elliptical Hertz -----------------------------------------------------------------------------
R_X, R_Y, LOAD = 0.04, 0.01, 0.05


def test_the_elliptical_reference_is_hertz_for_a_sphere_and_symmetric():
    sphere = reference.elliptical_hertz(LOAD, 0.01, 0.01, E_STAR)
    hertz = reference.hertz_from_load(LOAD, 0.01, G, NU)
    assert sphere.semi_axis_x == sphere.semi_axis_y == pytest.approx(hertz.radius, rel=1e-12)
    assert sphere.approach == pytest.approx(hertz.approach, rel=1e-12)
    near = reference.elliptical_hertz(LOAD, 0.01 * (1 + 1e-6), 0.01, E_STAR)  # the limit e -> 0, continuous
    assert near.semi_axis_x == pytest.approx(hertz.radius, rel=1e-5)
    assert near.peak_pressure == pytest.approx(hertz.peak_pressure, rel=1e-5)
    h, swapped = (reference.elliptical_hertz(LOAD, rx, ry, E_STAR) for rx, ry in ((R_X, R_Y), (R_Y, R_X)))
    assert (h.semi_axis_x, h.semi_axis_y) == (swapped.semi_axis_y, swapped.semi_axis_x)
    # the load closes: W = (2/3) pi a b p0
    assert 2 / 3 * math.pi * h.semi_axis_x * h.semi_axis_y * h.peak_pressure == pytest.approx(LOAD, rel=1e-12)


def test_an_ellipsoid_is_elliptical_hertz():
    truth = reference.elliptical_hertz(LOAD, R_X, R_Y, E_STAR)
    errors = {}
    for n in (32, 64):
        pb, records = _records(Ellipsoid(R_X, R_Y), n, 1.5 * truth.semi_axis_x, "load", LOAD)
        last = records[-1]
        mx, my = _second_moments(pb, last.pressure)
        errors[n] = (math.sqrt(my / mx) / (truth.semi_axis_y / truth.semi_axis_x) - 1,
                     float(last.pressure.max()) / truth.peak_pressure - 1, last.delta_z / truth.approach - 1)
    ratio, peak, approach = errors[64]
    assert abs(ratio) < 5e-3 and abs(peak) < 5e-3 and abs(approach) < 1e-3, errors
    assert abs(errors[32][0]) >= 3 * abs(ratio) and abs(errors[32][1]) >= 3 * abs(peak), errors
    assert pb.shape.size_at_load(LOAD, E_STAR) == pytest.approx(math.sqrt(truth.semi_axis_x * truth.semi_axis_y),
                                                                 rel=1e-12)


# --- Sneddon's cone -------------------------------------------------------------------------------
ALPHA, CONE_HALF_WIDTH, CONE_N = 70.3, 2e-4, 64


def _cone_approach(cells: float) -> float:
    """The approach [m] whose Sneddon contact radius is ``cells`` cells of the cone's grid."""
    dx = 2 * CONE_HALF_WIDTH / CONE_N
    return cells * dx * math.pi / (2 * math.tan(math.radians(ALPHA)))


@pytest.mark.parametrize("cells", [3, 10, 20])
def test_a_cone_follows_sneddon_load_depth_and_radius(cells):
    delta = _cone_approach(cells)
    truth = reference.Cone.from_approach(delta, math.radians(ALPHA), E_STAR)
    pb, records = _records(Cone(ALPHA), CONE_N, CONE_HALF_WIDTH, "displacement", delta)
    last, cell = records[-1], pb.grid.spacing / truth.radius
    assert abs(last.load / truth.load - 1) <= CONE_LOAD_ERROR_PER_CELL * cell
    mx, my = _second_moments(pb, last.pressure)
    assert abs(math.sqrt(3 * (mx + my)) / truth.radius - 1) <= 0.02 * cell
    assert abs(math.sqrt(last.contact_area / math.pi) / truth.radius - 1) <= 0.25 * cell
    # under the load Sneddon gives for that approach: the approach to half the load's error (W ~ delta^2)
    pb, records = _records(Cone(ALPHA), CONE_N, CONE_HALF_WIDTH, "load", truth.load)
    assert abs(records[-1].delta_z / delta - 1) <= 0.5 * CONE_LOAD_ERROR_PER_CELL * cell


def test_the_viscoelastic_cone_reference_is_the_hereditary_integral():
    """lee_radok_cone_load in closed form against the trapezoidal rule of its integral on 400,001
    points (measured 1.3e-10), and Sneddon's elastic load on an elastic body (exactly)."""
    alpha, zener = math.radians(ALPHA), Material.zener(G, G / 10, 0.01, NU)
    times, depths = [0.0, 0.02, 0.04], [0.0, 2e-5, 2e-5]
    t = np.array([0.005, 0.02, 0.021, 0.04])
    closed = reference.lee_radok_cone_load(t, times, depths, alpha, zener)
    for tk, value in zip(t, closed):
        s = np.linspace(0.0, tk, 400001)
        relaxation = zener.relaxation_modulus(tk - s)
        integral = np.trapezoid(relaxation * np.gradient(np.interp(s, times, depths) ** 2, s), s)
        assert value == pytest.approx(4 * math.tan(alpha) / (math.pi * (1 - NU)) * integral, rel=1e-8)
    elastic = reference.lee_radok_cone_load(1.0, [0.0, 0.5], [0.0, 1e-5], alpha, ELASTIC)
    assert elastic == pytest.approx(reference.Cone.from_approach(1e-5, alpha, E_STAR).load, rel=1e-14)


def test_the_cone_reference_closes():
    """Sneddon's relations: W = (2/pi) E* tan(alpha) delta^2 and the pressure's integral is W."""
    alpha = math.radians(ALPHA)
    cone = reference.Cone.from_load(0.01, alpha, E_STAR)
    assert cone.load == pytest.approx(2 / math.pi * E_STAR * math.tan(alpha) * cone.approach**2, rel=1e-12)
    assert reference.Cone.from_approach(cone.approach, alpha, E_STAR).radius == pytest.approx(cone.radius, rel=1e-12)
    r = np.linspace(0.0, cone.radius, 400001)[1:]
    integral = np.trapezoid(2 * math.pi * r * cone.pressure(r), r)
    assert integral == pytest.approx(cone.load, rel=1e-4)


# --- a finite roller's middle ----------------------------------------------------------------------
def test_a_finite_rollers_middle_is_hertz_line_contact():
    found = []
    for n in (64, 128):
        pb, records = _records(Cylinder(0.01, 2e-3, 4e-4), n, 1.3e-3, "load", 0.05)
        p, x, dx = records[-1].pressure, pb.grid.x, pb.grid.spacing
        row = 0.5 * (p[n // 2 - 1] + p[n // 2])  # y = 0, between the two middle rows
        per_length = float(row.sum() * dx)
        b = reference.hertz_line_half_width(per_length, 0.01, E_STAR)
        found.append((2 * math.sqrt(float((row * x**2).sum() / row.sum())) / b - 1,
                      float(row.max()) / (2 * per_length / (math.pi * b)) - 1))
        assert per_length > 0.05 / 2e-3  # the middle carries more than the mean: the ends are rounded
    assert all(abs(e) < 0.015 for pair in found for e in pair), found
    assert abs(found[0][0] - found[1][0]) < 2e-3 and abs(found[0][1] - found[1][1]) < 2e-3, found


# --- a flat punch creeping on a Zener half-space ---------------------------------------------------
@pytest.mark.parametrize("scheme", ["linear", "constant"])
def test_a_flat_punch_under_a_held_load_creeps_as_the_creep_compliance(scheme):
    zener = Material.zener(G, G / 10, 0.01, NU)
    pb, records = _records(FlatPunch(5e-4), 32, 1e-3, "load", 0.01, material=zener, t_end=0.05, dt=5e-4,
                           scheme=scheme)
    t = np.array([r.t for r in records])
    delta = np.array([r.delta_z for r in records])
    creep = zener.creep.compliance(t)
    assert np.max(np.abs(delta / delta[0] - creep / creep[0])) < 1e-11
    assert delta[-1] / delta[0] > 9  # it crept: J(5 tau)/J(0) = 10 - 9 exp(-5) = 9.94
    assert len({r.contact_area for r in records}) == 1  # the face, at every step
