"""A layer on a base in a periodic line contact (``[layer]``, ``grid.dimension = 1``, ``grid.periodic``).

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
"""
import numpy as np
import pytest

from viscontact.io.case import Case
from viscontact.running.loop import simulate

G, NU, R = 1.0e6, 0.3, 0.01
M = 2 * G * (1 - NU) / (1 - 2 * NU)


def _run(layer: dict | None, n: int, half_width: float, load: float):
    data = {"title": "layer line", "material": {"type": "elastic", "shear_modulus": G, "poisson_ratio": NU},
            "indenter": {"shape": "cylinder", "radius": R},
            "grid": {"n": n, "half_width": half_width, "dimension": 1, "periodic": True},
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


def test_a_thin_layer_tends_to_the_winkler_line_contact():
    errors = []
    for thickness in (2e-5, 5e-6):
        problem, rec = _run({"thickness": thickness}, 2048, 1e-3, 20.0)
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
