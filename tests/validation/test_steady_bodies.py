"""Steady sliding on the bodies built from compliance terms: a time-dependent Poisson ratio
(``bulk_modulus``, viscontact.bodies.bulk_elastic) and a viscoelastic layer on a rigid base (viscontact.bodies.layer),
on DC-FFT and periodic grids, against independent truth.

Each term's steady kernel is built from its own spectrum (Compliance.steady_convolver, the
shapes of viscontact.physics.steady_kernels.SteadyShape); on a periodic grid the operator is each term's
spectrum times its complex compliance at -k_x v (Compliance.steady_spectrum).

References and measured values (seed Zener G(0) = 1.93 MPa, G(inf) = G(0)/10, tau = 10 ms, R = 10 mm):

Bodies: nu(t) with K = 2 G(0); a layer bonded to a rigid base; a viscoelastic layer bonded to an
elastic base (G_s = 3 G(0), nu_s = 0.4: one kernel per shift node, viscontact.bodies.layer
.elastic_base_terms).

* slow sliding (v tau/a0 = 1e-4) is the elastic contact at G(inf), nu(inf); fast (1e4) at G(0), nu(0).
  nu(t) with K = 2 G(0), n = 64: Hertz peak pressure and approach within 0.08 % and 0.27 %
  (tolerance 1 %, as for the constant-nu steady limits: the grid resolves the Hertz peak to ~0.1 %
  and v tau/a = 1e4 leaves a viscous residue below 1e-3). Layer h = 0.4 mm bonded to a rigid base,
  n = 32: against the transient solver's elastic layer at G(inf) / G(0) (same kernels, one step),
  approach within 1e-9 / 4.2e-4 and pressure within 1e-4 / 1.2e-3 of the peak (tolerance 1 %); on
  the elastic base 1.2e-7 / 3.0e-4 and 1.0e-4 / 1.4e-3.
* the transient's sliding state after 6 tau tends to the steady state on the same grid (the wake on
  the grid): the remaining difference is the time discretisation of the moving frame (v dt = dx,
  linear scheme), as for the half-space (tests/validation/test_steady.py). DC-FFT, n = 32 (64):
  nu(t) mu_app 0.09 % (0.16 %), load 0.43 % (0.14 %); layer h = 0.5 mm mu_app 0.35 % (0.13 %), load
  0.51 % (0.17 %), on the elastic base mu_app 0.28 %, load 0.53 %; tolerance 1 %. Periodic,
  n = 32, load control: mu_app and approach within 0.08 % and 0.11 % (nu(t)), 0.14 % and 0.17 %
  (layer), 0.10 % and 0.14 % (on the elastic base), as the periodic half-space (0.07 %,
  0.11 %); tolerance 0.5 %.
* K -> inf (1e15 Pa) is the incompressible half-space, computed by the half-space's own steady
  kernels (one builder at nu = 0.5) and periodic spectrum (the material's complex modulus): the
  term route (nu = 0 and nu = 1 kernels with the J and L spectra) agrees to 1e-8.
"""
from __future__ import annotations

import dataclasses
import warnings

import numpy as np
import pytest

from vc_testing import SEED_A0, SEED_G0, SEED_RADIUS, SEED_TAU, seed_material, sphere_problem

from viscontact.errors import ViscontactWarning
from viscontact.numerics.grid import Grid
from viscontact.physics.materials import Material
from viscontact.bodies.bulk_elastic import BulkElasticMaterial
from viscontact.problem.problem import LayerSettings
from viscontact.physics.reference import hertz_from_load
from viscontact.solvers.steady import solve_steady
from viscontact.running.loop import simulate

LOAD = 0.148
K = 2 * SEED_G0
BULK = BulkElasticMaterial(seed_material(), K)
# the problem's material carries nu(0) (as a case with bulk_modulus builds it)
ZENER_NU0 = Material.zener(SEED_G0, SEED_G0 / 10, SEED_TAU, BULK.poisson_ratio_instantaneous)


