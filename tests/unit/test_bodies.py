"""The Body protocol (viscontact.bodies.base): one factory maps the case's description to a body, a
problem asks its body, solver.fft reaches every body's transforms, and the fingerprint's body part is
the bytes hashed before bodies existed."""
from __future__ import annotations

import dataclasses

import pytest
from vc_testing import seed_material, sphere_problem

from viscontact.bodies import registry
from viscontact.bodies.base import Body
from viscontact.bodies.bulk_elastic import BulkElasticHalfSpace
from viscontact.bodies.half_space import HomogeneousHalfSpace
from viscontact.bodies.layer import LayerOnBase
from viscontact.errors import ParameterError
from viscontact.numerics import fftbackends
from viscontact.numerics.fftbackends import ZeroBlockTransforms
from viscontact.problem.problem import LayerSettings

DESCRIPTIONS = {"half_space": ({}, HomogeneousHalfSpace),
                "bulk_modulus": ({"bulk_modulus": 5e6}, BulkElasticHalfSpace),
                "layer": ({"layer": LayerSettings(0.3e-3)}, LayerOnBase)}


def _problem(description):
    material = seed_material(poisson_ratio=0.25) if "bulk_modulus" in description else seed_material()
    return dataclasses.replace(sphere_problem(material, 16, 1.5e-3, t_end=1e-3, dt=5e-4), **description)


@pytest.mark.parametrize("name", DESCRIPTIONS)
def test_the_problem_builds_its_body_from_the_case_keys(name):
    description, kind = DESCRIPTIONS[name]
    problem = _problem(description)
    assert type(problem.body) is kind and isinstance(problem.body, Body)
    assert problem.body.material is problem.material and dict(problem.body.description) == description
    # given instead of the keys, the body sets them
    given = dataclasses.replace(problem, bulk_modulus=None, layer=None)
    again = type(problem)(**{f.name: getattr(given, f.name) for f in dataclasses.fields(given)})
    assert (again.bulk_modulus, again.layer) == (problem.bulk_modulus, problem.layer)


def test_a_copy_with_new_keys_or_material_gets_a_new_body():
    problem = _problem({})
    layered = dataclasses.replace(problem, layer=LayerSettings(1e-3))
    assert type(layered.body) is LayerOnBase and layered.body.settings == LayerSettings(1e-3)
    other = seed_material(ratio=3.0)
    assert dataclasses.replace(layered, material=other).body.material is other


def test_one_body_per_case():
    with pytest.raises(ParameterError, match="material.bulk_modulus: not supported with \\[layer\\]"):
        registry.body_of(seed_material(), bulk_modulus=5e6, layer=LayerSettings(1e-3))


def test_the_fingerprint_part_is_what_was_hashed_before_bodies():
    assert HomogeneousHalfSpace(seed_material()).fingerprint() == b""
    for description in ({"bulk_modulus": 5e6}, {"layer": LayerSettings(0.3e-3)}):
        before = {"bulk_modulus": description.get("bulk_modulus"), "layer": description.get("layer")}
        assert _problem(description).body.fingerprint() == repr(before).encode()


@pytest.mark.parametrize("name", DESCRIPTIONS)
def test_solver_fft_reaches_every_bodys_transforms(name, monkeypatch):
    """solver.fft = "pyfftw" builds the DC-FFT transforms by that name for every body (it once
    reached the half-space only): here a stand-in for pyFFTW's, so that no pyFFTW is needed."""
    class StandIn(ZeroBlockTransforms):
        pass

    monkeypatch.setitem(fftbackends.BACKENDS, "pyfftw", lambda n, workers: StandIn(n, workers))
    problem = _problem(DESCRIPTIONS[name][0])
    for fft, kind in (("scipy", ZeroBlockTransforms), ("pyfftw", StandIn)):
        compliance = problem.body.compliance(problem.grid, ("zz",), "linear", 5e-4, workers=1, fft=fft)
        assert type(compliance.convolver.transforms) is kind


def test_the_layers_contact_estimate_has_the_limits_of_its_docstring():
    """Thick: Hertz of the layer; thin on a rigid base: Winkler; thin on a much softer base: Hertz of the
    base; creep (the compliance factor) acts on the layer only."""
    import math

    from viscontact.bodies.half_space import hertz_radius
    from viscontact.physics.reference import winkler_sphere
    from viscontact.problem.shapes import Sphere

    g, nu, load, radius = 1.93e6, 0.3, 0.679, 0.01
    sphere = Sphere(radius)
    material = seed_material()
    thick = LayerOnBase(material, LayerSettings(1.0)).contact_radius(load, sphere)
    assert thick == pytest.approx(hertz_radius(load, radius, g, nu), rel=1e-9)
    thin = LayerOnBase(material, LayerSettings(2e-5)).contact_radius(load, sphere)
    assert thin == pytest.approx(winkler_sphere(load, radius, 2e-5, g, nu).radius, rel=1e-3)
    soft = LayerSettings(2e-6, "elastic", "bonded", g / 100, 0.4)
    on_soft = LayerOnBase(material, soft).contact_radius(load, sphere)
    assert on_soft == pytest.approx(hertz_radius(load, radius, g / 100, 0.4), rel=2e-2)
    assert LayerOnBase(material, soft).contact_radius(load, sphere, 10.0) == pytest.approx(on_soft, rel=2e-2)
    crept = LayerOnBase(material, LayerSettings(2e-5)).contact_radius(load, sphere, 10.0)
    assert crept == pytest.approx(thin * 10.0**0.25, rel=2e-3)  # Winkler: a^4 ~ W/M
    assert math.isinf(LayerOnBase(material, LayerSettings(2e-5)).contact_radius(load, sphere, math.inf))
