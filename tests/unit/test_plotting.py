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
from viscontact.problem.problem import (
    PHASE_GROSS_SLIDING,
    PHASE_INDENTATION,
    PHASE_NAMES,
    PHASE_PARTIAL_SLIP,
    PHASE_ROLLING,
)
from viscontact.io.results import to_dataset

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(autouse=True)
def _close_figures():
    """The figures a test draws are closed after it (pyplot keeps them open)."""
    yield
    from viscontact.plotting import pyplot

    pyplot().close("all")


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
    assert [phase_name(c) for c in (PHASE_INDENTATION, PHASE_PARTIAL_SLIP, PHASE_GROSS_SLIDING, PHASE_ROLLING)] == \
        ["indentation", "partial slip", "gross sliding", "rolling"]
    assert set(PHASE_NAMES) == {PHASE_INDENTATION, PHASE_PARTIAL_SLIP, PHASE_GROSS_SLIDING, PHASE_ROLLING}


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


def test_the_tangential_loop_starts_at_the_first_contact(result):
    """A normal history from zero touches after the indenter has moved (delta_x = rate t): Q is drawn
    against delta_x since the first record in contact, the records before it left out."""
    from viscontact.plotting.result import tangential_loop_figure

    ds = result.copy(deep=True)
    ds["contact_area"].values[:2] = 0.0
    ds["friction_force"].values[:] = [0.0, 0.0, 0.002, 0.004, 0.006]
    x, y = tangential_loop_figure(ds).axes[0].lines[0].get_data()
    delta_x = ds["delta_x"].values
    np.testing.assert_allclose(x, (delta_x[2:] - delta_x[2]) * 1e6)
    np.testing.assert_allclose(y, ds["friction_force"].values[2:] / (0.3 * float(ds["load"].max())))


def test_a_held_load_gets_no_panel_and_creep_is_drawn_with_lee_radok(tmp_path):
    """A creep run (held load, no sliding): panels for the contact radius and the approach only, each
    with Lee & Radok's curve for the result's own material and times."""
    from vc_testing import SEED_LOAD, SEED_RADIUS, seed_material, sphere_problem

    from viscontact.running.api import run
    from viscontact.plotting.result import contact_history_figure
    from viscontact.physics.reference import lee_radok_creep

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
    from viscontact.running.api import run_steady
    from viscontact.io.case import load_case
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
    from viscontact.io.results import sweep_dataset

    problem = make_problem()
    sweep = sweep_dataset(fake_records(problem)[:3], [0.01, 0.1, 1.0], problem)
    fig = speed_curve_figure(sweep)
    panels = [ax for ax in fig.axes if ax.get_ylabel()]
    assert [ax.get_ylabel().split(" ")[0] for ax in panels] == ["μ_app", "peak", "contact", "contact"]
    np.testing.assert_allclose(panels[0].get_lines()[0].get_xdata(), sweep["deborah"].values)
    tops = [child.get_xlabel() for ax in panels for child in ax.child_axes]
    assert tops == ["sliding speed v [m/s]"] * 2                                # the top axes of the upper row


@pytest.mark.parametrize("args, key", [(["--format", "gif"], "--format"), (["--dpi", "5"], "--dpi"),
                                       (["--times", "-1,1"], "--times")])  # t = 0 is taken (issue 33)
def test_plot_options_are_checked_in_one_line(tmp_path, capsys, result, args, key):
    from viscontact import cli
    from viscontact.io.netcdf import write_netcdf

    write_netcdf(result, tmp_path / "r.nc")
    assert cli.main(["plot", str(tmp_path / "r.nc"), "--out", str(tmp_path / "figs"), *args]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"viscontact: error: {key}: ")
    assert not (tmp_path / "figs").exists()


def test_plot_maps_at_chosen_times_in_pdf(tmp_path, capsys, result):
    from viscontact import cli
    from viscontact.io.netcdf import write_netcdf

    write_netcdf(result, tmp_path / "r.nc")
    assert cli.main(["plot", str(tmp_path / "r.nc"), "--out", str(tmp_path / "figs"), "--times", "0.001,0.003",
                     "--format", "pdf", "--dpi", "72"]) == 0
    written = sorted(Path(p).name for p in capsys.readouterr().out.split())
    assert "pressure_maps.pdf" in written and "stick_map.pdf" in written and "pressure.gif" in written
    assert (tmp_path / "figs" / "pressure_maps.pdf").read_bytes().startswith(b"%PDF")


