"""Hertz contact (Johnson, *Contact Mechanics*, §4.2) as the elastic limit of the transient solver.

Seed material: G(0) = 1.93 MPa (the seed's mu = 2G), G(inf) = G(0)/10, retardation time 0.01 s,
nu = 0.3, R = 10 mm, W = 0.15 N (a0 = 588.7 um, p0 = 0.2067 MPa, delta = 34.66 um).

Tolerances and why:

* Elastic, n = 128 on [-2 a0, 2 a0]^2 (a0/dx = 32): peak pressure and approach within 1% of Hertz
  (measured -2.1e-4 and -4.9e-5): the piecewise-constant BEM errs by O(dx^2) at the centre; the
  largest cell pressure sits at r = dx/sqrt(2), 1/(4 (a/dx)^2) = 2.4e-4 below p0. The contact
  radius from the counted contact cells sqrt(A/pi) is quantised by the cells crossing the edge:
  within 2% (measured 0.5%). Load balance sum p dA = W to 1e-10 (the CG enforces it exactly).
* Viscoelastic limits: the first step of a Zener run solves the elastic problem with J(0) = 1/G(0),
  so it equals the elastic G(0) solution on the same grid to round-off (1e-10); after 20 retardation
  times J(t) = J(inf) up to exp(-20) = 2e-9, so the held-load run equals the elastic G(inf) solution
  on the same grid to 1e-6. Both also within 1% (approach) / 2% (peak) of Hertz at n = 64.
* Grid convergence: fitted log-log slope over n = 32, 64, 128 at a fixed domain. Measured orders:
  peak pressure 2.05, approach 2.2, pressure at the centre cells against Hertz at the same points
  1.6, relative L2 error of the whole field 1.1 (limited by the square-root edge, where the
  piecewise-constant field errs by O(sqrt(dx)) over a band of width dx). Asserted with margin:
  > 1.7, > 1.7, > 1.2, > 0.8; the errors must also decrease monotonically.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from vc_testing import (SEED_A0, SEED_G0, SEED_GINF, SEED_LOAD, SEED_NU, SEED_P0, SEED_RADIUS, SEED_TAU, seed_material,
                        sphere_problem)

from viscontact.errors import ViscontactWarning
from viscontact.physics.materials import Material
from viscontact.problem.problem import SolverSettings
from viscontact.physics.reference import hertz_from_approach, hertz_from_load
from viscontact.running.loop import simulate

G0, GINF, LAM, NU, R, W = SEED_G0, SEED_GINF, SEED_TAU, SEED_NU, SEED_RADIUS, SEED_LOAD
HERTZ0 = hertz_from_load(W, R, G0, NU)
HERTZ_INF = hertz_from_load(W, R, GINF, NU)


def run(material: Material, n: int, half_width: float, *, control: str = "load", value: float = W,
        t_end: float = 0.0, dt: float = 1.0, scheme: str = "constant", every: int = 10**9):
    problem = sphere_problem(material, n, half_width, control=control, value=value, t_end=t_end, dt=dt,
                             scheme=scheme, every=every, solver=SolverSettings(tolerance=1e-12))
    return problem.grid, list(simulate(problem))


def test_seed_numbers():
    assert HERTZ0.radius == pytest.approx(SEED_A0, rel=2e-4)
    assert HERTZ0.peak_pressure == pytest.approx(SEED_P0, rel=2e-4)
    assert hertz_from_approach(HERTZ0.approach, R, G0, NU).load == pytest.approx(W, rel=1e-12)


@pytest.mark.parametrize("control", ["load", "displacement"])
def test_elastic_hertz_n128(control):
    value = W if control == "load" else HERTZ0.approach
    grid, (rec,) = run(Material.elastic(G0, NU), 128, 2 * HERTZ0.radius, control=control, value=value)
    assert rec.pressure.max() == pytest.approx(HERTZ0.peak_pressure, rel=0.01)
    assert rec.delta_z == pytest.approx(HERTZ0.approach, rel=0.01)
    assert np.sqrt(rec.contact_area / np.pi) == pytest.approx(HERTZ0.radius, rel=0.02)
    assert rec.pressure.sum() * grid.cell_area == pytest.approx(rec.load, rel=1e-12)
    assert rec.load == pytest.approx(W, rel=1e-10 if control == "load" else 0.01)
    # the field, not only its peak: Hertz profile within 1% of p0 away from the edge
    x, y = grid.mesh()
    r = np.hypot(x, y)
    inner = r < 0.8 * HERTZ0.radius
    assert np.max(np.abs(rec.pressure - HERTZ0.pressure(r))[inner]) < 0.01 * HERTZ0.peak_pressure
    assert np.all(rec.pressure[r > 1.1 * HERTZ0.radius] == 0)


@pytest.fixture(scope="module")
def limits():
    n, hw = 64, 2.0 * HERTZ_INF.radius
    zener = seed_material()
    # dt = 2 ms is below the stability limit of the constant scheme (2.2 ms, see test_lee_radok)
    # but above the shortest material time (1 ms), where the solver warns that it is coarse
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ViscontactWarning)
        _, recs = run(zener, n, hw, t_end=20 * LAM, dt=2e-3, every=10**9)
    _, (e0,) = run(Material.elastic(G0, NU), n, hw)
    _, (einf,) = run(Material.elastic(GINF, NU), n, hw)
    return recs, e0, einf


def test_viscoelastic_instantaneous_limit(limits):
    recs, e0, _ = limits
    first = recs[0]
    assert first.t == 0.0
    assert np.max(np.abs(first.pressure - e0.pressure)) < 1e-10 * e0.pressure.max()
    assert first.delta_z == pytest.approx(e0.delta_z, rel=1e-10)
    assert first.delta_z == pytest.approx(HERTZ0.approach, rel=0.01)
    assert first.pressure.max() == pytest.approx(HERTZ0.peak_pressure, rel=0.02)


def test_viscoelastic_long_time_limit(limits):
    recs, _, einf = limits
    last = recs[-1]
    assert last.t == pytest.approx(20 * LAM)
    assert np.max(np.abs(last.pressure - einf.pressure)) < 1e-6 * einf.pressure.max()
    assert last.delta_z == pytest.approx(einf.delta_z, rel=1e-6)
    assert last.delta_z == pytest.approx(HERTZ_INF.approach, rel=0.01)
    assert last.pressure.max() == pytest.approx(HERTZ_INF.peak_pressure, rel=0.02)
    assert np.sqrt(last.contact_area / np.pi) == pytest.approx(HERTZ_INF.radius, rel=0.03)


def _order(ns, errors) -> float:
    return float(-np.polyfit(np.log(ns), np.log(errors), 1)[0])


def test_grid_convergence_order():
    ns = np.array([32, 64, 128])
    hw = 2 * HERTZ0.radius
    peak, approach, centre, l2 = [], [], [], []
    for n in ns:
        grid, (rec,) = run(Material.elastic(G0, NU), int(n), hw)
        x, y = grid.mesh()
        exact = HERTZ0.pressure(np.hypot(x, y))
        c = slice(n // 2 - 1, n // 2 + 1)  # the four cells around the centre (x = 0 is a cell edge)
        peak.append(abs(rec.pressure.max() / HERTZ0.peak_pressure - 1))
        approach.append(abs(rec.delta_z / HERTZ0.approach - 1))
        centre.append(np.max(np.abs(rec.pressure[c, c] - exact[c, c])) / HERTZ0.peak_pressure)
        l2.append(np.sqrt(np.sum((rec.pressure - exact) ** 2) / np.sum(exact**2)))
    for errors in (peak, approach, centre, l2):
        assert np.all(np.diff(errors) < 0), errors
    assert _order(ns, peak) > 1.7, peak
    assert _order(ns, approach) > 1.7, approach
    assert _order(ns, centre) > 1.2, centre
    assert _order(ns, l2) > 0.8, l2
