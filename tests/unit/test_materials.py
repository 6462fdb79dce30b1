"""Prony materials and their exact creep spectra (viscontact.physics.materials).

The creep compliance is not fitted: it follows from J^(s) G^(s) = 1/s^2 (seed Eq. 3), i.e. the
Volterra identity  int_0^t G(t - s) dJ(s) = 1  for every t. We check it by adaptive quadrature of
the smooth part (J jumps by J_0 at s = 0, then J' is a sum of exponentials):

    G(t) J_0 + int_0^t G(t - s) J'(s) ds = 1.

Tolerance 1e-8 (absolute on a quantity of order 1): ``quad`` on these smooth integrands is
accurate to ~1e-13, and the spectrum comes from polynomial roots accurate to ~1e-14 relative, so
a wrong amplitude or retardation time (or a swapped relaxation/retardation time) fails by far more.
The complex-modulus test G*(w) J*(w) = 1 is the same identity in the frequency domain and checks
the storage and loss moduli against the creep spectrum.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest
from scipy.integrate import quad

from viscontact.errors import ParameterError
from viscontact.physics.materials import Material

from vc_testing import SEED_G0, SEED_GINF, SEED_NU, SEED_TAU

G0, GINF, LAM, NU = SEED_G0, SEED_GINF, SEED_TAU, SEED_NU  # seed material (G = mu/2, retardation time 0.01 s)

MATERIALS = {
    "zener": Material.zener(G0, GINF, LAM, NU),
    "zener_ratio3": Material.zener(3.0e6, 1.0e6, 2e-3, 0.5),
    "prony3": Material.prony(1.0e5, [1.0e6, 5.0e5, 2.0e5], [1e-3, 1e-2, 1e-1], 0.25),
    "prony3_close": Material.prony(2.0e5, [3.0e5, 3.0e5, 3.0e5], [1e-3, 2e-3, 4e-3], 0.0),
}


def creep_rate(material: Material, s: float) -> float:
    """J'(s) [1/(Pa s)] from the spectrum."""
    c = material.creep
    return float(np.sum(c.amplitudes / c.retardation_times * np.exp(-s / c.retardation_times)))


def volterra(material: Material, t: float) -> float:
    """int_0^t G(t - s) dJ(s), with the jump J_0 at s = 0 taken exactly."""
    jump = float(material.relaxation_modulus(t)) * material.creep.instantaneous
    if t == 0:
        return jump
    scales = np.concatenate([material.creep.retardation_times, np.asarray(material.tau)])
    points = [t - x for x in scales if 0 < x < t] + [x for x in scales if 0 < x < t]
    smooth, _ = quad(lambda s: float(material.relaxation_modulus(t - s)) * creep_rate(material, s), 0.0, t,
                     points=sorted(set(points)) or None, epsabs=1e-14, epsrel=1e-13, limit=400)
    return jump + smooth


@pytest.mark.parametrize("name", sorted(MATERIALS))
def test_volterra_identity(name):
    m = MATERIALS[name]
    lam_max = m.creep.retardation_times.max()
    for t in np.concatenate([[0.0], np.geomspace(1e-3 * m.shortest_time, 30 * lam_max, 25)]):
        assert volterra(m, t) == pytest.approx(1.0, abs=1e-8), t


@pytest.mark.parametrize("name", sorted(MATERIALS))
def test_compliance_limits(name):
    m = MATERIALS[name]
    c = m.creep
    assert float(m.creep_compliance(0.0)) == pytest.approx(1.0 / m.shear_modulus_instantaneous, rel=1e-14)
    assert c.long_term == pytest.approx(1.0 / m.shear_modulus_long_term, rel=1e-10)
    assert float(m.creep_compliance(60 * c.retardation_times.max())) == pytest.approx(c.long_term, rel=1e-12)
    assert np.all(c.amplitudes > 0) and np.all(c.retardation_times > 0)
    # J(t) is increasing and G(t) decreasing
    # (over a few of the longest times, before both saturate in floating point)
    t = np.linspace(0, 3 * c.retardation_times.max(), 200)
    assert np.all(np.diff(m.creep_compliance(t)) > 0)
    t = np.linspace(0, 3 * max(m.tau), 200)
    assert np.all(np.diff(m.relaxation_modulus(t)) < 0)


