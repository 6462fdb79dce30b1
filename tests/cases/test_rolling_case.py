"""The shipped rolling case (``rolling_polymer_roller``): a ball braking on a Zener rubber at a held
creepage, from standstill. Checked: the traction builds from zero at t = 0 and settles, the stick zone
at the leading edge, the rolling resistance resists the rolling, and the end state is the steady
rolling solver's (the same case, :func:`viscontact.running.api.run_steady`): measured at 32^2 (the
fast test) traction -0.77 %, rolling resistance -0.19 %; at 64^2 (the case's grid) +0.36 % and -0.21 %
(the transient's domain drops the wake behind the grid, the steady kernel holds the whole past):
tolerance 1 %."""
from pathlib import Path

import numpy as np
import pytest

from viscontact import load_case
from viscontact.running.api import run_steady
from viscontact.running.loop import simulate

CASES = Path(__file__).resolve().parents[2] / "cases"


def _check(case, tolerance: float) -> None:
    problem = case.to_problem()
    records = list(simulate(problem))
    steady = run_steady(case)
    force = np.array([r.friction_force for r in records])
    assert force[0] == 0.0 and np.all(force[1:] > 0)  # braking: the traction on the body in +x, from zero
    tail = force[int(0.9 * force.size):]
    assert (tail.max() - tail.min()) < 5e-3 * tail.mean()  # settled
    last = records[-1]
    assert last.friction_force == pytest.approx(float(steady["friction_force"][0]), rel=tolerance)
    assert last.hysteresis_force > 0
    assert last.hysteresis_force == pytest.approx(float(steady["hysteresis_force"][0]), rel=tolerance)
    x = problem.grid.x
    stuck = last.stick
    sliding = (last.pressure > 0) & ~stuck
    assert float((x[None, :] * stuck).sum() / stuck.sum()) > float((x[None, :] * sliding).sum() / sliding.sum())


def test_rolling_case_coarse():
    _check(load_case(CASES / "rolling_polymer_roller.toml").with_overrides({"grid.n": 32}), 0.01)


@pytest.mark.slow
def test_rolling_case_full_resolution():
    _check(load_case(CASES / "rolling_polymer_roller.toml"), 0.01)


def test_rolling_case_under_a_held_force_with_the_coupling():
    """The case braking with a held force of 0.02 N on a compressible rubber (nu = 0.3: the root find of
    the creepage inside each coupling pass): the creepage found settles to the steady solver's
    (measured -0.01790 against -0.01779 at 32^2, +0.63 %: the transient's wake; tolerance 1.5 %)."""
    case = load_case(CASES / "rolling_polymer_roller.toml").with_overrides(
        {"grid.n": 32, "tangential.creepage": None, "tangential.tangential_force": 0.02, "material.poisson_ratio": 0.3})
    records = list(simulate(case.to_problem()))
    assert all(r.friction_force == pytest.approx(0.02, rel=1e-8) for r in records)
    assert records[-1].creepage == pytest.approx(float(run_steady(case)["creepage"][0]), rel=1.5e-2)
