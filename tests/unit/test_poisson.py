"""Time-dependent Poisson ratio (viscontact.bodies.bulk_elastic): computed creep spectra of the influence factors.

Independent truths used:

* the polynomial-root creep spectrum of :class:`viscontact.physics.materials.Material` (another algorithm)
  for small spectra, where it is accurate;
* the Volterra identity int_0^t (G(t - s) + c) dC(s) = 1 (time domain, adaptive quadrature) for a
  24-term spectrum over 10 decades, where the polynomial route fails;
* the Carson-domain definition of each factor with nu~(s) = (3K - 2G~)/(2(3K + G~)), evaluated
  directly at s over 14 decades (checks the partial fractions and the residues);
* the elastic factors with (G(0), nu(0)) at t = 0 and (G(inf), nu(inf)) as t -> inf;
* the constant-nu influence coefficients of viscontact.physics.kernels (elastic shear, K finite).
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from viscontact.numerics.exponentials import carson_transform
from viscontact.errors import ParameterError
from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import influence_coefficients
from viscontact.physics.materials import Material
from viscontact.bodies.bulk_elastic import FACTORS, BulkElasticMaterial, half_space_terms, prony_creep_spectrum

PRONY3 = Material.prony(1.0e5, [1.0e6, 5.0e5, 2.0e5], [1e-3, 1e-2, 1e-1], 0.25)
SEED = Material.zener(1.93e6, 0.193e6, 0.01, 0.3)
WIDE_TAU = np.logspace(-6, 4, 24)
WIDE_G = 1e5 * (1.0 + np.sin(np.arange(24)) ** 2)
WIDE = Material.prony(1e3, list(WIDE_G), list(WIDE_TAU), 0.3)


def carson_modulus(material: Material, s: np.ndarray) -> np.ndarray:
    """G~(s) = g_inf + sum g_i s / (s + 1/tau_i) [Pa]."""
    out = np.full(np.shape(s), material.g_inf, dtype=float)
    for gi, ti in zip(material.g, material.tau):
        out = out + gi * s / (s + 1.0 / ti)
    return out


@pytest.mark.parametrize("material", [PRONY3, SEED], ids=["prony3", "seed"])
@pytest.mark.parametrize("shift", [0.0, 3e6, 3e9])
def test_secular_spectrum_matches_polynomial_roots(material, shift):
    ours = prony_creep_spectrum(material.g_inf, material.g, material.tau, shift)
    ref = Material.prony(material.g_inf + shift, list(material.g), list(material.tau), 0.3).creep
    assert ours.instantaneous == pytest.approx(ref.instantaneous, rel=1e-14)
    np.testing.assert_allclose(ours.retardation_times, ref.retardation_times, rtol=1e-10)
    np.testing.assert_allclose(ours.amplitudes, ref.amplitudes, rtol=1e-9)


@pytest.mark.parametrize("shift", [0.0, 3e6])
def test_wide_spectrum_volterra_identity(shift):
    """int_0^t (G(t-s) + c) dC(s) = 1 at t over 10 decades: tolerance 1e-9 (quadrature ~1e-12)."""
    spec = prony_creep_spectrum(WIDE.g_inf, WIDE.g, WIDE.tau, shift)
    lam, amps = spec.retardation_times, spec.amplitudes
    assert np.all(lam > 0) and np.all(amps > 0) and lam.size == 24
    assert spec.long_term == pytest.approx(1.0 / (WIDE.g_inf + shift), rel=1e-12)

    def modulus(t):
        return float(WIDE.relaxation_modulus(t)) + shift

    def rate(s):
        return float(np.sum(amps / lam * np.exp(-s / lam)))

    for t in np.logspace(-7, 5, 13):
        edges = np.concatenate([[0.0], np.geomspace(1e-9, t, 40)])
        integral = sum(quad(lambda s: modulus(t - s) * rate(s), a, b, epsabs=0.0, epsrel=1e-12, limit=200)[0]
                       for a, b in zip(edges[:-1], edges[1:]) if b > a)
        assert spec.instantaneous * modulus(t) + integral == pytest.approx(1.0, abs=1e-9), t


@pytest.mark.parametrize("material", [SEED, PRONY3, WIDE], ids=["seed", "prony3", "wide"])
@pytest.mark.parametrize("bulk", [3e6, 1e8])
def test_factor_carson_transforms(material, bulk):
    """Each factor's spectrum has the Carson transform of its elastic factor at G~(s), nu~(s)."""
    bm = BulkElasticMaterial(material, bulk)
    s = np.logspace(-8, 8, 65)
    g = carson_modulus(material, s)
    nu = (3 * bulk - 2 * g) / (2 * (3 * bulk + g))
    exact = {"normal": (1 - nu) / g, "tangential": 1 / g, "tangential_poisson": nu / g, "coupling": (1 - 2 * nu) / g}
    for name in FACTORS:
        np.testing.assert_allclose(carson_transform(bm.factor(name), s), exact[name], rtol=1e-10, atol=0, err_msg=name)


