"""A :class:`~viscontact.problem.problem.Problem` built in a script is checked as a case file is: every bad
value is a :class:`~viscontact.errors.ParameterError` naming the case key, never a deep numpy error
(a step of zero divided by zero) or a silent wrong answer (an unsorted load history interpolated as
if sorted, ``output.every = -1`` or a misspelt field accepted, an unknown normal control run as
displacement control)."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import viscontact as vc
from viscontact.numerics.grid import Grid
from viscontact.problem.problem import NormalLoading, OutputSettings, PiecewiseLinear, TangentialLoading, TimeStepping


def _problem() -> vc.Problem:
    case = vc.load_case(vc.shipped_case("creep_indentation"))
    return case.with_overrides({"grid.n": 16, "grid.half_width": 1.6e-3, "time.t_end": 5e-4}).to_problem()


BAD = [
    ("time.dt", lambda: TimeStepping(t_end=5e-4, dt=0.0)),
    ("time.dt", lambda: TimeStepping(t_end=5e-4, dt=float("nan"))),
    ("time.t_end", lambda: TimeStepping(t_end=-5e-4, dt=1e-4)),
    ("time.t_end", lambda: TimeStepping(t_end=float("inf"), dt=1e-4)),
    ("normal.control", lambda: NormalLoading("force", PiecewiseLinear.constant(0.15))),
    ("normal.history", lambda: NormalLoading("load", PiecewiseLinear.constant(-0.15))),
    ("normal.history", lambda: NormalLoading("load", PiecewiseLinear.constant(float("nan")))),
    ("normal.history", lambda: NormalLoading("load", PiecewiseLinear((0.0, 3e-4, 1e-4), (0.1, 0.15, 0.0)))),
    ("normal.history", lambda: NormalLoading("load", PiecewiseLinear((0.0, 3e-4), (0.1,)))),
    ("output.every", lambda: OutputSettings(every=0)),
    ("output.every", lambda: OutputSettings(every=-1)),
    ("output.fields", lambda: OutputSettings(fields=("presure",))),
    ("output.fields", lambda: OutputSettings(fields="pressure")),
    ("tangential.mode", lambda: TangentialLoading(mode="sliding")),
    ("tangential.steps_per_cell", lambda: TangentialLoading("frictionless_sliding", sliding_speed=0.05,
                                                            steps_per_cell=0)),
    ("tangential.friction_coefficient", lambda: TangentialLoading("gross_sliding", friction_coefficient=-0.3,
                                                                  sliding_speed=0.05)),
    ("tangential.sliding_speed", lambda: TangentialLoading("frictionless_sliding", sliding_speed=float("inf"))),
    ("grid.n", lambda: Grid(n=16.0, half_width=1e-3)),
    ("grid.half_width", lambda: Grid(n=16, half_width=float("nan"))),
    ("gap", lambda: dataclasses.replace(_problem(), gap=np.zeros((8, 8)))),
    ("gap", lambda: dataclasses.replace(_problem(), gap=np.full((16, 16), np.nan))),
    ("indenter.radius", lambda: dataclasses.replace(_problem(), radius=-0.01)),
]


@pytest.mark.parametrize(("key", "build"), BAD, ids=[f"{k}-{i}" for i, (k, _) in enumerate(BAD)])
def test_a_bad_value_in_a_scripted_problem_is_a_parameter_error_naming_its_key(key, build) -> None:
    with pytest.raises(vc.ParameterError) as err:
        build()
    assert err.value.key == key


def test_numpy_scalars_are_numbers() -> None:
    """What a script computes with numpy is accepted where a Python number is."""
    Grid(n=np.int64(16), half_width=np.float32(1e-3))
    TimeStepping(t_end=np.float64(5e-4), dt=np.float64(1e-4))
    NormalLoading("load", PiecewiseLinear.constant(np.float64(0.15)))
    OutputSettings(every=np.int64(2), fields=["pressure"])


def test_the_case_file_says_the_same_as_the_problem() -> None:
    """The case layer's history check is the problem layer's, word for word."""
    case = vc.load_case(vc.shipped_case("creep_indentation"))
    for history in ([[0.0, 0.1], [3e-4, 0.15], [1e-4, 0.0]], [[0.0, -0.1]]):
        with pytest.raises(vc.ParameterError) as from_case:
            case.with_overrides({"normal.history": history})
        with pytest.raises(vc.ParameterError) as direct:
            NormalLoading("load", PiecewiseLinear(*map(tuple, zip(*history))))
        assert str(from_case.value) == str(direct.value) and direct.value.key == "normal.history"


def test_a_history_of_numpy_arrays_is_checked_as_one_of_tuples() -> None:
    """Times and values given as numpy arrays (a scripted history, np.linspace) are checked as
    tuples are: accepted when valid (a held value of one point too), refused naming the key."""
    for times, values in (((0.0, 2e-4), (0.1, 0.15)), ((0.0,), (0.15,))):
        as_arrays = NormalLoading("load", PiecewiseLinear(np.array(times), np.array(values)))
        assert as_arrays.history(1e-4) == NormalLoading("load", PiecewiseLinear(times, values)).history(1e-4)
    with pytest.raises(vc.ParameterError) as info:
        NormalLoading("load", PiecewiseLinear(np.array([0.0, 3e-4, 1e-4]), np.array([0.1, 0.15, 0.0])))
    assert info.value.key == "normal.history" and "strictly increasing" in info.value.message
    with pytest.raises(vc.ParameterError) as info:
        NormalLoading("load", PiecewiseLinear(np.array([]), np.array([])))
    assert info.value.key == "normal.history"
