"""The shipped real-material case ``pmma_master_curve``: its term file against the cited table, and
its coarse steady speed curve against the Hertz limits.

References (independent of viscontact):
* the cited Prony series, typed below from ``tests/g2.dat`` of S. Shanbhag's PSI
  (https://github.com/shane5ul/psi, commit 67c702e): Schapery's (1962) PMMA tensile relaxation
  data as fitted by Park & Schapery (Int. J. Solids Struct. 36, 1653, 1999), reproduced in
  Shanbhag, J. Rheol. 67, 965 (2023), whose text gives "11 modes that are spaced one decade
  apart" and "Ge = 2.24 MPa";
* slow sliding relaxes the material fully: Hertz with G(inf); fast sliding leaves it no time:
  Hertz with G(0); both at the case's held approach (a = sqrt(R delta) in both). Tolerance 1 %,
  as in ``test_steady.py``: the case's grid has 16 cells per contact radius and the end speeds
  leave v tau/a below 1e-4 for the longest and above 1e4 for the shortest relaxation time.
"""
import numpy as np
import pytest

import viscontact as vc
from viscontact.prony_table import parse_prony_table
from viscontact.reference import hertz_from_approach
from viscontact.shipped import shipped_cases_dir

# the cited table: E_i [MPa], tau_i [s], E(inf) [MPa]
SOURCE_E_I = [1.94e2, 2.83e2, 5.54e2, 6.02e2, 3.88e2, 1.56e2, 4.10e1, 1.38e1, 3.68e0, 7.90e-1, 9.60e-1]
SOURCE_TAU_I = [2e-2, 2e-1, 2e0, 2e1, 2e2, 2e3, 2e4, 2e5, 2e6, 2e7, 2e8]
SOURCE_E_INF = 2.24
MPA = 1e6
SPEEDS = np.logspace(-17, 2, 20)     # m/s, one per decade: the case file's curve


@pytest.fixture(scope="module")
def case():
    return vc.load_case(vc.shipped_case("pmma_master_curve"))


def test_term_file_reproduces_the_cited_table(case) -> None:
    path = shipped_cases_dir() / case.material.file
    table = parse_prony_table(path.read_text(), str(path))
    assert table.quantity == "E" and case.material.modulus == "tensile"
    assert len(table.moduli) == len(SOURCE_E_I) == 11
    np.testing.assert_allclose(table.moduli, np.array(SOURCE_E_I) * MPA, rtol=1e-12)
    np.testing.assert_allclose(table.relaxation_times, SOURCE_TAU_I, rtol=1e-15)
    np.testing.assert_allclose(np.diff(np.log10(table.relaxation_times)), 1.0, rtol=1e-12)  # a decade apart
    assert table.long_term == pytest.approx(SOURCE_E_INF * MPA, rel=1e-9)
    assert table.long_term + sum(table.moduli) == pytest.approx((SOURCE_E_INF + sum(SOURCE_E_I)) * MPA, rel=1e-12)
    assert table.long_term + sum(table.moduli) == pytest.approx(2239.47 * MPA, rel=1e-12)   # E(0)
    # the case converts E to G with its nu: G = E / (2 (1 + nu))
    material = case.to_problem().material
    factor = 2.0 * (1.0 + material.poisson_ratio)
    assert material.shear_modulus_instantaneous == pytest.approx(2239.47 * MPA / factor, rel=1e-12)
    assert material.shear_modulus_long_term == pytest.approx(SOURCE_E_INF * MPA / factor, rel=1e-9)
    np.testing.assert_allclose(np.sort(material.tau), SOURCE_TAU_I, rtol=1e-15)


def test_coarse_speed_curve_meets_the_hertz_limits_with_one_maximum(case) -> None:
    ds = vc.run_steady(case, SPEEDS)
    material = case.to_problem().material
    mu, load, peak = ds["mu_app"].values, ds["load"].values, ds["peak_pressure"].values
    shift = np.abs(ds["contact_shift"].values)
    for k, g in ((0, material.shear_modulus_long_term), (-1, material.shear_modulus_instantaneous)):
        ref = hertz_from_approach(case.normal.value, case.indenter.radius, g, material.poisson_ratio)
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
