"""The adhesive-contact references of :mod:`viscontact.physics.adhesion` against their limits and
against ContactEngineering's Adhesion package (an independent implementation of Maugis 1992)."""
from __future__ import annotations

import numpy as np
import pytest

from viscontact.physics.adhesion import (
    cohesive_zone_length,
    dmt_pull_off,
    jkr_approach,
    jkr_load,
    jkr_pull_off,
    kendall_pull_off,
    maugis_dugdale,
    maugis_dugdale_pull_off,
    maugis_parameter,
)

R, E_STAR, W = 0.01, 5.515e6, 0.05  # a 10 mm sphere on a soft elastomer, w = 50 mJ/m^2


def sigma_for(lam: float) -> float:
    """The cohesive stress [Pa] that gives the Maugis parameter ``lam`` (lambda is linear in sigma_0)."""
    return lam / maugis_parameter(R, E_STAR, W, 1.0)


def test_jkr_pull_off_is_the_minimum_of_its_curves():
    """-3/2 pi w R is the least JKR load, -5/6 pi w R the load where the approach is least (to 1e-6,
    the resolution of the sampled curve)."""
    a = np.linspace(1e-7, 2e-3, 400001)
    load, approach = jkr_load(a, R, E_STAR, W), jkr_approach(a, R, E_STAR, W)
    assert load.min() == pytest.approx(jkr_pull_off(R, W, "load"), rel=1e-6)
    assert load[np.argmin(approach)] == pytest.approx(jkr_pull_off(R, W, "displacement"), rel=1e-4)


@pytest.mark.parametrize("lam, expected", [(1e3, -1.5), (1e-3, -2.0)])
def test_maugis_dugdale_pull_off_tends_to_jkr_and_dmt(lam, expected):
    """Load control: -1.5 pi w R as lambda -> infinity (JKR), -2 pi w R as lambda -> 0 (DMT), within
    the O(lambda^-1) and O(lambda) of the limits (Johnson & Greenwood 1997, Fig. 2)."""
    point = maugis_dugdale_pull_off(R, E_STAR, W, sigma_for(lam))
    assert float(point.load) / (np.pi * W * R) == pytest.approx(expected, rel=5e-3)
    assert jkr_pull_off(R, W) / (np.pi * W * R) == -1.5 and dmt_pull_off(R, W) / (np.pi * W * R) == -2.0


def test_maugis_dugdale_displacement_control_pull_off_tends_to_jkr():
    point = maugis_dugdale_pull_off(R, E_STAR, W, sigma_for(1e3), control="displacement")
    assert float(point.load) == pytest.approx(jkr_pull_off(R, W, "displacement"), rel=5e-3)


def test_maugis_dugdale_pull_off_falls_monotonically_from_dmt_to_jkr():
    """|P_c| / (pi w R) decreases from 2 to 1.5 as lambda grows (Maugis 1992, Fig. 7); at lambda = 1
    it is about 1.65."""
    pulls = [float(maugis_dugdale_pull_off(R, E_STAR, W, sigma_for(lam)).load) / (np.pi * W * R)
             for lam in (0.01, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0)]
    assert all(np.diff(pulls) > 0), pulls
    assert 1.60 < -pulls[3] < 1.70


@pytest.mark.parametrize("lam", [0.3, 1.0, 5.0])
def test_maugis_dugdale_curve_equals_the_adhesion_package(lam):
    """Load and approach at given contact radii equal ContactEngineering's Adhesion
    (``MaugisDugdale.load_and_displacement``, root-finding in m for each a) to 1e-8."""
    md = pytest.importorskip("Adhesion.ReferenceSolutions.MaugisDugdale")
    sigma = sigma_for(lam)
    curve = maugis_dugdale(np.geomspace(1.0 + 1e-6, 50.0, 40), R, E_STAR, W, sigma)
    load, approach, *_ = md.load_and_displacement(curve.contact_radius, R, E_STAR, W, sigma)
    np.testing.assert_allclose(curve.load, load, rtol=1e-8, atol=1e-12 * np.pi * W * R)
    np.testing.assert_allclose(curve.approach, approach, rtol=1e-8, atol=1e-14)


def test_maugis_dugdale_tends_to_the_jkr_curve_and_its_cohesive_zone():
    """lambda = 1e4: the curve is JKR's (load and approach at the same a, to 1e-3 of pi w R and of the
    JKR approach scale) and the ring c - a is the Dugdale zone pi E* w / (4 sigma_0^2) (to 2 %)."""
    sigma = sigma_for(1e4)
    curve = maugis_dugdale(1.0 + np.geomspace(1e-9, 1e-6, 20), R, E_STAR, W, sigma)
    scale = (np.pi**2 * W**2 * R / (4 * E_STAR / 3) ** 2) ** (1 / 3)
    np.testing.assert_allclose(curve.load, jkr_load(curve.contact_radius, R, E_STAR, W), atol=1e-3 * np.pi * W * R)
    np.testing.assert_allclose(curve.approach, jkr_approach(curve.contact_radius, R, E_STAR, W), atol=1e-3 * scale)
    ring = curve.cohesive_radius - curve.contact_radius
    np.testing.assert_allclose(ring, cohesive_zone_length(E_STAR, W, sigma), rtol=2e-2)


def test_kendall_flat_punch():
    """-sqrt(8 pi w E* a^3): the JKR energy balance of a flat punch (dU/da = 2 pi a w with the
    punch's stiffness 2 a E*, Sneddon)."""
    a = 1e-3
    stiffness = 2 * a * E_STAR
    # energy release rate of a punch under the load P: G = P^2 / (2 stiffness^2) d(stiffness)/dA
    load = kendall_pull_off(a, E_STAR, W)
    release = load**2 / (2 * stiffness**2) * (2 * E_STAR) / (2 * np.pi * a)
    assert release == pytest.approx(W, rel=1e-12)
