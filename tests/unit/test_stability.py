"""Stability of the hereditary time schemes (viscontact.numerics.schemes, TimeScheme.amplification).

For a Zener material the seed's piecewise-constant scheme amplifies a traction disturbance by
z = A - (J_1/J_0)(1 - A), A = exp(-dt/lambda), per step: unstable once dt > -lambda ln(1 - 2 G(inf)/G(0))
(2.23 ms for the seed's material). Measured (helper run, n = 32, held load): dt = 2.1 ms converges to the
G(inf) Hertz solution, dt = 2.3 ms oscillates between 1.5x and 2x the right peak pressure.
"""
import numpy as np
import pytest

from viscontact.errors import ParameterError
from viscontact.numerics.schemes import amplification, stable_step_limit
from viscontact.physics.materials import Material
from viscontact.solvers.transient import init

from vc_testing import SEED_TAU, seed_material, sphere_problem


@pytest.mark.parametrize("ratio", [3.0, 5.0, 10.0])
def test_zener_limit_is_closed_form(ratio):
    mat = seed_material(ratio)
    expected = -SEED_TAU * np.log(1 - 2 / ratio)
    assert stable_step_limit(mat.creep, "constant") == pytest.approx(expected, rel=1e-9)
    assert amplification(mat.creep, 0.99 * expected, "constant") < 1 < amplification(mat.creep, 1.01 * expected, "constant")


def test_linear_scheme_is_stable_for_any_step():
    mat = Material.prony(1e5, [2e5, 5e5, 1e6], [1e-3, 1e-2, 1e-1], 0.3)
    assert stable_step_limit(mat.creep, "linear") == np.inf
    for dt in np.logspace(-5, 1, 13):
        assert amplification(mat.creep, dt, "linear") <= 1.0


def test_transient_refuses_an_unstable_step():
    with pytest.raises(ParameterError) as err:
        init(sphere_problem(seed_material(), 16, 1.5e-3, t_end=0.1, dt=3e-3))
    assert err.value.key == "time.dt" and "linear" in str(err.value)
    init(sphere_problem(seed_material(), 16, 1.5e-3, t_end=0.1, dt=3e-3, scheme="linear"))


def _brute_force_growth(spectrum, dt: float, scheme: str, steps: int = 3000) -> float:
    """Iterate the recursion itself (PronyHistory, a held zero displacement after a unit traction
    step at t = 0): e_k = -r_k / J_inst. Returns max |e| over the last 100 steps over max |e| over
    steps 100..200 (>> 1: the disturbance grows)."""
    from viscontact.numerics.history import PronyHistory
    from viscontact.numerics.schemes import step_coefficients

    hist = PronyHistory.zeros(spectrum.retardation_times.size, 1)
    hist = hist.advanced(np.ones((1, 1)), step_coefficients(spectrum, dt, scheme, True), 0.0)
    coef = step_coefficients(spectrum, dt, scheme, False)
    values = []
    for k in range(1, steps):
        e = -hist.known(coef, k * dt) / coef.instantaneous
        hist = hist.advanced(e, coef, k * dt)
        values.append(abs(float(e[0, 0])))
    return max(values[-100:]) / max(max(values[100:200]), 1e-300)


def _wide_prony(terms: int = 20) -> Material:
    """A Prony series over 11 decades (1e-8 s to 1e3 s), G(0)/G(inf) = 1 + 0.5 terms."""
    tau = np.logspace(-8, 3, terms)
    return Material.prony(1e5, [5e4] * terms, tau, 0.3)


@pytest.mark.parametrize("material", [Material.zener(1.93e6, 1.93e6 / 5, 0.01, 0.3),
                                      Material.prony(1e5, [2e6, 5e5, 1e6], [1e-3, 1e-2, 1e-1], 0.3),
                                      _wide_prony()], ids=["zener", "prony3", "prony20"])
def test_stability_limit_against_brute_force_amplification(material):
    """The eigenvalue limit separates steps whose disturbance decays from steps where it grows
    (brute force, independent of the companion matrix); the 20-term series over 11 decades gets a
    finite, positive limit (the polynomial-root version reported 0 s)."""
    limit = stable_step_limit(material.creep, "constant")
    assert 0 < limit < np.inf
    assert _brute_force_growth(material.creep, 0.9 * limit, "constant") < 1.0
    assert _brute_force_growth(material.creep, 1.1 * limit, "constant") > 1e3
    for dt in (0.5 * limit, 1.1 * limit, 10 * limit):
        assert _brute_force_growth(material.creep, dt, "linear") < 1.0
