"""A rigid sphere on a thin layer bonded to a rigid base, through the case's guards and the transient
solver, against the thin-layer (Winkler) limit (viscontact.physics.reference.winkler_sphere).

The issue's case: h = 20 um, G = 1.93 MPa, nu = 0.3 (elastic, and the seed's Zener solid), R = 10 mm,
W = 0.679 N. Oedometric M = 2G(1 - nu)/(1 - 2nu) = 6.76 MPa: a = (4 W R h/(pi M))^(1/4) = 0.400 mm,
p0 = M a^2/(2 R h) = 2.70 MPa, delta = a^2/2R = 8.0 um (h/a = 0.05). The half-space's Hertz estimate,
0.974 mm, made the guards refuse it on a grid of half-width 0.88 mm; the layer's own estimate
(viscontact.bodies.layer.LayerOnBase.contact_radius) is the Winkler radius. Measured at n = 64:
a (from the contact area) 0.65 % and p0 0.26 % under Winkler, the approach 0.06 % over; under the held
load the Zener layer creeps as Winkler with J(t) (Lee & Radok on a local foundation:
a(t)^4 = a(0)^4 J(t)/J(0)): measured at 5 retardation times a 0.21 % and delta 0.02 % over.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from vc_testing import sphere_problem

from viscontact.errors import ParameterError
from viscontact.physics.materials import Material
from viscontact.physics.reference import winkler_sphere
from viscontact.problem.problem import LayerSettings
from viscontact.running import guards
from viscontact.running.loop import simulate

H, G, NU, R, W, HALF_WIDTH = 20e-6, 1.93e6, 0.3, 0.01, 0.679, 0.88e-3
MATERIALS = {"elastic": Material.elastic(G, NU), "zener": Material.zener(G, G / 10, 0.01, NU)}


def _problem(material: Material, t_end: float = 0.0, n: int = 64, half_width: float = HALF_WIDTH):
    problem = sphere_problem(material, n, half_width, value=W, t_end=t_end, dt=1e-3, scheme="linear")
    return dataclasses.replace(problem, layer=LayerSettings(H))


def test_the_thin_layer_estimates_its_own_contact():
    """The guards take the layer's estimate (Winkler here, within 0.1 %), not the half-space's."""
    est = guards.contact_estimate(_problem(MATERIALS["elastic"]))
    assert est.smallest == pytest.approx(winkler_sphere(W, R, H, G, NU).radius, rel=1e-3)
    assert est.largest < 0.5 * 0.974e-3  # Hertz: 0.974 mm


def test_the_grid_advice_holds_the_layers_contact():
    """Too narrow a domain is refused with the layer's radius and a half-width of 1.5 times it (the
    half-space's Hertz estimate would ask for 1.5 mm)."""
    with pytest.raises(ParameterError, match=r"reaches about 0\.0004 m \(layer compliance.*half_width = 0\.00061 m"):
        guards.check_problem(_problem(MATERIALS["elastic"], half_width=0.3e-3))


@pytest.mark.parametrize("name", MATERIALS)
def test_thin_bonded_layer_is_winkler(name):
    problem = _problem(MATERIALS[name])
    guards.check_problem(problem)  # refused before the layer had its own estimate
    rec = list(simulate(problem))[-1]
    ref = winkler_sphere(W, R, H, G, NU)
    a = np.sqrt(np.count_nonzero(rec.pressure) * problem.grid.cell_area / np.pi)
    assert a == pytest.approx(ref.radius, rel=9e-3)  # measured -0.65 %
    assert rec.pressure.max() == pytest.approx(ref.peak_pressure, rel=3.5e-3)  # measured -0.26 %
    assert rec.delta_z == pytest.approx(ref.approach, rel=3e-3)  # measured +0.06 %


def test_thin_zener_layer_creeps_as_winkler():
    """Held load over 5 retardation times: a(t)^4 = a(0)^4 J(t)/J(0) (Winkler with J(t))."""
    material = MATERIALS["zener"]
    problem = _problem(material, t_end=0.05)
    guards.check_problem(problem)
    rec = list(simulate(problem))[-1]
    ref = winkler_sphere(W, R, H, G, NU)
    ratio = float(material.creep_compliance(rec.t) / material.creep_compliance(0.0))
    a = np.sqrt(np.count_nonzero(rec.pressure) * problem.grid.cell_area / np.pi)
    assert a == pytest.approx(ref.radius * ratio**0.25, rel=1e-2)  # measured +0.21 %
    assert rec.delta_z == pytest.approx(ref.approach * ratio**0.5, rel=3e-3)  # measured +0.02 %
