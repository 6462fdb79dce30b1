"""The rolling keys of ``[tangential]``: accepted together, refused in one line otherwise."""
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
