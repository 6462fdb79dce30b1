"""The shipped fretting case (cases/fretting_zener.toml): three cycles of delta_x = +-8 um on a Zener
half-space under a held load, below gross slip, run as shipped (64 x 64, 131 steps, a few seconds)."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from viscontact.running.api import run
from viscontact.io.case import load_case
from viscontact.problem.problem import PHASE_PARTIAL_SLIP
from viscontact.physics.reference import cattaneo_mindlin

CASE = Path(__file__).resolve().parents[2] / "cases" / "fretting_zener.toml"
AMPLITUDE, MU, W, R = 8e-6, 0.3, 0.15, 0.01
TURNS = (0.0025, 0.0125, 0.0225, 0.0325)  # s: delta_x = +8 um; one cycle between two of them


@pytest.fixture(scope="module")
def result():
    return run(load_case(CASE))


def _cycle_energies(ds) -> list[float]:
    t, d, q = ds["t"].values, ds["delta_x"].values, ds["friction_force"].values
    energies = []
    for start, end in zip(TURNS[:-1], TURNS[1:]):
        m = (t >= start - 1e-9) & (t <= end + 1e-9)
        energies.append(float(np.sum(0.5 * (q[m][1:] + q[m][:-1]) * np.diff(d[m]))))
    return energies


def test_the_case_frets_below_gross_slip_with_the_incremental_slip(result):
    """Partial slip to the end (complete, never sliding), the incremental slip by default, delta_x
    following the history to round-off, Q of both signs within mu_f W and a stick zone at every
    step (measured at least 0.34 of the contact)."""
    problem = load_case(CASE).to_problem()
    assert problem.tangential.slip == "incremental" and problem.tangential.displacement_history is not None
    assert result.attrs["complete"] == 1 and np.all(result["phase"].values == PHASE_PARTIAL_SLIP)
    t = result["t"].values
    np.testing.assert_allclose(result["delta_x"].values, [problem.tangential.delta_x(s) for s in t], rtol=0,
                               atol=1e-12 * AMPLITUDE)
    ratio = result["friction_force"].values / (MU * result["load"].values)
    assert ratio.max() > 0.5 and ratio.min() < -0.5 and np.abs(ratio).max() < 1
    assert result["stick_ratio"].values.min() > 0.3


def test_the_loops_dissipate_more_than_the_elastic_limits(result):
    """Each cycle's loop area (the energy dissipated in it) is positive and lies above the elastic
    Mindlin-Deresiewicz loops of both G(0) and G(inf) at the same amplitude (0.092 and 0.0036 uJ): a
    viscoelastic body dissipates in its bulk as well as by slip, and a cycle of one retardation time
    lies near the Zener solid's loss peak. Measured 0.54, 0.58, 0.59 uJ: the contact grows by creep
    (a from 0.53 to 1.13 mm) and each cycle dissipates a little more than the last."""
    energies = _cycle_energies(result)
    elastic = [cattaneo_mindlin(W, R, MU, g, 0.5).cycle_energy(AMPLITUDE) for g in (1.93e6, 0.193e6)]
    assert min(energies) > 3 * max(elastic), (energies, elastic)
    assert energies[0] < energies[1] < energies[2], energies
    radius = np.sqrt(result["contact_area"].values / np.pi)
    assert radius[-1] > 2 * radius[0]


def test_the_result_states_the_displacement_history(result):
    """The result holds the history the run followed (attributes displacement_history_times [s] and
    _values [m]), also where no case text does (a run of a Problem); a ramp's result has neither -
    before, only the case text held it, and a Problem's run lost it."""
    from vc_testing import sphere_problem

    from viscontact.physics.materials import Material
    from viscontact.problem.problem import PiecewiseLinear

    history = load_case(CASE).to_problem().tangential.displacement_history
    np.testing.assert_array_equal(result.attrs["displacement_history_times"], history.times)
    np.testing.assert_array_equal(result.attrs["displacement_history_values"], history.values)
    fretting = PiecewiseLinear((0.0, 1.0, 3.0), (0.0, 1e-6, -1e-6))
    kw = dict(mode="partial_slip", friction=MU, t_end=0.2, dt=0.1, scheme="linear")
    ds = run(sphere_problem(Material.elastic(1.93e6, 0.5), 16, 1e-3, displacement_history=fretting, **kw))
    assert ds.attrs["case"] == "" and list(ds.attrs["displacement_history_values"]) == [0.0, 1e-6, -1e-6]
    ramp = run(sphere_problem(Material.elastic(1.93e6, 0.5), 16, 1e-3, rate=1e-6, speed=1.25e-3, **kw))  # dt = dx / v
    assert not any(key.startswith("displacement_history") for key in ramp.attrs)


def test_a_thinned_output_keeps_the_turning_points(tmp_path):
    """With output.every = 7 the steps of the turning points (10, 30, ..., 110 at 0.25 ms; 70 is
    kept anyway, 130 is the last) fall between the kept ones: before, the records turned at +-7.2 um instead of +-8 um, and the loop
    figure's tips were cut. They are recorded too (Problem.recorded), in memory and streamed, and
    the streamed file holds as many records as resources.recorded_steps claimed (disk space)."""
    from viscontact.running import resources
    from viscontact.running.api import run_to_file
    from viscontact.io.netcdf import open_result

    case = load_case(CASE).with_overrides({"grid.n": 16, "output.every": 7})
    problem = case.to_problem()
    assert sorted(problem.turning_steps) == [10, 30, 50, 70, 90, 110]
    ds = run(case)
    kept = ds["step"].values
    assert set(range(0, 131, 7)) | {130} | set(problem.turning_steps) == set(kept)
    assert ds.sizes["t"] == resources.recorded_steps(problem) == 20 + 5  # 0, 7, ..., 126, 130 and five turns
    assert ds["delta_x"].max() == pytest.approx(AMPLITUDE, rel=1e-12)
    assert ds["delta_x"].min() == pytest.approx(-AMPLITUDE, rel=1e-12)
    run_to_file(case, tmp_path / "r.nc")
    streamed = open_result(tmp_path / "r.nc")
    assert np.array_equal(streamed["step"].values, kept) and streamed.attrs["complete"] == 1
