"""One rule for dt (issue 33 item 3): when sliding ties the time step to the grid, dt = (2 half_width
/ n) / sliding_speed / steps_per_cell, and a load or displacement history or the material's response
asks for a smaller one, the refusal advises the ``tangential.steps_per_cell`` that the next run
accepts, never a ``time.dt`` that the sliding rule then refuses."""
from __future__ import annotations

import re
from pathlib import Path

import pytest
from vc_testing import SEED_MATERIAL_TOML, dry_run

ROOT = Path(__file__).resolve().parents[2]

#: a Zener half-space under a load oscillating between 0.05 and 0.15 N (turning points every 5 ms from
#: 2.5 ms) while sliding from t = 0; one cell of sliding takes 1.99 ms, so the default step (one cell)
#: misses the turning points
OSCILLATING_SLIDING = """\
title = "oscillating load, gross sliding"
""" + SEED_MATERIAL_TOML + """\
[indenter]
shape = "sphere"
radius = 0.01
[grid]
n = 32
half_width = 1.5e-3
[normal]
control = "load"
history = [[0.0, 0.1], [0.0025, 0.15], [0.0075, 0.05], [0.0125, 0.15], [0.0175, 0.05], [0.02, 0.1]]
[tangential]
mode = "gross_sliding"
friction_coefficient = 0.3
sliding_speed = 0.0471
[time]
t_end = 0.02
"""


def _advised(line: str) -> str:
    """The ``--set`` the refusal advises: tangential.steps_per_cell=k."""
    assert line.startswith("viscontact: error: "), line
    k = re.search(r"use tangential\.steps_per_cell = (\d+)", line)
    assert k is not None and "use time.dt" not in line, line
    return f"tangential.steps_per_cell={k.group(1)}"


@pytest.mark.filterwarnings("ignore::viscontact.ViscontactWarning")
def test_a_history_while_sliding_is_advised_a_steps_per_cell_that_is_accepted(tmp_path, capsys):
    """Before: 'use time.dt = 0.00125 s', then 'time.dt: must equal ... 0.00199 s'. Now the turning
    point's refusal names tangential.steps_per_cell (the smallest that meets every turning point), and
    a time.dt given while sliding is refused with the same kind of advice; applied, each passes."""
    case = tmp_path / "osc.toml"
    case.write_text(OSCILLATING_SLIDING)
    code, err = dry_run(capsys, case)
    assert code == 2 and len(err) == 1 and err[0].startswith("viscontact: error: tangential.steps_per_cell: ")
    advice = _advised(err[0])
    assert dry_run(capsys, case, advice)[0] == 0
    smaller = f"tangential.steps_per_cell={int(advice.split('=')[1]) - 1}"
    assert dry_run(capsys, case, smaller)[0] == 2  # the smallest that works
    code, err = dry_run(capsys, case, "time.dt=0.0005")
    assert code == 2 and err[0].startswith("viscontact: error: time.dt: 0.0005 s is not the sliding's step")
    assert "remove time.dt" in err[0]
    assert dry_run(capsys, case, "time.dt=", _advised(err[0]))[0] == 0


def test_a_finer_grid_of_a_sliding_seed_case_is_advised_a_steps_per_cell_that_is_accepted(capsys):
    """``run --set grid.n=64`` on seed Table 3 case 3 (the seed's first-order scheme, dt following the
    grid): refused for missing the relaxation, naming the steps_per_cell that ``reproduce --n 64`` sets
    itself; applied, accepted."""
    case = ROOT / "cases" / "seed_table3_case3.toml"
    code, err = dry_run(capsys, case, "grid.n=64")
    assert code == 2 and len(err) == 1 and err[0].startswith("viscontact: error: tangential.steps_per_cell: ")
    assert dry_run(capsys, case, "grid.n=64", _advised(err[0]))[0] == 0


@pytest.mark.filterwarnings("ignore::viscontact.ViscontactWarning")
def test_the_time_step_advice_also_meets_the_turning_points(tmp_path, capsys):
    """A faster material (retardation 2 ms) fails the time-step guard first: halving the sliding step
    8 times is enough for the creep, but misses the load's turning points, which the next run would
    refuse; the advice is the smallest steps_per_cell from 8 on that meets both, and is accepted."""
    case = tmp_path / "osc.toml"
    case.write_text(OSCILLATING_SLIDING.replace("retardation_time = 0.01", "retardation_time = 0.002"))
    code, err = dry_run(capsys, case)
    assert code == 2 and "misses the creep" in err[0]
    advice = _advised(err[0])
    assert int(advice.split("=")[1]) > 8
    assert dry_run(capsys, case, advice)[0] == 0


@pytest.mark.filterwarnings("ignore::viscontact.ViscontactWarning")
def test_without_sliding_the_time_step_advice_also_meets_the_turning_points():
    """Without sliding the halved step (0.25 ms) is enough for the creep but misses the load's peak at
    2.63 ms by more than 1 %: the advice is a time.dt below it that meets the peak, and is accepted."""
    from viscontact.errors import ParameterError
    from viscontact.io.case import Case
    from viscontact.running import guards

    text = (OSCILLATING_SLIDING.replace("retardation_time = 0.01", "retardation_time = 0.002")
            .replace('mode = "gross_sliding"', 'mode = "none"').replace("t_end = 0.02", "t_end = 0.02\ndt = 0.002")
            .replace("[0.0025, 0.15]", "[0.00263, 0.15]"))
    case = Case.from_toml_text(text)
    with pytest.raises(ParameterError, match="misses the creep") as info:
        guards.check_problem(case.to_problem())
    dt = float(info.value.message.split("use time.dt = ")[1].split(" s")[0])
    assert dt < 2.5e-4
    guards.check_problem(case.with_overrides({"time.dt": dt}).to_problem())