# --- rough contact on a periodic cell (issue 11, items 4 and 5) --------------------------------------
@pytest.fixture(scope="module")
def rough(tmp_path_factory):
    """The shipped rough case on a 32² period, to 7 τ: partial slip, then gross sliding from 5 τ,
    saved and reopened (figures read saved results)."""
    import warnings

    from viscontact.running.api import run
    from viscontact.io.case import load_case
    from viscontact.errors import ViscontactWarning
    from viscontact.io.netcdf import open_result, write_netcdf
    from viscontact.io.shipped import shipped_case

    case = load_case(shipped_case("rough_periodic_sliding")).with_overrides({"grid.n": 32, "time.t_end": 0.07})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ViscontactWarning)  # coarse grid and time step: a preview
        ds = run(case)
    path = write_netcdf(ds, tmp_path_factory.mktemp("rough") / "rough.nc")
    return open_result(path).load()


@pytest.fixture
def rough_result(rough):
    return rough.copy(deep=True)


def _panel(fig, ylabel: str):
    (ax,) = [ax for ax in fig.axes if ax.get_visible() and ax.get_ylabel() == ylabel]
    return ax


def test_rough_contact_figure_draws_the_result_histories(rough_result):
    from viscontact.plotting.result import is_rough, rough_contact_figure

    ds = rough_result
    assert is_rough(ds)
    fig = rough_contact_figure(ds)
    t = ds["t"].values / ds.attrs["retardation_time"]
    expected = {"real contact area fraction A_r / A_0 [-]": ds["contact_fraction"].values,
                "contact patches [-]": ds["contact_patches"].values,
                "mean gap [µm]": ds["mean_gap"].values * 1e6,
                "approach δ_z [µm]": ds["delta_z"].values * 1e6}
    for label, values in expected.items():
        line = _panel(fig, label).get_lines()[0]
        np.testing.assert_allclose(line.get_xdata(), t, rtol=1e-12)
        np.testing.assert_allclose(line.get_ydata(), values, rtol=1e-12)
    friction = _panel(fig, "friction coefficient [-]").get_lines()
    np.testing.assert_allclose(friction[0].get_ydata(), ds["mu_app"].values, rtol=1e-12)
    np.testing.assert_allclose(friction[1].get_ydata(), ds["friction_force"].values / ds["load"].values, rtol=1e-12)
    assert not [ax for ax in fig.axes if ax.get_ylabel() == "load W [N]"]         # the load is held
    gross = [line for line in friction if line.get_label() == "gross sliding"]
    assert gross and gross[0].get_xdata()[0] == pytest.approx(float(ds["t_gross_sliding"]) / 0.01)
    title = _suptitle(fig)
    assert "period L = 1 mm" in title and "p̄ = W/L² = 10 kPa" in title and "τ = 10 ms" in title, title
    assert "(load held)" in title and "a0" not in title                       # no Hertz scale on a period
    # the run itself went from partial slip to gross sliding with several patches: the figure is not empty
    assert ds["contact_patches"].values.max() > 1 and 0 < np.nanmin(ds["contact_fraction"].values) < 1


def test_maps_of_a_periodic_result_are_drawn_over_the_period(rough_result):
    """Pressure and stick/slip maps at chosen times: the result's fields, the period [-w, w)² as the
    axes, wrapped around when the surface sits at a sub-cell offset."""
    from viscontact.plotting.base import contact_state
    from viscontact.plotting.result import pressure_maps_figure, stick_maps_figure

    ds = rough_result
    w = ds.attrs["grid_half_width"]
    dx = 2 * w / ds.attrs["grid_n"]
    times = [0.01, 0.04, 0.06]
    picks = [int(np.argmin(np.abs(ds["t"].values - t))) for t in times]
    for draw, values in ((pressure_maps_figure, lambda k: ds["pressure"].values[k] / 1e6),
                         (stick_maps_figure, lambda k: contact_state(ds, k))):
        fig = draw(ds, times)
        axes = [ax for ax in fig.axes if ax.images]
        assert len(axes) == len(times)
        for ax, k in zip(axes, picks):
            (image,) = ax.images
            data = np.asarray(image.get_array())
            np.testing.assert_array_equal(data[:, :-1], values(k))
            np.testing.assert_array_equal(data[:, -1], values(k)[:, 0])      # the period wraps around
            np.testing.assert_allclose(ax.get_xlim(), (-w * 1e3, w * 1e3), rtol=1e-12)
            np.testing.assert_allclose(ax.get_ylim(), (-w * 1e3, w * 1e3), rtol=1e-12)
            # τ: the result's retardation time (the material's, computed from its Prony series: 0.01 s to round-off)
            assert ax.get_title().startswith(f"t/τ = {ds['t'].values[k] / ds.attrs['retardation_time']:.3g}")
        assert "period L = 1 mm" in _suptitle(fig)
    # a sub-cell frame offset (steps_per_cell > 1) moves the image, not the cell
    ds["frame_offset"].values[:] = 0.25 * dx
    fig = pressure_maps_figure(ds, times[:1])
    extent = fig.axes[0].images[0].get_extent()
    np.testing.assert_allclose(extent[:2], ((-w - 0.25 * dx) * 1e3, (w + 0.75 * dx) * 1e3), rtol=1e-12)
    np.testing.assert_allclose(fig.axes[0].get_xlim(), (-w * 1e3, w * 1e3), rtol=1e-12)


