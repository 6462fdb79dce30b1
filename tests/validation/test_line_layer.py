"""A layer on a base in a line contact (``[layer]``, ``grid.dimension = 1``), periodic or isolated.

A load uniform along y on a layered half-space is a plane-strain problem: its Fourier transform along
y is concentrated at q_y = 0, so the plane-strain surface compliance of the layer is its 3-D spectral
compliance at q = (k, 0), M(|k|) (the in-plane problem of :mod:`viscontact.bodies.layer`; the
anti-plane one does not enter). The two limits:

* thick (h = 250 periods): the periodic half-space line contact, its pressure to round-off and its
  approach shifted by the uniform compliance of the layer on a rigid base, (h/M) p_mean
  (M = 2G(1 - nu)/(1 - 2 nu), p_mean = W / period);
* thin, compressible, bonded to a rigid base: each column deforms in uniaxial strain,
  sigma_zz = M u_z / h (the Winkler limit of the layer), so under a cylinder
  p(x) = (M/h)(delta - x^2/(2R)) over |x| < a = sqrt(2 R delta), W = (4/3)(M/h) a delta, i.e.
  a = (3 W h R / (2 M))^(1/3). The exact layer tends to it as (h/a)^2: measured peak pressure
  -0.23 % at a/h = 6, -0.034 % at a/h = 15; approach +0.15 % and +0.027 %.

The isolated line's kernels (DC-FFT: the strips' closed form with the depth-smoothed swap and a
remainder on a periodic box, :func:`viscontact.bodies.layer.influence_coefficients`) are built
independently of the periodic ones (the exact alias sums): far from its images (a period of 13 to
200 h, where a layer on a rigid base has screened every load) the periodic contact is the isolated
one, its pressure to 1e-9 of the peak and its approach (relative to the base in both) to 2.4e-7
(measured); the transient and the steady state alike. An elastic base of the layer's own material is
the half-space, its strips and datum, to round-off; a layer 0.1 m thick carries Hertz's line
contact of the half-space (the pressure within 3.7e-5 of its peak, falling as (a/h)^2).
"""
import numpy as np
import pytest

from viscontact.bodies.layer import Layer, unit_kernels
from viscontact.io.case import Case
from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import influence_coefficients
from viscontact.running.loop import simulate
from viscontact.solvers.steady import solve_steady

G, NU, R = 1.0e6, 0.3, 0.01
M = 2 * G * (1 - NU) / (1 - 2 * NU)


def _run(layer: dict | None, n: int, half_width: float, load: float, periodic: bool = True):
    data = {"title": "layer line", "material": {"type": "elastic", "shear_modulus": G, "poisson_ratio": NU},
            "indenter": {"shape": "cylinder", "radius": R},
            "grid": {"n": n, "half_width": half_width, "dimension": 1, "periodic": periodic},
            "normal": {"control": "load", "value": load}, "tangential": {"mode": "none"},
            "time": {"t_end": 1e-3, "dt": 1e-3}}
    if layer is not None:
        data["layer"] = layer
    problem = Case.from_dict(data).to_problem()
    return problem, list(simulate(problem))[-1]


def test_a_thick_layer_is_the_periodic_half_space():
    _, half_space = _run(None, 512, 2e-3, 20.0)
    thickness = 1.0
    _, thick = _run({"thickness": thickness}, 512, 2e-3, 20.0)
    assert 0 < thick.contact_fraction < 0.3 and thick.load == pytest.approx(20.0, rel=1e-10)
    np.testing.assert_allclose(thick.pressure, half_space.pressure, rtol=0, atol=1e-8 * half_space.pressure.max())
    p_mean = 20.0 / 4e-3
    assert thick.delta_z - half_space.delta_z == pytest.approx(thickness / M * p_mean, rel=1e-6)


