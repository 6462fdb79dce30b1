"""The shipped cases of the analytic shapes, run as shipped (64 x 64 cells, a few seconds each):
cases/flat_punch_creep.toml (a flat punch creeping under a held load on the seed's Zener solid) and
cases/conical_indentation.toml (a 70.3 degree cone pushed to 20 um at a constant rate, then held)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from viscontact.io.case import load_case
from viscontact.physics.reference import FlatPunch, contact_modulus, lee_radok_cone_load
from viscontact.running.api import run

CASES = Path(__file__).resolve().parents[2] / "cases"


@pytest.fixture(scope="module")
def punch():
    return load_case(CASES / "flat_punch_creep.toml"), run(load_case(CASES / "flat_punch_creep.toml"))


@pytest.fixture(scope="module")
def cone():
    return load_case(CASES / "conical_indentation.toml"), run(load_case(CASES / "conical_indentation.toml"))


def test_the_punch_creeps_as_the_creep_compliance(punch):
    """delta(t)/delta(0) = J(t)/J(0) to the solver's tolerance (the face and its pressure field are the
    same at every step: measured 7.8e-10 with the default solver.tolerance = 1e-8, 2.4e-13 with 1e-12
    in tests/validation/test_shapes.py), delta(0) Boussinesq's W / (2 a E*) within the rim's 0.12 dx/a plus
    the face's lattice area (+0.5 %) (measured -0.41 %), the contact area the face's at every step."""
    case, ds = punch
    problem = case.to_problem()
    t, delta = ds["t"].values, ds["delta_z"].values
    creep = problem.material.creep.compliance(t)
    assert np.max(np.abs(delta / delta[0] - creep / creep[0])) < problem.solver.tolerance
    g0, nu = problem.material.shear_modulus_instantaneous, problem.material.poisson_ratio
    truth = FlatPunch.from_load(0.02, 0.5e-3, contact_modulus(g0, nu))
    assert abs(delta[0] / truth.approach - 1) < 0.12 * problem.grid.spacing / 0.5e-3 + 0.005
    assert np.ptp(ds["contact_area"].values) == 0 and ds["contact_area"].values[0] == pytest.approx(
        math.pi * 0.5e-3**2, rel=0.01)
    assert ds.attrs["indenter_shape"] == "flat_punch" and ds.attrs["a0"] == 0.5e-3


def test_the_cone_follows_sneddon_with_lee_and_radok(cone):
    """The load against Lee & Radok's hereditary Sneddon load
    (:func:`viscontact.physics.reference.lee_radok_cone_load`, in closed form: independent of the
    solver's recursive Prony history) from a tenth of the ramp on within 1 %
    (measured at most 0.66 %, at 2.5 ms where the contact radius is 1.2 cells, and 0.45 % just after
    the ramp's end: the time step against the relaxation time of 1 ms), at the end within 0.1 % (measured 0.012 %: G(inf)'s 0.392 mN); the contact radius from the
    contact area (a count of cells) against a = 2 delta tan(alpha)/pi, whatever the modulus, within
    0.4 dx/a from 2 cells on (measured at most 0.35 dx/a; 0.8 % at 20 um)."""
    case, ds = cone
    problem = case.to_problem()
    alpha = math.radians(70.3)
    history = problem.normal.history
    t, load, delta = ds["t"].values, ds["load"].values, ds["delta_z"].values
    truth = lee_radok_cone_load(t, history.times, history.values, alpha, problem.material)
    later = t > 0.002
    assert np.max(np.abs(load[later] / truth[later] - 1)) < 0.01
    assert load[-1] == pytest.approx(truth[-1], rel=1e-3)
    sneddon = 2 * delta * math.tan(alpha) / math.pi
    cells = sneddon / problem.grid.spacing
    deep = cells >= 2
    radius = np.sqrt(ds["contact_area"].values[deep] / math.pi)
    assert np.max(np.abs(radius / sneddon[deep] - 1) * cells[deep]) < 0.4
    assert ds.attrs["indenter_shape"] == "cone" and ds.attrs["indenter_half_angle"] == 70.3