def test_plot_of_a_periodic_result_draws_the_rough_history_not_a_contact_radius(rough_result, tmp_path):
    from viscontact.plotting import plot_any
    from viscontact.plotting.result import is_rough

    names = sorted(p.name for p in plot_any(rough_result, tmp_path, fmt="svg"))
    assert names == ["friction.svg", "pressure.gif", "pressure_maps.svg", "pressure_profiles.svg",
                     "rough_contact.svg", "stick_map.svg", "tangential_loop.svg"]
    problem = make_problem()                  # a smooth sphere, one patch: no rough-contact figure
    assert not is_rough(to_dataset(fake_records(problem), problem))


def _creep_result(overrides: dict, material: str | None = None):
    """A 3-step creep run of the shipped case at 16^2 with ``overrides`` and, when given, its
    ``[material]`` table replaced by ``material`` in the case text (which the result keeps)."""
    import viscontact as vc
    from viscontact.io.case import Case

    text = (ROOT / "cases" / "creep_indentation.toml").read_text()
    if material is not None:
        start, end = text.index("[material]"), text.index("[indenter]")
        text = text[:start] + material + "\n" + text[end:]
    case = Case.from_toml_text(text, ROOT / "cases").with_overrides({"grid.n": 16, "time.t_end": 5e-4, **overrides})
    return vc.run(case), case


PRONY_WLF = """[material]
type = "prony"
g_inf = 0.193e6
g = [1.737e6]
tau = [0.05]
poisson_ratio = 0.3
temperature = 40.0
reference_temperature = 20.0
wlf_c1 = 17.44
wlf_c2 = 51.6
"""


def test_the_reference_material_of_a_result_has_the_runs_relaxation_times():
    """A typed Prony material with a WLF shift: the Lee & Radok reference needs the shifted times (it
    drew the unshifted ones, a creep about 3 times too slow); a nu(t) or layered body has no such
    reference."""
    from viscontact.plotting.result import material_of

    ds, case = _creep_result({}, PRONY_WLF)
    run = case.to_problem().material
    assert ds.attrs["a_T"] < 1e-4
    t = np.array([0.0, 1e-7, 1e-6, 1e-5])
    older = ds.copy()
    for key in ("relaxation_moduli", "relaxation_times"):  # a result written before they were kept
        del older.attrs[key]
    for result in (ds, older):
        rebuilt = material_of(result)
        assert rebuilt is not None
        np.testing.assert_allclose(rebuilt.relaxation_modulus(t), run.relaxation_modulus(t), rtol=1e-12)
    assert material_of(_creep_result({"material.bulk_modulus": 5e6, "material.poisson_ratio": None})[0]) is None
    assert material_of(_creep_result({"layer.thickness": 1e-3})[0]) is None


