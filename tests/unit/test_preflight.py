"""The one preflight (:mod:`viscontact.running.preflight`): what it returns, the checks each caller asks
for, and that a run given its preflight does not check again."""
from __future__ import annotations

import warnings
from pathlib import Path

import pytest

from viscontact.errors import ParameterError, ViscontactWarning
from viscontact.io.case import load_case
from viscontact.running import api
from viscontact.running import preflight as preflight_module
from viscontact.running.preflight import Preflight, preflight

CASES = Path(__file__).resolve().parents[2] / "cases"
SMALL = {"grid.n": 16, "grid.half_width": 1.6e-3, "time.t_end": 5e-4}


def _case(**more):
    return load_case(CASES / "creep_indentation.toml").with_overrides({**SMALL, **more})


def test_it_returns_the_problem_the_case_text_and_with_resources_the_estimate(tmp_path):
    case = _case()
    checked = preflight(case)
    assert isinstance(checked, Preflight) and checked.problem.grid.n == 16 and checked.text == case.text
    assert checked.transient and checked.estimate is None and checked.warnings == ()
    estimated = preflight(case, out=tmp_path / "r.nc", resources=True)
    assert estimated.estimate is not None and estimated.estimate.records == estimated.problem.time.n_steps
    with pytest.raises(TypeError, match="needs the result file"):
        preflight(case, resources=True)


def test_a_case_file_path_is_read_and_never_replaced(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text((CASES / "creep_indentation.toml").read_text())
    assert preflight(path, transient=False, validate=False, machine=False).problem.grid.n == 128
    with pytest.raises(FileExistsError):
        preflight(path, out=path, force=True, machine=False)


def test_without_warn_the_warnings_are_recorded_not_shown():
    """A sweep's plan (``warn=False``) keeps the checks' warnings in :attr:`Preflight.warnings` (the run
    shows them when it runs); with ``warn`` they are issued as they arise."""
    case = _case(**{"solver.device": "gpu"})  # a GPU below 512^2 cells: warned about
    with warnings.catch_warnings():
        warnings.simplefilter("error", ViscontactWarning)
        quiet = preflight(case, machine=False, warn=False)
    assert len(quiet.warnings) == 1 and "solver.device = 'gpu' on 16 x 16 cells" in quiet.warnings[0]
    with pytest.warns(ViscontactWarning, match="solver.device = 'gpu' on 16 x 16"):
        shown = preflight(case, machine=False)
    assert shown.warnings == ()


def test_the_machine_check_is_the_last_and_can_be_left_out(monkeypatch):
    """``machine=False`` (a sweep's plan) passes a case this machine cannot run; the run's preflight
    refuses it after every other check."""
    calls = []
    monkeypatch.setattr(preflight_module, "check_machine", lambda problem: calls.append(problem.grid.n))
    preflight(_case(), machine=False)
    assert calls == []
    preflight(_case())
    assert calls == [16]
    with pytest.raises(ParameterError, match="grid.n"):  # refused before the machine is asked
        preflight(_case(**{"grid.n": 8}))
    assert calls == [16]


def test_a_run_given_its_preflight_does_not_check_again(tmp_path, monkeypatch):
    out = tmp_path / "r.nc"
    checked = preflight(_case(), out=out)
    monkeypatch.setattr(preflight_module, "_preflight", lambda *a, **k: pytest.fail("checked twice"))
    written = api.run_to_file(checked, out)
    assert written.path == out and written.records == checked.problem.time.n_steps and out.exists()