def with_body(problem, periodic: bool = False, **body):
    grid = Grid(problem.grid.n, problem.grid.half_width, periodic)
    return dataclasses.replace(problem, grid=grid, **body)


def last_record(problem):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ViscontactWarning)  # dt above the shortest material time
        return list(simulate(problem))[-1]


def sliding(material, n, half_width, speed_ratio, **kwargs):
    return sphere_problem(material, n, half_width, value=LOAD, mode="frictionless_sliding",
                          speed=speed_ratio * SEED_A0 / SEED_TAU, t_end=1.0, **kwargs)


@pytest.mark.parametrize("speed_ratio", [1e-4, 1e4])
def test_bulk_modulus_steady_limits_are_hertz(speed_ratio):
    slow = speed_ratio < 1
    g = ZENER_NU0.shear_modulus_long_term if slow else SEED_G0
    nu = BULK.poisson_ratio_long_term if slow else BULK.poisson_ratio_instantaneous
    ref = hertz_from_load(LOAD, SEED_RADIUS, g, nu)
    rec = solve_steady(with_body(sliding(ZENER_NU0, 64, 1.6 * ref.radius, speed_ratio), bulk_modulus=K))
    assert rec.load == pytest.approx(LOAD, rel=1e-9)
    assert rec.pressure.max() == pytest.approx(ref.peak_pressure, rel=0.01)
    assert rec.delta_z == pytest.approx(ref.approach, rel=0.01)
    # nu(t) matters here: the Hertz approach with the other limit's nu is off by more than 5 %
    other = hertz_from_load(LOAD, SEED_RADIUS, g, BULK.poisson_ratio_instantaneous if slow else BULK.poisson_ratio_long_term)
    assert abs(other.approach / rec.delta_z - 1) > 0.05


# on an elastic base (3 G(0), nu_s = 0.4) a viscoelastic layer has one kernel per shift node
ON_RIGID, ON_ELASTIC = LayerSettings(0.4e-3), LayerSettings(0.4e-3, "elastic", "bonded", 3 * SEED_G0, 0.4)


# on a periodic domain the modes uniform along x (k_x = 0) relax fully at any speed: no fast limit
@pytest.mark.parametrize("speed_ratio, periodic, layer", [(1e-4, False, ON_RIGID), (1e4, False, ON_RIGID),
                                                          (1e-4, True, ON_RIGID), (1e-4, False, ON_ELASTIC),
                                                          (1e4, False, ON_ELASTIC)])
def test_layer_steady_limits_are_the_elastic_layer(speed_ratio, periodic, layer):
    g = seed_material().shear_modulus_long_term if speed_ratio < 1 else SEED_G0
    elastic = with_body(sphere_problem(Material.elastic(g, 0.3), 32, 1.6e-3, value=LOAD, t_end=1e-3, dt=1e-3),
                        periodic, layer=layer)
    ref = last_record(elastic)
    rec = solve_steady(with_body(sliding(seed_material(), 32, 1.6e-3, speed_ratio), periodic, layer=layer))
    assert rec.delta_z == pytest.approx(ref.delta_z, rel=0.01)
    assert np.abs(rec.pressure - ref.pressure).max() <= 0.01 * ref.pressure.max()
    # the layer matters: the half-space at the same modulus is softer by far
    half = hertz_from_load(LOAD, SEED_RADIUS, g, 0.3)
    assert ref.delta_z < 0.9 * half.approach


def test_periodic_bulk_modulus_slow_limit_is_the_elastic_contact():
    ref = solve_steady(with_body(sliding(Material.elastic(SEED_G0 / 10, BULK.poisson_ratio_long_term), 32, 2e-3, 1e-4),
                                 True))
    rec = solve_steady(with_body(sliding(ZENER_NU0, 32, 2e-3, 1e-4), True, bulk_modulus=K))
    assert rec.delta_z == pytest.approx(ref.delta_z, rel=0.01)
    assert np.abs(rec.pressure - ref.pressure).max() <= 0.01 * ref.pressure.max()