def test_a_result_keeps_the_prony_terms_of_a_material_file(tmp_path):
    """A material read from a Prony table (here PMMA's, tensile, 11 terms) is kept in the result's
    attributes, so the result holds its material when the table is edited or lost."""
    import shutil

    import viscontact as vc
    from viscontact.plotting.result import material_of

    shutil.copytree(ROOT / "cases" / "materials", tmp_path / "materials")
    shutil.copy(ROOT / "cases" / "pmma_master_curve.toml", tmp_path)
    case = vc.load_case(tmp_path / "pmma_master_curve.toml").with_overrides({"grid.n": 16, "time.t_end": 9.765625})
    ds, run = vc.run(case), case.to_problem().material
    (tmp_path / "materials" / "pmma_schapery1962.csv").unlink()
    assert len(ds.attrs["relaxation_times"]) == 11
    t = np.logspace(-3, 9, 13)
    np.testing.assert_allclose(material_of(ds).relaxation_modulus(t), run.relaxation_modulus(t), rtol=1e-12)


# --- the docs/figures review ---------------------------------------------------------------------------
@pytest.fixture(scope="module")
def subsurface():
    """The shipped subsurface case at 16^2 to 0.006 s, stresses at two recorded times."""
    import viscontact as vc

    case = vc.load_case(ROOT / "cases" / "creep_subsurface_stress.toml").with_overrides(
        {"grid.n": 16, "time.t_end": 0.006, "output.subsurface_times": [0.0, 0.006]})
    return vc.run(case)


def test_subsurface_maps_have_depth_downwards_one_row_per_recorded_time_and_a_title(subsurface):
    """The two panels share the y axis: each inverted it once and the two inversions cancelled
    (the surface was drawn at the bottom); only the last time was drawn, with no title. The maps span
    the depths computed, no more: the bands of the first and last depths reached half a gap beyond
    them (above the surface, below the deepest depth)."""
    from viscontact.plotting.result import subsurface_figure

    ds = subsurface
    fig = subsurface_figure(ds)
    maps = [ax for ax in fig.axes if ax.collections and ax.get_label() != "<colorbar>"]
    assert len(maps) == 2 * ds.sizes["t_sub"] == 4
    a0, p0 = ds.attrs["a0"], ds.attrs["p0"]
    for i, ax in enumerate(maps):
        k, name = divmod(i, 2)
        assert ax.yaxis_inverted(), ax.get_title()                       # depth downwards
        bottom, top = ax.get_ylim()
        z = ds["z"].values / a0
        assert top == z[0] == 0.0 and bottom == z[-1]                      # the surface z = 0 on top
        corners = ax.collections[0].get_coordinates()                    # the mesh: the depths computed
        assert corners[..., 1].min() == z[0] and corners[..., 1].max() == z[-1]
        assert ax.get_title().startswith(f"{('von Mises', 'maximum shear')[name]}, t/τ = "
                                         f"{ds['t_sub'].values[k] / 0.01:.3g}:")
        expected = ds[("von_mises_stress", "max_shear_stress")[name]].values[k] / p0
        np.testing.assert_allclose(np.asarray(ax.collections[0].get_array()).reshape(expected.shape), expected,
                                   rtol=1e-12)
    title = _suptitle(fig)
    assert title.startswith("Subsurface stresses under a Zener") and "a0 = 588.7 µm" in title and "τ = 10 ms" in title


def test_subsurface_maps_draw_depths_listed_in_any_order_downwards(subsurface):
    """output.subsurface_depths in any order (here the shipped case's, reversed): the maps are those
    of the depths in increasing order, from the first to the last."""
    from viscontact.plotting.result import subsurface_figure

    ds, a0 = subsurface, subsurface.attrs["a0"]
    fig = subsurface_figure(ds.isel(z=slice(None, None, -1)))
    ax = next(ax for ax in fig.axes if ax.collections and ax.get_label() != "<colorbar>")
    assert ax.get_ylim() == (ds["z"].values[-1] / a0, 0.0)
    np.testing.assert_allclose(np.asarray(ax.collections[0].get_array()).reshape(ds.sizes["z"], -1),
                               ds["von_mises_stress"].values[0] / ds.attrs["p0"], rtol=1e-12)


