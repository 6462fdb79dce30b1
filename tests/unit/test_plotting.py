"""Figures read saved results: the one profile along y = 0 and the phase labels, checked on the
data the figures actually draw."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from test_results import N, fake_records, make_problem  # tests/unit is on sys.path

from viscontact.plotting import phase_name, profile
from viscontact.plotting.result import profiles_figure
from viscontact.plotting.seed import frictional_figure
from viscontact.problem import PHASE_GROSS_SLIDING, PHASE_INDENTATION, PHASE_NAMES, PHASE_PARTIAL_SLIP
from viscontact.results import to_dataset

ROOT = Path(__file__).resolve().parents[2]


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


# --- what each figure shows (issue 13) ---------------------------------------------------------------
def _suptitle(fig) -> str:
    return fig._suptitle.get_text()


def test_every_result_figure_states_its_scales(result):
    from viscontact.plotting.result import contact_history_figure, pressure_maps_figure, tangential_loop_figure

    for fig in (profiles_figure(result), pressure_maps_figure(result), contact_history_figure(result),
                tangential_loop_figure(result)):
        title = _suptitle(fig)
        assert title.startswith("fake: ") and "a0 = 588.7 µm" in title and "p0 = 0.2067 MPa" in title \
            and "τ = 10 ms" in title, title


def test_a_held_load_gets_no_panel_and_creep_is_drawn_with_lee_radok(tmp_path):
    """A creep run (held load, no sliding): panels for the contact radius and the approach only, each
    with Lee & Radok's curve for the result's own material and times."""
    from vc_testing import SEED_LOAD, SEED_RADIUS, seed_material, sphere_problem

    from viscontact.api import run
    from viscontact.plotting.result import contact_history_figure
    from viscontact.reference import lee_radok_creep

    problem = sphere_problem(seed_material(), 16, 1.6e-3, t_end=0.01, dt=2.5e-3, scheme="linear", title="creep")
    ds = run(problem)
    ds.attrs["case"] = '[material]\ntype = "zener"\n'  # what the case text says (a Problem has none)
    fig = contact_history_figure(ds)
    assert [ax.get_ylabel() for ax in fig.axes] == ["contact radius √(A/π), a / a0", "approach δ_z [µm]"]
    assert "(load held)" in _suptitle(fig)
    reference = lee_radok_creep(SEED_LOAD, SEED_RADIUS, seed_material(), ds["t"].values)
    tau = ds.attrs["retardation_time"]
    for ax, expected in zip(fig.axes, (reference.radius / ds.attrs["a0"], reference.approach * 1e6)):
        simulated, lee_radok = ax.get_lines()
        assert lee_radok.get_label() == "Lee & Radok (1960)"
        np.testing.assert_allclose(lee_radok.get_xdata(), ds["t"].values / tau)
        np.testing.assert_allclose(lee_radok.get_ydata(), expected, rtol=1e-12)
        # the run follows it (a coarse 16 x 16 grid: the radius is a count of cells)
        np.testing.assert_allclose(simulated.get_ydata(), expected, rtol=0.25)


def test_a_steady_state_is_drawn_as_one_state(tmp_path):
    from viscontact.api import run_steady
    from viscontact.case import load_case
    from viscontact.plotting import plot_result

    case = load_case(ROOT / "cases" / "seed_table1_v0.8.toml").with_overrides({"grid.n": 16})
    ds = run_steady(case)
    paths = plot_result(ds, tmp_path, fmt="svg")
    assert sorted(p.name for p in paths) == ["pressure_maps.svg", "pressure_profiles.svg"]  # no time histories
    fig = profiles_figure(ds)
    (line,) = fig.axes[0].get_lines()
    assert line.get_label().startswith("steady state at v = 0.0471 m/s") and "τ =" in _suptitle(fig)
    assert "t/τ" not in line.get_label() and "t/τ" not in _suptitle(fig)


def test_speed_curve_panels_against_deborah_number_and_speed(result):
    from viscontact.plotting.result import speed_curve_figure
    from viscontact.results import sweep_dataset

    problem = make_problem()
    sweep = sweep_dataset(fake_records(problem)[:3], [0.01, 0.1, 1.0], problem)
    fig = speed_curve_figure(sweep)
    panels = [ax for ax in fig.axes if ax.get_ylabel()]
    assert [ax.get_ylabel().split(" ")[0] for ax in panels] == ["μ_app", "peak", "contact", "contact"]
    np.testing.assert_allclose(panels[0].get_lines()[0].get_xdata(), sweep["deborah"].values)
    tops = [child.get_xlabel() for ax in panels for child in ax.child_axes]
    assert tops == ["sliding speed v [m/s]"] * 2                                # the top axes of the upper row


@pytest.mark.parametrize("args, key", [(["--format", "gif"], None), (["--dpi", "5"], "--dpi"),
                                       (["--times", "0,1"], "--times")])
def test_plot_options_are_checked_in_one_line(tmp_path, capsys, result, args, key):
    from viscontact import cli
    from viscontact.results import write_netcdf

    write_netcdf(result, tmp_path / "r.nc")
    if key is None:  # argparse refuses a format it does not know (exit 2, usage line)
        with pytest.raises(SystemExit) as info:
            cli.main(["plot", str(tmp_path / "r.nc"), "--out", str(tmp_path / "figs"), *args])
        assert info.value.code == 2
        return
    assert cli.main(["plot", str(tmp_path / "r.nc"), "--out", str(tmp_path / "figs"), *args]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"viscontact: error: {key}: ")
    assert not (tmp_path / "figs").exists()


def test_plot_maps_at_chosen_times_in_pdf(tmp_path, capsys, result):
    from viscontact import cli
    from viscontact.results import write_netcdf

    write_netcdf(result, tmp_path / "r.nc")
    assert cli.main(["plot", str(tmp_path / "r.nc"), "--out", str(tmp_path / "figs"), "--times", "0.001,0.003",
                     "--format", "pdf", "--dpi", "72"]) == 0
    written = sorted(Path(p).name for p in capsys.readouterr().out.split())
    assert "pressure_maps.pdf" in written and "stick_map.pdf" in written and "pressure.gif" in written
    assert (tmp_path / "figs" / "pressure_maps.pdf").read_bytes().startswith(b"%PDF")
