"""The shipped real-material cases ``pmma_master_curve`` (a glassy polymer) and
``pu_elastomer_master_curve`` (an elastomer): their term files against the cited tables, and their
steady speed curves against the Hertz limits.

References (independent of viscontact):
* PMMA, typed below from ``tests/g2.dat`` of S. Shanbhag's PSI (https://github.com/shane5ul/psi,
  commit 67c702e): Schapery's (1962) PMMA tensile relaxation data as fitted by Park & Schapery
  (Int. J. Solids Struct. 36, 1653, 1999), reproduced in Shanbhag, J. Rheol. 67, 965 (2023),
  whose text gives "11 modes that are spaced one decade apart" and "Ge = 2.24 MPa";
* PU elastomer, typed below from ``frontend/tests/sfem_MRViscoStrainRateValidation.cpp`` of sfem
  (https://github.com/zulianp/sfem, commit af84fda): Pei, Du, Miao & Suo, Polymer Testing 133,
  108375 (2024), Table 3 (g_i at tau_i = 1e-7 ... 1e2 s, g_inf = 0.0225) and Table 1 (long-term
  Mooney-Rivlin A10 = -0.5341 MPa, A01 = 1.7549 MPa, so G(inf) = 2 (A10 + A01));
* slow sliding relaxes the material fully: Hertz with G(inf); fast sliding leaves it no time:
  Hertz with G(0); both at the case's held approach (a = sqrt(R delta) in both). Tolerance 1 %,
  as in ``test_steady.py``: the cases' grids have 16 (PMMA) and 32 (PU) cells per contact radius
  and the end speeds leave v tau/a below 1e-4 for the longest and above 1e4 for the shortest
  relaxation time.
"""
import numpy as np
import pytest

import viscontact as vc
from viscontact.io.prony_table import PronyTable, parse_prony_table
from viscontact.physics.reference import hertz_from_approach
from viscontact.io.shipped import shipped_cases_dir

MPA = 1e6

# PMMA, the cited table: E_i [MPa], tau_i [s], E(inf) [MPa]
PMMA_E_I = [1.94e2, 2.83e2, 5.54e2, 6.02e2, 3.88e2, 1.56e2, 4.10e1, 1.38e1, 3.68e0, 7.90e-1, 9.60e-1]
PMMA_TAU_I = [2e-2, 2e-1, 2e0, 2e1, 2e2, 2e3, 2e4, 2e5, 2e6, 2e7, 2e8]
PMMA_E_INF = 2.24

# PU elastomer, the cited tables: Table 3 weights g_i [-] at tau_i [s], g_inf [-]; Table 1 [MPa]
PU_G_I = [0.2874, 0.2671, 0.2064, 0.1292, 0.0660, 0.0288, 0.0111, 0.0033, 5.296e-4, 1.795e-5]
PU_TAU_I = [1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1e0, 1e1, 1e2]
PU_G_INF = 0.0225
PU_A10, PU_A01 = -0.5341, 1.7549

# the case files' speed curves [m/s], one per decade
CURVES = {"pmma_master_curve": np.logspace(-17, 2, 20), "pu_elastomer_master_curve": np.logspace(-10, 8, 19)}


def _load(name: str) -> vc.Case:
    return vc.load_case(vc.shipped_case(name))


def _term_file(case: vc.Case) -> PronyTable:
    path = shipped_cases_dir() / case.material.file
    return parse_prony_table(path.read_text(), str(path))


def test_pmma_term_file_reproduces_the_cited_table() -> None:
    case = _load("pmma_master_curve")
    table = _term_file(case)
    assert table.quantity == "E" and case.material.modulus == "tensile"
    assert len(table.moduli) == len(PMMA_E_I) == 11
    np.testing.assert_allclose(table.moduli, np.array(PMMA_E_I) * MPA, rtol=1e-12)
    np.testing.assert_allclose(table.relaxation_times, PMMA_TAU_I, rtol=1e-15)
    np.testing.assert_allclose(np.diff(np.log10(table.relaxation_times)), 1.0, rtol=1e-12)  # a decade apart
    assert table.long_term == pytest.approx(PMMA_E_INF * MPA, rel=1e-9)
    assert table.long_term + sum(table.moduli) == pytest.approx((PMMA_E_INF + sum(PMMA_E_I)) * MPA, rel=1e-12)
    assert table.long_term + sum(table.moduli) == pytest.approx(2239.47 * MPA, rel=1e-12)   # E(0)
    # the case converts E to G with its nu: G = E / (2 (1 + nu))
    material = case.to_problem().material
    factor = 2.0 * (1.0 + material.poisson_ratio)
    assert material.shear_modulus_instantaneous == pytest.approx(2239.47 * MPA / factor, rel=1e-12)
    assert material.shear_modulus_long_term == pytest.approx(PMMA_E_INF * MPA / factor, rel=1e-9)
    np.testing.assert_allclose(np.sort(material.tau), PMMA_TAU_I, rtol=1e-15)