@pytest.mark.parametrize("material", [SEED, WIDE], ids=["seed", "wide"])
def test_limits_are_the_elastic_factors(material):
    """t = 0: G(0), nu(0); t -> inf: G(inf), nu(inf)."""
    bm = BulkElasticMaterial(material, 5e6)
    g0, ginf = material.shear_modulus_instantaneous, material.shear_modulus_long_term
    for name in FACTORS:
        f = bm.factor(name)
        assert float(f.compliance(0.0)) == pytest.approx(bm.elastic_factor(name, g0), rel=1e-12)
        assert float(f.compliance(1e12)) == pytest.approx(bm.elastic_factor(name, ginf), rel=1e-10)
    assert bm.poisson_ratio_instantaneous == pytest.approx((15e6 - 2 * g0) / (2 * (15e6 + g0)))
    assert bm.poisson_ratio_long_term > bm.poisson_ratio_instantaneous  # nu rises as G relaxes


def test_seed_numbers():
    """The seed material with K = 10 G(0): nu(0) = 28/62 = 0.4516, nu(inf) = 29.8/60.2 = 0.4950."""
    bm = BulkElasticMaterial(SEED, 10 * 1.93e6)
    assert bm.poisson_ratio_instantaneous == pytest.approx(28 / 62, rel=1e-12)
    assert bm.poisson_ratio_long_term == pytest.approx((30 - 0.2) / (2 * 30.1), rel=1e-12)


def test_incompressible_limit():
    """K = inf: nu = 0.5, coupling 0, normal (1-nu)/G = J/2 = nu/G; large K tends to it."""
    j = SEED.creep
    t = np.logspace(-5, 1, 13)
    inc = BulkElasticMaterial(SEED, np.inf)
    assert inc.poisson_ratio_instantaneous == inc.poisson_ratio_long_term == 0.5
    assert inc.factor("coupling").compliance(t) == pytest.approx(np.zeros_like(t), abs=0)
    for name in ("normal", "tangential_poisson"):
        np.testing.assert_allclose(inc.factor(name).compliance(t), 0.5 * SEED.creep_compliance(t), rtol=1e-13)
    big = BulkElasticMaterial(SEED, 1e6 * 1.93e6)
    np.testing.assert_allclose(big.factor("normal").compliance(t), 0.5 * SEED.creep_compliance(t), rtol=1e-6)
    assert np.max(big.factor("coupling").compliance(t)) < 1e-6 * j.long_term


def test_constant_nu_kernels_reproduced():
    """Elastic shear, finite K: the terms sum to IC(nu)/G of viscontact.physics.kernels (and, with a Prony
    shear modulus, at every time to IC(nu(t)) of the factors: checked through the Carson test)."""
    g, k = 2.0e6, 5.0e6
    bm = BulkElasticMaterial(Material.elastic(g, 0.3), k)
    nu = bm.poisson_ratio_instantaneous
    grid = Grid(8, 1e-3)
    ref = influence_coefficients(grid, nu)
    total = {c: np.zeros_like(ref[c]) for c in ref}
    terms = half_space_terms(grid, bm)
    assert sorted(t.name for t in terms) == ["xx:bulk", "xx:shear", "xz:bulk", "zx:bulk", "zz:bulk", "zz:shear"]
    for term in terms:
        assert term.response.amplitudes.size == 0
        total[term.displacement + term.traction] += term.kernel * term.response.instantaneous
    for c in ref:
        np.testing.assert_allclose(total[c], ref[c] / g, rtol=1e-12, atol=1e-12 * np.abs(ref[c]).max() / g)


def test_incompressible_terms_drop_coupling():
    terms = half_space_terms(Grid(4, 1e-3), BulkElasticMaterial(SEED, np.inf))
    assert sorted(t.name for t in terms) == ["xx:shear", "zz:shear"]


@pytest.mark.parametrize("bulk", [0.0, -1.0, 1.0e6, float("nan")])
def test_bulk_modulus_too_small(bulk):
    with pytest.raises(ParameterError, match="material.bulk_modulus"):
        BulkElasticMaterial(SEED, bulk)


