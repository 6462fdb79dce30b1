"""Figures read saved results: the one profile along y = 0 and the phase labels, checked on the
data the figures actually draw."""
from __future__ import annotations

import numpy as np
import pytest
from test_results import N, fake_records, make_problem  # tests/unit is on sys.path

from viscontact.plotting import phase_name, profile
from viscontact.plotting.result import profiles_figure
from viscontact.plotting.seed import frictional_figure
from viscontact.problem import PHASE_GROSS_SLIDING, PHASE_INDENTATION, PHASE_NAMES, PHASE_PARTIAL_SLIP
from viscontact.results import to_dataset


@pytest.fixture
def result():
    """A partial-slip result whose fields vary with y and whose indenter sits off the grid centre."""
    problem = make_problem()
    ds = to_dataset(fake_records(problem), problem)
    ds["frame_offset"].values[:] = np.arange(ds.sizes["t"]) * 0.3 * problem.grid.spacing
    return ds


def test_profile_is_the_mean_of_the_rows_straddling_y0_in_the_indenter_frame(result):
    k = 3
    x, p = profile(result, "pressure", k)
    rows = result["pressure"].values[k]
    np.testing.assert_array_equal(p, 0.5 * (rows[N // 2 - 1] + rows[N // 2]))
    assert result["y"].values[N // 2 - 1] == -result["y"].values[N // 2]      # the two rows straddle y = 0
    np.testing.assert_allclose(x, result["x"].values - float(result["frame_offset"][k]), rtol=0, atol=1e-18)
    odd = result.isel(y=slice(0, N - 1))                                       # an odd grid: the middle row
    np.testing.assert_array_equal(profile(odd, "pressure", k)[1], odd["pressure"].values[k][(N - 1) // 2])


def test_result_figure_draws_that_profile(result):
    fig = profiles_figure(result)
    a0, p0 = result.attrs["a0"], result.attrs["p0"]
    lines = fig.axes[0].get_lines()
    assert len(lines) == result.sizes["t"]   # five records: each is drawn
    for k, line in enumerate(lines):
        x, p = profile(result, "pressure", k)
        np.testing.assert_allclose(line.get_xdata(), x / a0, rtol=1e-12)
        np.testing.assert_allclose(line.get_ydata(), p / p0, rtol=1e-12)


def test_phase_names_come_from_the_problem_constants():
    assert [phase_name(c) for c in (PHASE_INDENTATION, PHASE_PARTIAL_SLIP, PHASE_GROSS_SLIDING)] == \
        ["indentation", "partial slip", "gross sliding"]
    assert set(PHASE_NAMES) == {PHASE_INDENTATION, PHASE_PARTIAL_SLIP, PHASE_GROSS_SLIDING}


def test_frictional_figure_labels_each_curve_with_its_phase(result):
    result.attrs["retardation_time"] = 1e-3   # the records are 1 ms apart: t/tau = 0, 1, 2, 3, 4
    result["phase"].values[:] = [PHASE_INDENTATION, PHASE_PARTIAL_SLIP, PHASE_PARTIAL_SLIP,
                                 PHASE_GROSS_SLIDING, PHASE_GROSS_SLIDING]
    fig = frictional_figure({"case": result}, (0.0, 1.0, 3.0), "test", ("case",))
    shear_axes = fig.axes[0::2]
    labels = [ax.get_legend_handles_labels()[1][0] for ax in shear_axes]
    assert labels == ["case: q_x (indentation)", "case: q_x (partial slip)", "case: q_x (gross sliding)"]