def test_tangential_loop_divides_by_the_load_of_each_step_under_a_held_approach(result):
    """Under displacement control the load relaxes: Q was divided by mu_f max(W) = mu_f W(0) and the
    curve levelled at W(t)/W(0) (about 0.1 for the seed's Table 3 case 4) at the onset of gross
    sliding, where Q = mu_f W(t). Now Q(t)/(mu_f W(t)) reaches 1 there; a step without load has no
    ratio; the elastic Cattaneo-Mindlin curve of the held approach is drawn (any G gives it)."""
    from viscontact.plotting.result import tangential_loop_figure
    from viscontact.physics.reference import cattaneo_mindlin, hertz_from_approach

    ds = result
    mu, load = ds.attrs["friction_coefficient"], np.array([0.0, 0.15, 0.06, 0.02, 0.015])
    ds.attrs["normal_control"] = "displacement"
    ds["delta_z"].values[:] = 3e-5
    ds["load"].values[:] = load
    ds["friction_force"].values[:] = [0.0, 0.3 * mu * 0.15, 0.8 * mu * 0.06, mu * 0.02, mu * 0.015]
    assert list(ds["phase"].values[3:]) == [PHASE_GROSS_SLIDING] * 2
    fig = tangential_loop_figure(ds)
    (ax,) = fig.axes
    simulated, reference = ax.get_lines()
    ratio = simulated.get_ydata()
    assert np.isnan(ratio[0])                                               # W = 0: no ratio
    np.testing.assert_allclose(ratio[1:], [0.3, 0.8, 1.0, 1.0], rtol=1e-12)  # 1 in gross sliding
    assert ax.get_ylabel() == "Q(t) / (μ_f W(t))" and "W(t)" in ax.get_title()
    assert reference.get_label() == "Cattaneo-Mindlin, elastic at the held approach (any G)"
    nu, R = ds.attrs["poisson_ratio"], ds.attrs["radius"]
    for g in (ds.attrs["shear_modulus_instantaneous"], ds.attrs["shear_modulus_long_term"]):
        cm = cattaneo_mindlin(hertz_from_approach(3e-5, R, g, nu).load, R, mu, g, nu)
        d = reference.get_xdata() * 1e-6
        np.testing.assert_allclose(reference.get_ydata(), cm.force(d) / (mu * cm.load), rtol=1e-9, atol=1e-12)
    assert "(here 0.3)" in ax.get_legend().get_title().get_text()              # exact only at nu = 0.5
    # a held load: Q / (mu_f W), G(0) and G(inf) under that load
    ds.attrs["normal_control"] = "load"
    ds["load"].values[:] = 0.15
    ax = tangential_loop_figure(ds).axes[0]
    assert ax.get_ylabel() == "Q / (μ_f W)"
    assert [line.get_label() for line in ax.get_lines()] == \
        ["viscontact", "Cattaneo-Mindlin, elastic G(0)", "Cattaneo-Mindlin, elastic G(∞)"]


def test_fig4_labels_each_speed_in_mm_per_s_and_in_the_a0_of_its_axes(result):
    """The seed's cases give v = 1.2 a0/tau with the a0 of 0.15 N (588.7 um); panel (c) said
    "v tau/a0 = 1.21" with the a0 of its 0.148 N without saying which: the speed is given in mm/s
    too, and v tau/a0 is the one of the a0 in the figure's title."""
    from viscontact.plotting.seed import profiles_figure as fig4

    fig = fig4({"case": result}, (0.0, 0.001), "test")
    expected = 0.05 * 0.01 / result.attrs["a0"]                # the fake run: 50 mm/s, tau = 10 ms
    assert fig.axes[0].get_title() == f"(a) v = 50 mm/s = {expected:.2f} a0/τ"
    assert fig.axes[1].get_legend_handles_labels()[1] == [f"v = 50 mm/s = {expected:.2f} a0/τ"]
    assert "a0 = 588.7 µm" in _suptitle(fig)


def _extent(fig, artist):
    return artist.get_window_extent(fig.canvas.get_renderer())


def test_the_pressure_animation_title_fits_its_frames(result):
    """The frames are saved at the figure's size (no tight bounding box): a long title ran off both
    sides ("stomer on a periodic ... pressu"). It is wrapped to the width and sits above the map's."""
    from viscontact.plotting.result import pressure_animation_figure

    result.attrs["title"] = "Elastomer on a periodic self-affine surface: partial slip to gross sliding"
    fig, frame, count = pressure_animation_figure(result)
    assert count == result.sizes["t"]
    frame(count - 1)
    title, (ax, _) = fig._suptitle, fig.axes
    box, page = _extent(fig, title), fig.bbox
    assert page.x0 <= box.x0 and box.x1 <= page.x1 and box.y1 <= page.y1, (box, page)
    assert _extent(fig, ax.title).y1 <= box.y0                                 # the frame's t/tau below it
    assert title.get_text().replace("\n", " ").startswith(result.attrs["title"] + ": pressure")