@pytest.mark.parametrize("periodic", [False, True])
def test_huge_bulk_modulus_steady_is_the_incompressible_half_space(periodic):
    incompressible = Material.zener(SEED_G0, SEED_G0 / 10, SEED_TAU, 0.5)
    half = solve_steady(with_body(sliding(incompressible, 32, 2.6 * SEED_A0, 0.8), periodic))
    ours = solve_steady(with_body(sliding(incompressible, 32, 2.6 * SEED_A0, 0.8), periodic, bulk_modulus=1e15))
    assert half.mu_app > 0.01                     # a viscous state, not a limit
    assert ours.delta_z == pytest.approx(half.delta_z, rel=1e-8)
    assert ours.mu_app == pytest.approx(half.mu_app, rel=1e-7)
    assert np.abs(ours.pressure - half.pressure).max() <= 1e-7 * half.pressure.max()


BODIES = {"half_space": (seed_material(), {}), "bulk_modulus": (ZENER_NU0, {"bulk_modulus": K}),
          "layer": (seed_material(), {"layer": LayerSettings(0.5e-3)}),
          "layer on elastic": (seed_material(), {"layer": dataclasses.replace(ON_ELASTIC, thickness=0.5e-3)})}


@pytest.mark.parametrize("body", ["bulk_modulus", "layer", "layer on elastic"])
def test_long_time_sliding_tends_to_the_steady_state(body):
    material, extra = BODIES[body]
    problem = with_body(sphere_problem(material, 32, 5.12 * SEED_A0, control="displacement", value=30e-6,
                                       mode="frictionless_sliding", speed=0.8 * SEED_A0 / SEED_TAU,
                                       t_end=6 * SEED_TAU, scheme="linear", every=10**6), **extra)
    with warnings.catch_warnings():
        warnings.filterwarnings("error", message="history dropped")  # the wake must fit on the grid
        last = last_record(problem)
    ref = solve_steady(problem)
    assert ref.mu_app > 0.01
    assert last.mu_app == pytest.approx(ref.mu_app, rel=0.01)
    assert last.load == pytest.approx(ref.load, rel=0.01)


@pytest.mark.parametrize("body", ["half_space", "bulk_modulus", "layer", "layer on elastic"])
def test_periodic_long_time_sliding_tends_to_the_steady_state(body):
    material, extra = BODIES[body]
    problem = with_body(sphere_problem(material, 32, 2e-3, value=LOAD, mode="frictionless_sliding",
                                       speed=0.8 * SEED_A0 / SEED_TAU, t_end=6 * SEED_TAU, scheme="linear",
                                       every=10**6), True, **extra)
    last = last_record(problem)
    ref = solve_steady(problem)
    assert ref.mu_app > 0.01
    assert last.mu_app == pytest.approx(ref.mu_app, rel=0.005)
    assert last.delta_z == pytest.approx(ref.delta_z, rel=0.005)


def test_bulk_modulus_steady_friction_couples_as_the_instantaneous_half_space():
    """Gross sliding (mu_f = 0.3) at v tau/a0 = 1e4: the (1 - 2 nu) coupling term of the steady
    operator (K_zz + mu_f K_zx, each from its own spectrum) shifts the contact as the elastic
    half-space with G(0), nu(0) does (measured -0.0423 a and -0.0429 a; +0.0005 a without the
    coupling, solver.coupling = false)."""
    ref_material = Material.elastic(SEED_G0, BULK.poisson_ratio_instantaneous)
    hertz = hertz_from_load(LOAD, SEED_RADIUS, SEED_G0, BULK.poisson_ratio_instantaneous)

    def gross(material, **body):
        return solve_steady(with_body(sphere_problem(material, 64, 1.6 * hertz.radius, value=LOAD, mode="gross_sliding",
                                                     friction=0.3, speed=1e4 * SEED_A0 / SEED_TAU, t_end=1.0), **body))

    ours, ref = gross(ZENER_NU0, bulk_modulus=K), gross(ref_material)
    assert abs(ref.contact_shift) > 0.02 * hertz.radius
    assert ours.contact_shift == pytest.approx(ref.contact_shift, abs=1e-3 * hertz.radius)
