"""The transient solver on substrates built from compliance terms (viscontact.bodies.compliance
.term_substrate): a time-dependent Poisson ratio (viscontact.bodies.bulk_elastic) and a viscoelastic layer on a
rigid base (viscontact.bodies.layer), under a held load.

* nu(t), K elastic (seed Zener shear modulus, K = 2 G(0): nu rises from 0.286 to 0.475): Lee & Radok
  with the creep function of the normal compliance operator, a(t)^3 = 3 W R Phi(t)/8 with
  Phi = creep of (1 - nu)/(2G) (viscontact.physics.reference.lee_radok_creep with the BulkElasticMaterial).
  n = 64 on [-2 mm, 2 mm]^2, linear scheme, dt = 0.5 ms to 20 ms: measured 4.0e-4, tolerance 1%
  as for the constant-nu case (tests/validation/test_lee_radok.py); the constant-nu(0) prediction
  is 22% off at 20 ms.
* thin layer (h = 0.12 mm, nu = 0.3, a from 0.43 to 0.74 mm) bonded to a rigid base: Winkler in
  the limit, so under a held load delta(t) = delta(0) (J(t)/J(0))^(1/2) (elastic Winkler:
  W = pi M R delta^2 / h; the Lee-Radok argument for a growing contact). Measured: delta(0) 0.41%
  above Winkler, delta(t)/delta(0) within 0.18% of (J(t)/J(0))^(1/2); tolerance 2% (finite h/a and
  the contact edge crossing cells).
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from vc_testing import SEED_G0, SEED_LOAD, SEED_RADIUS, SEED_TAU, seed_material, sphere_problem

from viscontact.bodies.compliance import term_substrate
from viscontact.errors import ViscontactWarning
from viscontact.bodies.layer import Layer, rigid_base_terms
from viscontact.physics.materials import Material
from viscontact.bodies.bulk_elastic import BulkElasticMaterial, half_space_terms
from viscontact.problem.problem import SolverSettings
from viscontact.physics.reference import lee_radok_creep
from viscontact.running.loop import simulate

ZENER = seed_material()


def held_load(problem, compliance):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ViscontactWarning)  # dt above the shortest material time
        return list(simulate(problem, compliance=compliance))


def test_lee_radok_with_time_dependent_poisson_ratio():
    bulk = BulkElasticMaterial(ZENER, 2 * SEED_G0)
    nu0 = bulk.poisson_ratio_instantaneous
    problem = sphere_problem(Material.zener(SEED_G0, SEED_G0 / 10, SEED_TAU, nu0), 64, 2e-3, t_end=0.02,
                             dt=5e-4, scheme="linear", solver=SolverSettings(tolerance=1e-11))
    compliance = term_substrate(problem.grid, half_space_terms(problem.grid, bulk, ("zz",)), "linear", 5e-4)
    records = held_load(problem, compliance)
    t = np.array([r.t for r in records])
    delta = np.array([r.delta_z for r in records])
    ref = lee_radok_creep(SEED_LOAD, SEED_RADIUS, bulk, t).approach
    np.testing.assert_allclose(delta, ref, rtol=0.01)
    # nu(t) matters: the constant nu(0) prediction is off by far more at the end
    const = lee_radok_creep(SEED_LOAD, SEED_RADIUS, Material.zener(SEED_G0, SEED_G0 / 10, SEED_TAU, nu0), t[-1])
    assert abs(float(const.approach) / delta[-1] - 1) > 0.1


def test_thin_viscoelastic_layer_creeps_as_square_root_of_compliance():
    problem = sphere_problem(ZENER, 48, 1.2e-3, t_end=0.02, dt=5e-4, scheme="linear",
                             solver=SolverSettings(tolerance=1e-11))
    layer = Layer(0.12e-3, SEED_G0, 0.3)
    compliance = term_substrate(problem.grid, rigid_base_terms(problem.grid, layer, ZENER, ("zz",)), "linear", 5e-4)
    records = held_load(problem, compliance)
    t = np.array([r.t for r in records])
    delta = np.array([r.delta_z for r in records])
    winkler0 = np.sqrt(SEED_LOAD * layer.thickness / (np.pi * layer.oedometric_modulus * SEED_RADIUS))
    assert delta[0] == pytest.approx(winkler0, rel=0.02)
    j = ZENER.creep_compliance(t)
    np.testing.assert_allclose(delta / delta[0], np.sqrt(j / j[0]), rtol=0.02)