@pytest.mark.parametrize("periodic", [True, False])
def test_a_thin_layer_tends_to_the_winkler_line_contact(periodic):
    errors = []
    for thickness in (2e-5, 5e-6):
        problem, rec = _run({"thickness": thickness}, 2048, 1e-3, 20.0, periodic)
        a = (1.5 * 20.0 * thickness * R / M) ** (1 / 3)
        delta = a * a / (2 * R)
        assert rec.load == pytest.approx(20.0, rel=1e-10)
        assert rec.contact_area / 2 == pytest.approx(a, abs=2 * problem.grid.spacing + 0.02 * a)
        peak = rec.pressure.max() / (M / thickness * delta) - 1
        approach = rec.delta_z / delta - 1
        assert abs(peak) < 3e-3 and abs(approach) < 2e-3
        errors.append((abs(peak), abs(approach)))
    # second order in h/a: (15/6)^2 = 6.3
    assert errors[0][0] / errors[1][0] > 5 and errors[0][1] / errors[1][1] > 4.5


@pytest.mark.parametrize("thickness", [2e-5, 1e-4])
def test_the_isolated_line_layer_is_the_periodic_one_far_from_its_images(thickness):
    _, isolated = _run({"thickness": thickness}, 512, 1e-3, 20.0, periodic=False)
    _, periodic = _run({"thickness": thickness}, 1024, 2e-3, 20.0, periodic=True)
    middle = periodic.pressure[0][256:768]
    np.testing.assert_allclose(isolated.pressure[0], middle, rtol=0, atol=1e-8 * middle.max())
    assert isolated.delta_z == pytest.approx(periodic.delta_z, rel=2e-6)


def test_an_elastic_base_of_the_layer_material_is_the_half_space():
    grid = Grid(64, 1e-3, dimension=1)
    for thickness in (2 * grid.spacing, 1e-3):
        layer = Layer(thickness, G, NU, base="elastic", base_shear_modulus=G, base_poisson_ratio=NU)
        kernels, half_space = unit_kernels(grid, layer), influence_coefficients(grid, NU)
        for c, k in kernels.items():
            np.testing.assert_allclose(k, half_space[c], rtol=0, atol=1e-14 * np.abs(half_space[c]).max())


def test_a_thick_isolated_layer_carries_hertz_line_contact():
    _, half_space = _run(None, 512, 1e-3, 20.0, periodic=False)
    _, thick = _run({"thickness": 0.1}, 512, 1e-3, 20.0, periodic=False)
    np.testing.assert_allclose(thick.pressure, half_space.pressure, rtol=0, atol=1e-4 * half_space.pressure.max())


def test_the_isolated_line_layer_slides_as_the_periodic_one():
    """Steady frictionless sliding of the cylinder on a Zener layer (h = 0.1 mm on a rigid base,
    v = 0.03 m/s): mu_app of the isolated line within 1e-4 of the periodic line's (measured 5e-6)."""
    def case(n: int, half_width: float, periodic: bool) -> Case:
        return Case.from_dict({
            "title": "sliding layer", "material": {"type": "zener", "shear_modulus_instantaneous": 1e6,
                                                   "shear_modulus_long_term": 1e5, "retardation_time": 0.01,
                                                   "poisson_ratio": NU},
            "indenter": {"shape": "cylinder", "radius": R}, "layer": {"thickness": 1e-4},
            "grid": {"n": n, "half_width": half_width, "dimension": 1, "periodic": periodic},
            "normal": {"control": "load", "value": 20.0},
            "tangential": {"mode": "frictionless_sliding", "sliding_speed": 0.03}, "time": {"t_end": 0.01}})
    isolated = solve_steady(case(512, 1e-3, False).to_problem())
    periodic = solve_steady(case(1024, 2e-3, True).to_problem())
    assert isolated.mu_app > 0.01
    assert isolated.mu_app == pytest.approx(periodic.mu_app, rel=1e-4)
    assert isolated.delta_z == pytest.approx(periodic.delta_z, rel=1e-5)
