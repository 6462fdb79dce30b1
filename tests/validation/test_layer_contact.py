"""Frictionless sphere on an elastic layer bonded to a rigid base (viscontact.bodies.layer kernels + the
Polonsky-Keer solver), against the asymptotic limits of the layer:

* thin compressible layer: Winkler foundation with the oedometric modulus M = 2G(1-nu)/(1-2nu),
  p = M (delta - r^2/2R) / h (the elastic-foundation model; exact as h/a -> 0). h/a = 0.1: the edge region
  of width ~h deviates from Winkler, measured 0.2 % on the load and 1.4 % of the peak on the
  profile; tolerances 0.5 % and 3 %.
* thin incompressible layer: the squeeze-flow limit (in-plane displacement parabolic across the
  layer, zero at the bonded base, shear-free at the frictionless top; volume conserved) gives
  u_z = -(h^3/3G) lap p, whose contact solution with p = dp/dr = 0 at r = a is
  p = p0 (1 - r^2/a^2)^2, a^2 = 4 R delta, p0 = 3 G a^4 / (32 R h^3) (cf. Jaffar 1989). The correction is O(h/a): the test
  measures first-order convergence of the contact radius and the profile (h/a = 1/10, 1/20).
* thick layer: Hertz as h/a -> inf (errors falling at least as fast as a/h).
* a layer many periods thick on a periodic grid: the periodic half-space of the layer material
  (through the transient solver, frictionless and in gross sliding), its approach shifted by the
  uniform compliance h/M times the mean pressure.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from vc_testing import sphere_problem

from viscontact.numerics.constrained import constrained_cg
from viscontact.numerics.convolution import Convolver, FourierPreconditioner
from viscontact.numerics.grid import Grid
from viscontact.bodies.layer import Layer, influence_coefficients
from viscontact.physics.materials import Material
from viscontact.problem.problem import LayerSettings
from viscontact.physics.reference import hertz_from_approach
from viscontact.running.loop import simulate

G, R, A = 1.0e6, 0.01, 1.0e-3


def contact(grid: Grid, layer: Layer, approach: float) -> np.ndarray:
    """Pressure [Pa] under a rigid sphere pushed by ``approach`` [m] (displacement control)."""
    kernel = influence_coefficients(grid, layer, ("zz",))["zz"]
    conv = Convolver.from_kernels(grid.n, {"zz": kernel})
    x, y = grid.mesh()
    gap = (x**2 + y**2) / (2 * R)
    sol = constrained_cg(lambda p: conv.apply("zz", p), approach - gap, np.zeros_like(gap), 0.0, np.inf,
                         preconditioner=FourierPreconditioner.for_kernel(kernel), tolerance=1e-10)
    return sol.x


def contact_radius(grid: Grid, p: np.ndarray) -> float:
    return float(np.sqrt(np.count_nonzero(p) * grid.cell_area / np.pi))


def test_thin_compressible_layer_is_winkler():
    grid = Grid(64, 1.6 * A)
    layer = Layer(A / 10, G, 0.3)
    approach = A**2 / (2 * R)
    p = contact(grid, layer, approach)
    x, y = grid.mesh()
    winkler = layer.oedometric_modulus / layer.thickness * np.clip(approach - (x**2 + y**2) / (2 * R), 0, None)
    assert p.sum() == pytest.approx(winkler.sum(), rel=5e-3)
    assert np.max(np.abs(p - winkler)) < 0.03 * winkler.max()


def test_thin_incompressible_layer_profile():
    errors = []
    for ratio in (10, 20):
        grid = Grid(64, 1.6 * A)
        h = A / ratio
        p = contact(grid, Layer(h, G, 0.5), A**2 / (4 * R))
        a_num = contact_radius(grid, p)
        x, y = grid.mesh()
        shape = p.max() * np.clip(1 - (x**2 + y**2) / a_num**2, 0, None) ** 2
        p0 = 3 * G * A**4 / (32 * R * h**3)
        errors.append((abs(a_num / A - 1), np.max(np.abs(p - shape)) / p.max(), abs(p.max() / p0 - 1)))
    (a10, s10, p10), (a20, s20, p20) = errors
    assert a10 / a20 > 1.6 and s10 / s20 > 1.6  # first order in h/a (measured 1.8, 1.9)
    assert a20 < 0.07 and s20 < 0.08 and p20 < 0.05  # measured 0.058, 0.063, 0.026


def test_thick_layer_tends_to_hertz():
    grid = Grid(32, 1.6 * A)
    hertz = hertz_from_approach(A**2 / R, R, G, 0.3)
    errors = []
    for ratio in (2, 4):
        p = contact(grid, Layer(ratio * A, G, 0.3), A**2 / R)
        errors.append(abs(p.sum() * grid.cell_area / hertz.load - 1))
    assert errors[1] < errors[0] / 2  # measured (n = 64): 0.71, 0.28, 0.12 for h/a = 2, 4, 8
    assert errors[1] < 0.35


@pytest.mark.parametrize("mode, friction", [("none", 0.0), ("gross_sliding", 0.5)])
def test_periodic_contact_on_a_thick_layer_is_the_half_space(mode, friction):
    """A bi-sinusoidal surface (wavelength L = 2 mm, amplitude 2 um, n = 32, load 0.02 N per period:
    about half the cells in contact) on an elastic layer h = 10 L thick bonded to a rigid base, periodic
    grid, load control, one step of the transient solver (viscontact.running.loop.simulate): at
    k h >= 2 pi h/L = 63 the layer is the half-space (to exp(-126)), so the pressure is that of the
    periodic half-space run (the Ewald kernels of viscontact.physics.periodic) and the approach that one
    plus the uniform compliance h/M times the mean pressure. Frictionless and in gross sliding with
    mu = 0.5 (the zx coupling). Measured: pressures within 4e-14 of the peak, the approach shift
    within 3e-16 of h/M p_mean; tolerance 1e-9 (the kernels differ by round-off, far below the CG
    tolerance 1e-8, so both runs take the same iterations). (The former periodic layer kernels:
    1.5 % and 6.9 % of the peak, the shift 6e-4 and 7e-4 off.)"""
    grid = Grid(32, 1e-3, periodic=True)
    x, y = grid.mesh()
    period = 2 * grid.half_width
    gap = 2e-6 * (2 - np.cos(2 * np.pi * x / period) - np.cos(2 * np.pi * y / period))
    load, dt = 0.02, 1e-3
    layer = Layer(10 * period, G, 0.3)

    def last(body: LayerSettings | None):
        problem = sphere_problem(Material.elastic(G, 0.3), grid.n, grid.half_width, value=load, mode=mode,
                                 friction=friction, speed=grid.spacing / dt if friction else 0.0, t_end=dt, dt=dt)
        problem = dataclasses.replace(problem, grid=grid, gap=gap, layer=body)
        return list(simulate(problem))[-1]

    half, ours = last(None), last(LayerSettings(layer.thickness))
    assert 0.4 < np.count_nonzero(half.pressure) / grid.n**2 < 0.6  # partial contact
    assert np.abs(ours.pressure - half.pressure).max() <= 1e-9 * half.pressure.max()
    shift = layer.thickness / layer.oedometric_modulus * load / period**2
    assert ours.delta_z - half.delta_z == pytest.approx(shift, rel=1e-9)
