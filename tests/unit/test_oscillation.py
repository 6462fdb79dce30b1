"""``[normal] oscillation = {mean, amplitude, frequency, cycles}``: a sine about a mean, turned into the
piecewise-linear normal history (issue 33 item 3), instead of a table typed by hand."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from viscontact.errors import ParameterError
from viscontact.io.case import Case, load_case

ROOT = Path(__file__).resolve().parents[2]
CREEP = ROOT / "cases" / "creep_indentation.toml"


def _oscillating(**oscillation) -> Case:
    return load_case(CREEP).with_overrides({"normal.oscillation": oscillation})


def test_an_oscillation_is_the_sampled_sine_with_its_peaks_on_points():
    case = _oscillating(mean=0.1, amplitude=0.05, frequency=100.0, cycles=2)
    history = case.to_problem().normal.history
    times, values = np.array(history.times), np.array(history.values)
    assert len(times) == 2 * 64 + 1 and times[-1] == pytest.approx(0.02)
    np.testing.assert_allclose(values, 0.1 + 0.05 * np.sin(2 * np.pi * 100.0 * times), rtol=0, atol=1e-15)
    assert values.max() == 0.1 + 0.05 and values.min() == 0.1 - 0.05  # the peaks and troughs exactly
    assert history(0.05) == values[-1] == pytest.approx(0.1)  # then held
    assert case.normal.history is None and case.normal.value is None  # value and history dropped


def test_an_oscillation_is_checked_like_a_history():
    with pytest.raises(ParameterError, match="^normal.oscillation.points_per_cycle"):
        _oscillating(mean=0.1, amplitude=0.05, frequency=100.0, cycles=2, points_per_cycle=6)
    with pytest.raises(ParameterError, match="^normal.oscillation.frequency"):
        _oscillating(mean=0.1, amplitude=0.05, frequency=0.0, cycles=2)
    with pytest.raises(ParameterError, match=r"^normal.history: values must be >= 0"):
        _oscillating(mean=0.1, amplitude=0.2, frequency=100.0, cycles=2).to_problem()  # no [adhesion]
    both = load_case(CREEP).with_overrides({"normal.oscillation": {"mean": 0.1, "amplitude": 0.05, "frequency": 100.0,
                                                                    "cycles": 2}})
    with pytest.raises(ParameterError, match="give exactly one of 'value'"):
        Case.from_toml_text(both.text.replace("[normal]\n", "[normal]\nhistory = [[0.0, 0.1]]\n", 1)
                            + "\n[normal.oscillation]\nmean = 0.1\namplitude = 0.05\nfrequency = 100.0\ncycles = 2\n")


@pytest.mark.filterwarnings("ignore::viscontact.ViscontactWarning")
def test_an_oscillating_load_runs_and_its_turning_points_are_recorded():
    import viscontact as vc

    case = _oscillating(mean=0.1, amplitude=0.05, frequency=500.0, cycles=1).with_overrides(
        {"grid.n": 32, "time.t_end": 2e-3, "time.dt": 1.25e-4})
    ds = vc.run(case)
    t = ds["t"].values
    assert np.isclose(t, 5e-4).any() and np.isclose(t, 1.5e-3).any()  # the peak and the trough
    load = ds["load"].values
    assert load.max() == pytest.approx(0.15, rel=1e-6) and load.min() == pytest.approx(0.05, rel=1e-6)
