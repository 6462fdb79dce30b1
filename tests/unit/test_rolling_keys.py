"""The rolling keys of ``[tangential]``: accepted together, refused in one line otherwise."""
import numpy as np
import pytest

from viscontact.errors import ParameterError
from viscontact.io.case import Case

from vc_testing import SEED_MATERIAL_TOML

BASE = SEED_MATERIAL_TOML + """
[indenter]
shape = "sphere"
radius = 0.01
[grid]
n = 16
half_width = 1.6e-3
[normal]
control = "load"
value = 0.15
[time]
t_end = 0.01
[tangential]
"""


def _case(tangential: str) -> Case:
    return Case.from_toml_text(BASE + tangential)


def test_rolling_keys_accepted_and_dt_from_the_rolling_speed():
    case = _case('mode = "rolling"\nrolling_speed = 0.1\ncreepage = -2e-3\nfriction_coefficient = 0.3\n')
    tan = case.to_problem().tangential
    assert tan.rolls and tan.creepage == -2e-3 and tan.sliding_speed == 0.1
    assert case.default_dt() == pytest.approx(2 * 1.6e-3 / 16 / 0.1)
    held = _case('mode = "rolling"\nrolling_speed = 0.1\ntangential_force = 0.01\nfriction_coefficient = 0.3\n')
    assert held.to_problem().tangential.tangential_force == 0.01


@pytest.mark.parametrize("tangential, key", [
    ('mode = "rolling"\nrolling_speed = 0.1\nfriction_coefficient = 0.3\n', "tangential.creepage"),
    ('mode = "rolling"\nrolling_speed = 0.1\ncreepage = 0.0\ntangential_force = 0.01\nfriction_coefficient = 0.3\n',
     "tangential.creepage"),
    ('mode = "rolling"\ncreepage = 0.0\nfriction_coefficient = 0.3\n', "tangential.rolling_speed"),
    ('mode = "rolling"\nrolling_speed = 0.1\ntangential_force = 0.01\n', "tangential.friction_coefficient"),
    ('mode = "rolling"\nrolling_speed = 0.1\ncreepage = 0.0\nsliding_speed = 0.1\n', "tangential.sliding_speed"),
    ('mode = "rolling"\nrolling_speed = 0.1\ncreepage = 0.0\nsteps_per_cell = 2\n', "tangential.steps_per_cell"),
    ('mode = "gross_sliding"\nsliding_speed = 0.1\ncreepage = 0.0\n', "tangential.creepage"),
    ('mode = "partial_slip"\nfriction_coefficient = 0.3\ndisplacement_rate = 0.01\nsliding_speed = 0.1\n'
     'rolling_speed = 0.1\n', "tangential.rolling_speed"),
])
def test_rolling_keys_refused_in_one_line(tangential, key):
    with pytest.raises(ParameterError) as info:
        _case(tangential).to_problem()
    assert info.value.key == key and "\n" not in str(info.value)


ROLLING = 'mode = "rolling"\nrolling_speed = 0.1\ncreepage = -2e-3\nfriction_coefficient = 0.3\n'


def test_a_held_force_beyond_mu_w_is_refused_before_the_run():
    from viscontact.solvers.transient import validate

    problem = _case('mode = "rolling"\nrolling_speed = 0.1\ntangential_force = 0.05\nfriction_coefficient = 0.3\n'
                    ).to_problem()  # mu_f W = 0.045 N
    with pytest.raises(ParameterError, match="below mu_f W = 0.045 N") as info:
        validate(problem)
    assert info.value.key == "tangential.tangential_force"