def test_the_material_figure_labels_do_not_overlap():
    """J(t)'s axis label ran into the middle panel's "[Pa]" (2 px apart at 100 dpi), the title into
    the middle panel's (3.7 px)."""
    from viscontact.physics.materials import Material
    from viscontact.plotting.material import material_figure
    from viscontact.io.results import material_dataset

    fig = material_figure(material_dataset(Material.zener(1.93e6, 0.193e6, 0.01, 0.3)))
    fig.canvas.draw()
    first, middle, last, twin = fig.axes
    assert middle.get_ylabel() == "G', G'' [Pa]"
    assert _extent(fig, middle.yaxis.label).x0 - _extent(fig, twin.yaxis.label).x1 >= 0.2 * fig.dpi
    for ax in (first, middle, last):
        assert _extent(fig, fig._suptitle).y0 - _extent(fig, ax.title).y1 >= 0.05 * fig.dpi


def test_tau_is_given_in_a_unit_that_suits_it_and_said_to_be_the_shortest(result):
    """The PU elastomer's title said "τ = 0.0001368 ms" and its Deborah number used the shortest of
    10 retardation times without saying so."""
    from viscontact.plotting.base import format_duration, scales_line
    from viscontact.plotting.result import speed_curve_figure
    from viscontact.io.results import sweep_dataset

    assert [format_duration(t) for t in (0.01, 1.368063495551196e-07, 2.5, 3600.0, 4e-6)] == \
        ["10 ms", "136.8 ns", "2.5 s", "3600 s", "4 µs"]
    assert scales_line(result).endswith("τ = 10 ms")                          # one retardation time
    problem = make_problem()
    sweep = sweep_dataset(fake_records(problem)[:3], [0.01, 0.1, 1.0], problem)
    sweep.attrs.update(retardation_time=1.368063495551196e-07, relaxation_times=np.logspace(-7, 2, 10))
    fig = speed_curve_figure(sweep)
    assert _suptitle(fig).endswith("τ = 136.8 ns (the shortest of 10 retardation times)")
    assert fig.axes[2].get_xlabel() == "Deborah number v τ / a0, τ the shortest retardation time"


def test_an_elastic_material_is_compared_with_hertz(tmp_path):
    from vc_testing import SEED_G0, SEED_NU, sphere_problem

    from viscontact.running.api import run
    from viscontact.physics.materials import Material
    from viscontact.plotting.result import contact_history_figure

    problem = sphere_problem(Material.elastic(SEED_G0, SEED_NU), 16, 1.6e-3, control="displacement", value=3e-5,
                             t_end=2e-3, dt=1e-3, title="elastic")
    ds = run(problem)
    ds.attrs["case"] = '[material]\ntype = "elastic"\n'
    labels = [line.get_label() for ax in contact_history_figure(ds).axes for line in ax.get_lines()]
    assert "Hertz (1882)" in labels and "Lee & Radok (1960)" not in labels


def test_the_coulomb_bound_is_drawn_over_the_shear_it_bounds(result):
    """In full slip q_x = mu_f p: the dotted mu_f p of a record lay under its own q_x and the later
    records' (the fake result: q = 0.3 p, mu_f = 0.3)."""
    fig = profiles_figure(result)
    shear = fig.axes[1].get_lines()
    solid = [line for line in shear if line.get_linestyle() == "-"]
    dotted = [line for line in shear if line.get_linestyle() == ":"]
    assert len(solid) == len(dotted) == result.sizes["t"]
    assert min(line.get_zorder() for line in dotted) > max(line.get_zorder() for line in solid)
    assert all(line.get_color() == "k" for line in dotted) and "black dotted: μ_f p" in fig.axes[1].get_title()