def test_zener_retardation_time_is_the_given_one():
    m = MATERIALS["zener"]
    c = m.creep
    assert c.retardation_times.shape == (1,)
    assert c.retardation_times[0] == pytest.approx(LAM, rel=1e-12)
    # relaxation time = retardation time * G(inf)/G(0) (seed Eqs. 13-14), G(0), G(inf) recovered
    assert m.tau[0] == pytest.approx(LAM * GINF / G0, rel=1e-14)
    assert m.shear_modulus_instantaneous == pytest.approx(G0, rel=1e-14)
    assert m.shear_modulus_long_term == pytest.approx(GINF, rel=1e-14)
    # closed form of the standard linear solid: J(t) = 1/G0 + (1/Ginf - 1/G0)(1 - exp(-t/lam))
    t = np.linspace(0, 0.05, 11)
    expected = 1 / G0 + (1 / GINF - 1 / G0) * (1 - np.exp(-t / LAM))
    np.testing.assert_allclose(m.creep_compliance(t), expected, rtol=1e-12)


def test_three_term_prony_spectrum_interlaces():
    """For a Prony series with positive moduli the retardation times are real, one per relaxation
    time, and interlace with them: tau_1 < lam_1 < tau_2 < lam_2 < tau_3 < lam_3."""
    for name in ("prony3", "prony3_close"):
        m = MATERIALS[name]
        lam = m.creep.retardation_times
        tau = np.sort(m.tau)
        assert lam.shape == (3,)
        merged = np.empty(6)
        merged[0::2], merged[1::2] = tau, lam
        assert np.all(np.diff(merged) > 0), (tau, lam)


@pytest.mark.parametrize("name", sorted(MATERIALS))
def test_complex_modulus_times_complex_compliance_is_one(name):
    """G*(w) = G' + i G'' and J*(w) = J_0 + sum_m J_m / (1 + i w lam_m) satisfy G* J* = 1."""
    m = MATERIALS[name]
    c = m.creep
    w = np.geomspace(1e-3 / c.retardation_times.max(), 1e3 / m.shortest_time, 60)
    g_star = m.storage_modulus(w) + 1j * m.loss_modulus(w)
    j_star = c.instantaneous + np.sum(c.amplitudes[:, None] / (1 + 1j * w[None] * c.retardation_times[:, None]),
                                      axis=0)
    np.testing.assert_allclose(g_star * j_star, 1.0, rtol=1e-11, atol=1e-11)


@pytest.mark.parametrize("name", sorted(MATERIALS))
def test_storage_and_loss_moduli_limits(name):
    m = MATERIALS[name]
    lo, hi = 1e-6 / max(m.tau), 1e6 / min(m.tau)
    assert float(m.storage_modulus(0.0)) == pytest.approx(m.shear_modulus_long_term, rel=1e-14)
    assert float(m.storage_modulus(lo)) == pytest.approx(m.shear_modulus_long_term, rel=1e-9)
    assert float(m.storage_modulus(hi)) == pytest.approx(m.shear_modulus_instantaneous, rel=1e-9)
    assert float(m.loss_modulus(0.0)) == 0.0
    assert float(m.loss_modulus(lo)) < 1e-5 * m.shear_modulus_instantaneous
    assert float(m.loss_modulus(hi)) < 1e-5 * m.shear_modulus_instantaneous
    w = np.geomspace(lo, hi, 400)
    assert np.all(np.diff(m.storage_modulus(w)) > 0)
    assert np.all(m.loss_modulus(w) > 0)


WIDE = {  # measured-spectrum shapes: 20 and 40 terms over 11 and 15 decades, equal and falling moduli
    "20_terms": Material.prony(1e5, np.full(20, 1e5), np.geomspace(1e-8, 1e3, 20), 0.3),
    "40_terms": Material.prony(2e4, 1e7 * np.geomspace(1, 1e-4, 40), np.geomspace(1e-10, 1e5, 40), 0.5),
}


@pytest.mark.parametrize("name", sorted(WIDE))
def test_wide_spectrum_is_exact(name):
    """Many terms over many decades: G* J* = 1 at every frequency to round-off, J_inf = 1/G(inf),
    the retardation times interlace with the relaxation times (the expanded characteristic
    polynomial loses these to cancellation; the secular-equation roots keep them)."""
    m = WIDE[name]
    c = m.creep
    assert c.retardation_times.size == len(m.tau) and np.all(c.amplitudes > 0)
    merged = np.empty(2 * len(m.tau))
    merged[0::2], merged[1::2] = np.sort(m.tau), c.retardation_times
    assert np.all(np.diff(merged) > 0)
    assert c.long_term == pytest.approx(1.0 / m.g_inf, rel=1e-12)
    w = np.geomspace(1e-3 / c.retardation_times.max(), 1e3 / m.shortest_time, 400)
    g_star = m.storage_modulus(w) + 1j * m.loss_modulus(w)
    j_star = c.instantaneous + np.sum(c.amplitudes[:, None] / (1 + 1j * w[None] * c.retardation_times[:, None]),
                                      axis=0)
    np.testing.assert_allclose(g_star * j_star, 1.0, rtol=1e-11, atol=1e-11)


