"""Stability of the hereditary time schemes (viscontact.history.amplification).

For a Zener material the seed's piecewise-constant scheme amplifies a traction disturbance by
z = A - (J_1/J_0)(1 - A), A = exp(-dt/lambda), per step: unstable once dt > -lambda ln(1 - 2 G(inf)/G(0))
(2.23 ms for the seed's material). Measured (helper run, n = 32, held load): dt = 2.1 ms converges to the
G(inf) Hertz solution, dt = 2.3 ms oscillates between 1.5x and 2x the right peak pressure.
"""
import numpy as np
import pytest

from viscontact.errors import ParameterError
from viscontact.history import amplification, stable_step_limit
from viscontact.materials import Material
from viscontact.transient import init

from vc_testing import SEED_TAU, seed_material, sphere_problem


@pytest.mark.parametrize("ratio", [3.0, 5.0, 10.0])
def test_zener_limit_is_closed_form(ratio):
    mat = seed_material(ratio)
    expected = -SEED_TAU * np.log(1 - 2 / ratio)
    assert stable_step_limit(mat, "constant") == pytest.approx(expected, rel=1e-9)
    assert amplification(mat, 0.99 * expected, "constant") < 1 < amplification(mat, 1.01 * expected, "constant")


def test_linear_scheme_is_stable_for_any_step():
    mat = Material.prony(1e5, [2e5, 5e5, 1e6], [1e-3, 1e-2, 1e-1], 0.3)
    assert stable_step_limit(mat, "linear") == np.inf
    for dt in np.logspace(-5, 1, 13):
        assert amplification(mat, dt, "linear") <= 1.0


def test_transient_refuses_an_unstable_step():
    with pytest.raises(ParameterError) as err:
        init(sphere_problem(seed_material(), 16, 1.5e-3, t_end=0.1, dt=3e-3))
    assert err.value.key == "time.dt" and "linear" in str(err.value)
    init(sphere_problem(seed_material(), 16, 1.5e-3, t_end=0.1, dt=3e-3, scheme="linear"))