def _plot_one_line(capsys, path: Path, out: Path) -> str:
    from viscontact import cli

    assert cli.main(["plot", str(path), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"viscontact: error: {path}: "), err
    assert not out.exists()  # refused before any figure
    return err[0]


def test_plot_of_a_run_killed_before_its_first_record_is_one_line(tmp_path, capsys):
    """The streamed file a kill -9 leaves before the first record is a valid result without a
    record: `plot` says so in one line (it raised ValueError: max() arg is an empty sequence)."""
    from viscontact.io.streaming import ResultStream

    partial = tmp_path / "r.nc.partial"
    ResultStream.create(partial, make_problem(), case_text="title = 'x'", require_space=False).close()
    assert "holds no record" in _plot_one_line(capsys, partial, tmp_path / "figs")


@pytest.mark.parametrize("drop", ["contact_area", "delta_x"])
def test_plot_of_a_result_without_a_variable_its_figures_draw_is_one_line(tmp_path, capsys, result, drop):
    """A result rewritten without a history its figures read names it (it raised KeyError)."""
    from viscontact.io.netcdf import write_netcdf

    write_netcdf(result.drop_vars(drop), tmp_path / "r.nc")
    assert f"has no variable '{drop}'" in _plot_one_line(capsys, tmp_path / "r.nc", tmp_path / "figs")


def test_plot_of_a_speed_curve_without_mu_app_is_one_line(tmp_path, capsys, result):
    from viscontact.io.results import sweep_dataset
    from viscontact.io.netcdf import write_netcdf

    problem = make_problem("frictionless_sliding")
    curve = sweep_dataset(fake_records(problem, (0, 1)), [0.01, 0.1], problem)
    write_netcdf(curve.drop_vars("mu_app"), tmp_path / "c.nc")
    assert "has no variable 'mu_app'" in _plot_one_line(capsys, tmp_path / "c.nc", tmp_path / "figs")


def test_plot_of_an_incomplete_run_warns_that_its_figures_stop_early(tmp_path, capsys, result):
    """A run stopped half way (complete = 0) was drawn without a word: its friction and contact
    histories could pass for a whole run's."""
    from viscontact import cli
    from viscontact.io.netcdf import write_netcdf

    stopped = result.copy()
    stopped.attrs.update(complete=0, stopped_by="SIGINT")
    write_netcdf(stopped, tmp_path / "r.nc")
    assert cli.main(["plot", str(tmp_path / "r.nc"), "--out", str(tmp_path / "figs")]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("viscontact: warning: ") and "incomplete run" in err[0]
    assert "SIGINT" in err[0] and f"t = {float(result['t'][-1]):.4g} s" in err[0]
    write_netcdf(result, tmp_path / "whole.nc")  # a complete one: no warning
    assert cli.main(["plot", str(tmp_path / "whole.nc"), "--out", str(tmp_path / "figs2")]) == 0
    assert not capsys.readouterr().err.strip()


def test_the_tangential_loop_of_a_reversing_history_draws_the_whole_path():
    """Fretting (a displacement history that reverses, the shipped case at 16^2 and one cycle): Q /
    (mu_f W) against the indenter's delta_x at every record, both signs (not clipped at delta_x >= 0
    nor at Q >= 0 as for a ramp), with the elastic Mindlin-Deresiewicz loops of G(0) and G(inf) at
    the run's amplitude, each closing at (+-delta_a, +-Q_a / (mu_f W))."""
    from viscontact.running.api import run
    from viscontact.io.case import load_case
    from viscontact.plotting.result import tangential_loop_figure
    from viscontact.physics.reference import cattaneo_mindlin

    ds = run(load_case(ROOT / "cases" / "fretting_zener.toml").with_overrides({"grid.n": 16, "time.t_end": 0.0125}))
    ax = tangential_loop_figure(ds).axes[0]
    x, y = ax.lines[0].get_data()
    np.testing.assert_allclose(x, ds["delta_x"].values * 1e6)
    np.testing.assert_allclose(y, ds["friction_force"].values / (0.3 * ds["load"].values))
    assert y.min() < -0.4 and y.max() > 0.4 and ax.get_ylim() == (-1.1, 1.1)
    references = [line for line in ax.lines if "Mindlin-Deresiewicz" in str(line.get_label())]
    assert [line.get_label() for line in references] == ["Mindlin-Deresiewicz, elastic G(0)",
                                                         "Mindlin-Deresiewicz, elastic G(∞)"]
    for line, g in zip(references, (1.93e6, 0.193e6)):
        q_a = float(cattaneo_mindlin(0.15, 0.01, 0.3, g, 0.5).force(8e-6)) / (0.3 * 0.15)
        rx, ry = line.get_data()
        assert rx[0] == pytest.approx(8.0) and rx[-1] == pytest.approx(8.0) and rx.min() == pytest.approx(-8.0)
        assert ry[0] == pytest.approx(q_a) and ry[-1] == pytest.approx(q_a) and ry.min() == pytest.approx(-q_a)