def test_pu_term_file_reproduces_the_cited_tables() -> None:
    """The file holds Table 3's weights scaled to sum to 1 - g_inf (the typed ones sum to
    0.99985), G(inf) = 2 (A10 + A01) of Table 1 and G(0) = G(inf) / g_inf; shear moduli, nu = 0.5
    (the source's model is incompressible)."""
    case = _load("pu_elastomer_master_curve")
    table = _term_file(case)
    assert table.quantity == "G" and case.material.modulus == "shear"
    assert len(table.moduli) == len(PU_G_I) == 10
    np.testing.assert_allclose(table.relaxation_times, PU_TAU_I, rtol=1e-15)
    g_long = 2.0 * (PU_A10 + PU_A01) * MPA                                  # 2.4416 MPa
    g_zero = g_long / PU_G_INF                                              # 108.52 MPa
    assert table.long_term == pytest.approx(2.4416 * MPA, rel=1e-12)
    assert table.long_term + sum(table.moduli) == pytest.approx(g_zero, rel=1e-12)
    weights = np.array(PU_G_I) / sum(PU_G_I)
    np.testing.assert_allclose(np.array(table.moduli) / (g_zero - g_long), weights, rtol=1e-10)
    np.testing.assert_allclose(np.array(table.moduli) / np.array(PU_G_I), (g_zero - g_long) / sum(PU_G_I),
                               rtol=1e-10)                                  # proportional to Table 3
    material = case.to_problem().material
    assert material.poisson_ratio == 0.5
    assert material.shear_modulus_long_term / material.shear_modulus_instantaneous == pytest.approx(PU_G_INF, rel=1e-12)
    assert material.shear_modulus_instantaneous == pytest.approx(g_zero, rel=1e-12)
    np.testing.assert_allclose(np.sort(material.tau), PU_TAU_I, rtol=1e-15)


@pytest.mark.parametrize("name", sorted(CURVES))
def test_coarse_speed_curve_meets_the_hertz_limits_with_one_maximum(name: str) -> None:
    case = _load(name)
    speeds = CURVES[name]
    ds = vc.run_steady(case, speeds)
    problem = case.to_problem()
    material, approach = problem.material, problem.normal.history(problem.time.t_end)  # the steady approach
    radius = case.indenter.radius
    tau = np.asarray(material.tau)
    assert speeds[0] * tau.max() / np.sqrt(radius * approach) < 1e-4
    assert speeds[-1] * tau.min() / np.sqrt(radius * approach) > 1e4
    mu, load, peak = ds["mu_app"].values, ds["load"].values, ds["peak_pressure"].values
    shift = np.abs(ds["contact_shift"].values)
    for k, g in ((0, material.shear_modulus_long_term), (-1, material.shear_modulus_instantaneous)):
        ref = hertz_from_approach(approach, radius, g, material.poisson_ratio)
        assert load[k] == pytest.approx(ref.load, rel=0.01)
        assert peak[k] == pytest.approx(ref.peak_pressure, rel=0.01)
        assert shift[k] < 0.01 * ref.radius
        assert mu[k] < 0.01 * mu.max()
    assert load[-1] / load[0] == pytest.approx(material.shear_modulus_instantaneous
                                               / material.shear_modulus_long_term, rel=0.01)
    assert np.all(mu > 0)
    top = int(np.argmax(mu))
    assert 0 < top < len(mu) - 1
    assert np.all(np.diff(mu[: top + 1]) > 0) and np.all(np.diff(mu[top:]) < 0)