def test_equal_relaxation_times_merge():
    split = Material.prony(1e5, [1e5, 2e5, 3e5], [1e-3, 1e-2, 1e-3], 0.3)
    merged = Material.prony(1e5, [4e5, 2e5], [1e-3, 1e-2], 0.3)
    np.testing.assert_allclose(split.creep.amplitudes, merged.creep.amplitudes, rtol=1e-14)
    np.testing.assert_allclose(split.creep.retardation_times, merged.creep.retardation_times, rtol=1e-14)


def test_zener_loss_peak():
    """Standard linear solid: G'' peaks at w = 1/tau_relax with height (G0 - Ginf)/2."""
    m = MATERIALS["zener"]
    tau = m.tau[0]
    assert float(m.loss_modulus(1 / tau)) == pytest.approx((G0 - GINF) / 2, rel=1e-14)
    w = np.geomspace(0.1 / tau, 10 / tau, 2001)
    assert w[np.argmax(m.loss_modulus(w))] == pytest.approx(1 / tau, rel=5e-3)


def test_elastic_material():
    m = Material.elastic(2.0e6, 0.4)
    assert m.is_elastic
    np.testing.assert_allclose(m.creep_compliance([0.0, 1.0, 1e6]), 5e-7, rtol=1e-15)
    assert m.creep.amplitudes.size == 0
    assert float(m.loss_modulus(10.0)) == 0.0
    assert m.reduced_modulus() == pytest.approx(2 * 2.0e6 / 0.6, rel=1e-15)
    # a Zener with G(0) = G(inf) is elastic
    assert Material.zener(1e6, 1e6, 0.01, 0.3).is_elastic


@pytest.mark.parametrize("build, key", [
    (lambda: Material.zener(0.0, 1e5, 0.01, 0.3), "material.shear_modulus_instantaneous"),
    (lambda: Material.zener(-1e6, 1e5, 0.01, 0.3), "material.shear_modulus_instantaneous"),
    (lambda: Material.zener(float("nan"), 1e5, 0.01, 0.3), "material.shear_modulus_instantaneous"),
    (lambda: Material.zener(1e6, 0.0, 0.01, 0.3), "material.shear_modulus_long_term"),
    (lambda: Material.zener(1e6, 2e6, 0.01, 0.3), "material.shear_modulus_long_term"),
    (lambda: Material.zener(1e6, 1e5, 0.0, 0.3), "material.retardation_time"),
    (lambda: Material.zener(1e6, 1e5, float("inf"), 0.3), "material.retardation_time"),
    (lambda: Material.zener(1e6, 1e5, 0.01, -0.1), "material.poisson_ratio"),
    (lambda: Material.zener(1e6, 1e5, 0.01, 0.51), "material.poisson_ratio"),
    (lambda: Material.zener(1e6, 1e5, 0.01, float("nan")), "material.poisson_ratio"),
    (lambda: Material.elastic(0.0, 0.3), "material.shear_modulus"),
    (lambda: Material.elastic(1e6, 0.7), "material.poisson_ratio"),
    (lambda: Material.prony(0.0, [1e6], [1e-3], 0.3), "material.g_inf"),
    (lambda: Material.prony(1e5, [-1e6], [1e-3], 0.3), "material.g"),
    (lambda: Material.prony(1e5, [1e6, 1e5], [1e-3], 0.3), "material.g"),
    (lambda: Material.prony(1e5, [1e6], [0.0], 0.3), "material.tau"),
    (lambda: Material.prony(1e5, [1e6], [-1e-3], 0.3), "material.tau"),
    (lambda: Material.prony(1e5, [1e6], [1e-3], -0.01), "material.poisson_ratio"),
])
def test_invalid_parameters_name_their_key(build, key):
    with pytest.raises(ParameterError) as info:
        build()
    assert info.value.key == key
    assert key in str(info.value)
    assert isinstance(info.value, ValueError)


@pytest.mark.parametrize("nu", [0.0, 0.5])
def test_poisson_ratio_bounds_are_allowed(nu):
    assert Material.zener(1e6, 1e5, 0.01, nu).poisson_ratio == nu


def test_relaxation_times_one_ulp_apart_convert_without_numpy_warnings():
    """The secular equation's bracket ends within round-off of its poles overflow to inf of the right
    sign: numpy's RuntimeWarning leaked to `viscontact material`. J(0) = 1/G(0), J(inf) = 1/G(inf)."""
    tau = 1e-3
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        creep = Material.prony(0.193e6, [1.0e6, 0.737e6], [tau, np.nextafter(tau, 1.0)], 0.3).creep
    assert creep.instantaneous == pytest.approx(1 / 1.93e6, rel=1e-12)
    assert creep.long_term == pytest.approx(1 / 0.193e6, rel=1e-12)