def test_traction_creepage_curve_in_one_call_and_its_figure(tmp_path):
    """``run_steady(case, creepages=...)`` (``viscontact steady --creepages``): a Dataset along
    ``creepage``, the traction odd in it and bounded by mu_f W; ``plot`` draws the curve."""
    import numpy as np

    from viscontact.plotting import plot_any
    from viscontact.running.api import run_steady

    decoupled = Case.from_toml_text((BASE + ROLLING).replace("poisson_ratio = 0.3", "poisson_ratio = 0.5"))
    ds = run_steady(decoupled, creepages=[-0.1, -2e-3, 0.0, 2e-3])  # nu = 0.5: free rolling at creepage 0
    ratio = ds["traction_ratio"].values
    assert ratio[0] == pytest.approx(1.0) and ratio[2] == 0.0 and ratio[1] == pytest.approx(-ratio[3])
    assert np.all(np.abs(ratio) <= 1 + 1e-12) and ds["creepage"].attrs["units"] == "1"
    assert [p.name for p in plot_any(ds, tmp_path)] == ["creep_curve.png"]
    single = run_steady(_case(ROLLING))
    assert single["creepage"].values.tolist() == [-2e-3] and int(single["phase"][0]) == 3
    with pytest.raises(ParameterError) as info:
        run_steady(_case(ROLLING), speeds=[0.1])
    assert info.value.key == "speeds"


def test_the_rolling_keys_enter_the_checkpoint_fingerprint():
    """A checkpoint of another creepage or speed is another case's; the other modes' fingerprints are
    those written before rolling came (pinned in test_resume_bodies)."""
    from viscontact.io.checkpoint import problem_fingerprint

    base = problem_fingerprint(_case(ROLLING).to_problem())
    for change in ("creepage = -2e-3", "rolling_speed = 0.1"):
        other = ROLLING.replace(change, change.replace("2e-3", "3e-3").replace("0.1", "0.2"))
        assert problem_fingerprint(_case(other).to_problem()) != base


def test_rolling_with_adhesion_is_refused_in_one_line():
    text = BASE + ROLLING + "[adhesion]\nwork_of_adhesion = 0.05\ncohesive_stress = 1.0e6\n"
    with pytest.raises(ParameterError) as info:
        Case.from_toml_text(text).to_problem()
    assert info.value.key == "tangential.mode" and "adhesion" in str(info.value)


ROUGH_SPHERE = '[indenter]\nshape = "sphere"\nradius = 0.01\n[indenter.roughness]\nhurst = 0.8\nrms_height = 1e-7\n'
SELF_AFFINE = '[indenter]\nshape = "self_affine"\nhurst = 0.8\nrms_slope = 0.1\n'


def _rough_rolling(indenter: str, rolling: str = ROLLING, periodic: bool = True) -> str:
    text = BASE.replace('[indenter]\nshape = "sphere"\nradius = 0.01\n', indenter) + rolling
    return text.replace("[grid]\n", "[grid]\nperiodic = true\n") if periodic else text


@pytest.mark.parametrize("indenter", [ROUGH_SPHERE, SELF_AFFINE])
def test_rolling_on_a_rough_periodic_surface_carries_its_roughness(indenter):
    """A rough surface rolls on a periodic grid with a held creepage; its roughness is carried through
    the contact (the gap of a later step differs from the first's; the validation tests check how)."""
    problem = Case.from_toml_text(_rough_rolling(indenter)).to_problem()
    assert problem.rolls_rough
    assert problem.rolling_gap(0) is problem.gap
    assert not np.array_equal(problem.rolling_gap(1), problem.gap)


@pytest.mark.parametrize("rolling,periodic,missing", [
    (ROLLING, False, "grid.periodic"),
    ('mode = "rolling"\nrolling_speed = 0.1\ntangential_force = 0.01\nfriction_coefficient = 0.3\n', True,
     "held tangential.creepage")])
def test_rolling_on_a_rough_surface_refuses_what_is_missing_in_one_line(rolling, periodic, missing):
    """Rough rolling needs the Fourier shift of a periodic grid and a held creepage (the distance its
    surface turned is then known at every step); a smooth sphere rolls on either grid."""
    with pytest.raises(ParameterError) as info:
        Case.from_toml_text(_rough_rolling(ROUGH_SPHERE, rolling, periodic)).to_problem()
    assert info.value.key == "tangential.mode" and "rough" in str(info.value) and missing in str(info.value)
    smooth = Case.from_toml_text(BASE + ROLLING).to_problem()  # a smooth sphere rolls
    assert smooth.tangential.rolls and not smooth.rolls_rough
