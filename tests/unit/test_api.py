"""The scripting API around a fake solver: datasets, partial results on failure, steady layouts."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from test_results import fake_records, make_problem  # tests/unit is on sys.path

import viscontact as vc
from viscontact.solvers import transient
from viscontact.errors import ConvergenceError

ROOT = Path(__file__).resolve().parents[2]


def test_steady_is_the_solver_module_and_run_steady_the_api() -> None:
    from viscontact.solvers.steady import solve_steady  # noqa: F401

    assert callable(vc.run_steady) and vc.steady.solve_steady is solve_steady


def test_run_accepts_a_path(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    text = (ROOT / "cases" / "creep_indentation.toml").read_text().replace("\nn = 128", "\nn = 32")
    (tmp_path / "case.toml").write_text(text)
    seen = []

    def fake(problem, *, progress=None, state=None, compliance=None):
        seen.append(problem.grid.n)
        for k, rec in enumerate(fake_records(make_problem(), (0, 0))):
            if progress:
                progress(k + 1, 2)
            yield None, rec

    monkeypatch.setattr(transient, "steps", fake)
    calls = []
    ds = vc.run(tmp_path / "case.toml", progress=lambda d, t: calls.append((d, t)))
    assert seen == [32] and calls == [(1, 2), (2, 2)]
    assert ds.attrs["case"] == text
    assert ds.attrs["complete"] == 0            # 2 of 161 steps


def test_failure_keeps_the_steps_done(monkeypatch: pytest.MonkeyPatch) -> None:
    def failing(problem, *, progress=None, state=None, compliance=None):
        for rec in fake_records(problem, (0, 1)):
            yield None, rec
        raise ConvergenceError("normal contact", 10, 1e-3, 1e-8)

    monkeypatch.setattr(transient, "steps", failing)
    with pytest.raises(ConvergenceError) as info:
        vc.run(make_problem())
    partial = info.value.partial
    assert partial.sizes["t"] == 2 and partial.attrs["complete"] == 0 and partial.attrs["case"] == ""


def test_steady_layouts(monkeypatch: pytest.MonkeyPatch) -> None:
    import sys

    steady = sys.modules["viscontact.solvers.steady"]
    problem = make_problem("gross_sliding")
    record = fake_records(problem, (2,))[0]
    monkeypatch.setattr(steady, "solve_steady", lambda p, speed=None: record)
    monkeypatch.setattr(steady, "speed_sweep", lambda p, speeds: [record] * len(speeds))
    single = vc.run_steady(problem)
    assert single.sizes["t"] == 1 and single.attrs["complete"] == 1
    sweep = vc.run_steady(problem, [0.01, 0.1])
    assert sweep.sizes["speed"] == 2
    for name in ("mu_app", "peak_pressure", "contact_area", "contact_shift", "delta_z", "load"):
        assert sweep[name].dims == ("speed",), name
    assert {"a0", "p0", "retardation_time"} <= set(sweep.attrs)


@pytest.mark.parametrize("speeds", [[float("inf")], [0.01, float("nan")], [-0.1], [], [0.1, 0.1], 0.1, "0.1",
                                    [0.1, True]])
def test_run_steady_checks_its_speeds_as_the_command_line_does(speeds) -> None:
    """Before: inf raised OverflowError deep in the kernels, a scalar or a string a TypeError or
    ValueError of float(), and an empty or repeated list returned a Dataset (no state, or a speed
    coordinate with a repeated value) that ``steady --speeds`` refuses."""
    with pytest.raises(vc.ParameterError) as err:
        vc.run_steady(make_problem("frictionless_sliding"), speeds)
    assert err.value.key == "speeds"


@pytest.mark.parametrize("victim", ["result.nc", "case.toml", "heights.npy"])
def test_run_never_writes_its_checkpoint_over_a_file_that_is_no_checkpoint(tmp_path, victim) -> None:
    """``vc.run(case, checkpoint="result.nc")`` (the checkpoint taken for the output) wrote the
    solver state over the finished result; over the case file too. A numpy array file (a case's
    heights), which ``np.load`` reads as an array and not as an archive, is refused the same way."""
    path = tmp_path / victim
    if victim.endswith(".npy"):
        np.save(path, np.zeros((4, 4)))
    else:
        path.write_bytes(b"\x89HDF\r\n\x1a\n a result" if victim.endswith(".nc") else b"title = 'x'\n")
    before = path.read_bytes()
    with pytest.raises(FileExistsError, match="not a viscontact checkpoint"):
        vc.run(make_problem("none"), checkpoint=path, checkpoint_every=1)
    assert path.read_bytes() == before
    ckpt = tmp_path / "run.checkpoint.npz"  # a checkpoint of an earlier run is replaced
    vc.run(make_problem("none"), checkpoint=ckpt, checkpoint_every=1)
    vc.run(make_problem("none"), checkpoint=ckpt, checkpoint_every=1)


@pytest.mark.parametrize(("kwargs", "key"), [({"checkpoint_every": 2}, "checkpoint"),
                                             ({"checkpoint": "c.npz", "checkpoint_every": -1}, "checkpoint_every"),
                                             ({"checkpoint": "c.npz", "checkpoint_every": 1.5}, "checkpoint_every"),
                                             ({"checkpoint": "c.npz", "checkpoint_every": "2"}, "checkpoint_every")])
def test_run_checks_its_checkpoint_settings(tmp_path, monkeypatch, kwargs, key) -> None:
    """Before: checkpoint_every without a checkpoint file wrote no checkpoint without a word, -1 and
    1.5 were taken (every step, some steps), "2" raised TypeError at the first step."""
    monkeypatch.chdir(tmp_path)
    with pytest.raises(vc.ParameterError) as err:
        vc.run(make_problem("none"), **kwargs)
    assert err.value.key == key and not (tmp_path / "c.npz").exists()


def test_run_to_file_checks_checkpoint_every(tmp_path) -> None:
    with pytest.raises(vc.ParameterError) as err:
        vc.run_to_file(make_problem("none"), tmp_path / "r.nc", checkpoint_every=-1)
    assert err.value.key == "checkpoint_every" and not list(tmp_path.iterdir())