def test_terms_regroup_the_factors():
    """At any t the terms sum to S (1-nu)/G(t), S_xx/G + D_xx nu/G and S (1-2nu)/G as operators."""
    bm = BulkElasticMaterial(SEED, 5e6)
    grid = Grid(6, 1e-3)
    s0 = influence_coefficients(grid, 0.0)
    d_xx = influence_coefficients(grid, 1.0)["xx"] - s0["xx"]
    terms = half_space_terms(grid, bm)
    for t in (0.0, 3e-3, 0.05, 10.0):
        value = {c: 0.0 for c in ("zz", "xx", "xz", "zx")}
        for term in terms:
            value[term.displacement + term.traction] = (value[term.displacement + term.traction]
                                                        + term.kernel * float(term.response.compliance(t)))
        f = {name: float(bm.factor(name).compliance(t)) for name in FACTORS}
        expected = {"zz": s0["zz"] * f["normal"], "xx": s0["xx"] * f["tangential"] + d_xx * f["tangential_poisson"],
                    "xz": s0["xz"] * f["coupling"], "zx": s0["zx"] * f["coupling"]}
        for c in expected:
            np.testing.assert_allclose(value[c], expected[c], rtol=1e-12, atol=1e-14 * np.abs(expected[c]).max())


def test_kernels_at_zero_and_infinity():
    """Issue 12: at t = 0 the terms are the half-space of (G(0), nu(0)), as t -> inf of (G(inf), nu(inf))."""
    bm = BulkElasticMaterial(SEED, 5e6)
    grid = Grid(6, 1e-3)
    terms = half_space_terms(grid, bm)
    for t, g, nu in ((0.0, SEED.shear_modulus_instantaneous, bm.poisson_ratio_instantaneous),
                     (1e6, SEED.shear_modulus_long_term, bm.poisson_ratio_long_term)):
        ref = influence_coefficients(grid, nu)
        total = {c: np.zeros_like(ref[c]) for c in ref}
        for term in terms:
            total[term.displacement + term.traction] += term.kernel * float(term.response.compliance(t))
        for c in ref:
            np.testing.assert_allclose(total[c], ref[c] / g, rtol=1e-10, atol=1e-12 * np.abs(ref[c]).max() / g)


def test_lee_radok_with_bulk_modulus():
    """Lee-Radok creep radius: a(t)^3 proportional to the normal creep function; t = 0 and inf give
    Hertz with (G(0), nu(0)) and (G(inf), nu(inf)); an elastic shear modulus gives Hertz with its nu."""
    from viscontact.physics.reference import hertz_from_load, lee_radok_creep

    bm = BulkElasticMaterial(SEED, 5e6)
    creep = lee_radok_creep(0.15, 0.01, bm, np.array([0.0, 1e6]))
    for a, g, nu in zip(creep.radius, (SEED.shear_modulus_instantaneous, SEED.shear_modulus_long_term),
                        (bm.poisson_ratio_instantaneous, bm.poisson_ratio_long_term)):
        assert a == pytest.approx(hertz_from_load(0.15, 0.01, g, nu).radius, rel=1e-10)
    elastic = BulkElasticMaterial(Material.elastic(2e6, 0.3), 5e6)
    nu = elastic.poisson_ratio_instantaneous
    assert float(lee_radok_creep(0.15, 0.01, elastic, 3.0).radius) == pytest.approx(
        float(lee_radok_creep(0.15, 0.01, Material.elastic(2e6, nu), 3.0).radius), rel=1e-12)


def test_term_substrate_of_an_elastic_shear_modulus_is_the_half_space():
    """The core seam: the nu(t) terms with an elastic shear modulus give the HalfSpace compliance's
    operators with nu = nu(0) (normal and tangential self operators, coupling)."""
    from viscontact.bodies.compliance import term_substrate
    from viscontact.bodies.half_space import HalfSpace

    g, k = 2.0e6, 5.0e6
    bm = BulkElasticMaterial(Material.elastic(g, 0.3), k)
    grid = Grid(8, 1e-3)
    ours = term_substrate(grid, half_space_terms(grid, bm), "linear", 1e-3)
    ref = HalfSpace(grid, Material.elastic(g, bm.poisson_ratio_instantaneous), ("zz", "xx", "xz", "zx"), "linear", 1e-3)
    field = np.random.default_rng(1).random((8, 8))
    for comp in ("z", "x"):
        np.testing.assert_allclose(ours.elastic_operator(comp, True).apply(field),
                                   ref.elastic_operator(comp, True).apply(field), rtol=1e-10)
    np.testing.assert_allclose(ours.cross_displacement("z", "x", field, True), ref.cross_displacement("z", "x", field, True),
                               rtol=1e-10)
