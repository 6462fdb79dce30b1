"""Figures ready for a paper (issue 33): per-map colour scales, a key on stick maps, no empty panel,
fretting cycles told apart with the energy each dissipates, short log-axis labels, titles that do
not repeat themselves."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from test_results import fake_records, make_problem  # tests/unit is on sys.path

from viscontact.io.results import energy_per_cycle, fretting_cycles, to_dataset


def test_a_cycle_runs_from_a_turning_point_to_the_second_after_it_and_its_energy_is_its_loop_area():
    s = np.linspace(0.0, 3.25, 131)  # a quarter cycle out, then three full ones, as the shipped fretting case
    x = np.interp(s, [0, 0.25, 0.75, 1.25, 1.75, 2.25, 2.75, 3.25], [0, 1, -1, 1, -1, 1, -1, 1])
    assert [(s[a], s[b]) for a, b in fretting_cycles(x)] == [(0.25, 1.25), (1.25, 2.25), (2.25, 3.25)]
    q = 2.0 * x + 0.5 * np.sign(np.gradient(x))  # a parallelogram 1 high, 2 wide: area 2 per cycle
    np.testing.assert_allclose(energy_per_cycle(x, q), 2.0, rtol=0.05)
    assert fretting_cycles(np.linspace(0, 1, 5)) == [] and fretting_cycles([0, 1, 0]) == []


def _scaled(problem, factors):
    records = fake_records(problem, (1,) * len(factors))
    return [dataclasses.replace(r, pressure=r.pressure * f) for r, f in zip(records, factors)]


def test_pressure_maps_share_a_scale_unless_their_peaks_differ_by_more_than_three_times():
    from viscontact.plotting.result import pressure_maps_figure

    problem = make_problem()
    for factors, own in (((1.0, 1.0, 0.9, 0.8), False), ((1.0, 0.2, 0.2, 0.2), True)):
        fig = pressure_maps_figure(to_dataset(_scaled(problem, factors), problem))
        tops = [ax.images[0].get_clim()[1] for ax in fig.axes if ax.images]
        bars = [ax for ax in fig.axes if ax.get_label() == "<colorbar>"]
        assert len(bars) == (4 if own else 1) and (len(set(tops)) == 4 if own else len(set(tops)) == 1)
        assert ("each map its own colour scale" if own else "one colour scale") in fig._suptitle.get_text()


def test_stick_maps_have_a_key_and_fretting_loops_a_colour_and_an_energy_per_cycle():
    from viscontact.plotting.result import stick_maps_figure, tangential_loop_figure

    problem = make_problem()
    records = [dataclasses.replace(r, delta_x=x) for r, x in
               zip(fake_records(problem, (1,) * 6), (0, 1e-6, 0, -1e-6, 0, 1e-6))]
    ds = to_dataset(records, problem)
    assert [t.get_text() for t in stick_maps_figure(ds).legends[0].get_texts()] == ["no contact", "slip", "stick"]
    ax = tangential_loop_figure(ds).axes[0]
    (cycle,) = [line for line in ax.lines if str(line.get_label()).startswith("cycle 1: ")]
    assert f"{float(ds['energy_per_cycle'][0]) * 1e6:.4g} µJ dissipated" in cycle.get_label()


def test_rough_contact_has_no_empty_panel_and_counts_patches_in_integers():
    from viscontact.plotting.result import _panel_grid

    for count in range(1, 8):
        fig, axes = _panel_grid(count)
        assert len(fig.axes) == count == len(axes) and all(ax.get_visible() for ax in fig.axes)


@pytest.mark.parametrize("title, expected", [
    ("Seed Table 1 / Fig. 4: frictionless sliding at v = 0.8 a0/tau, W = 0.148 N",
     "Seed Table 1 / Fig. 4: frictionless sliding, W = 0.148 N"),
    ("Sweep base: W = 0.148 N, frictionless sliding", "Sweep base: W = 0.148 N, frictionless sliding")])
def test_a_speed_curve_title_drops_the_one_speed_of_its_case(title, expected):
    from viscontact.plotting.result import without_speed

    assert without_speed(title) == expected


def test_log_tick_labels_of_less_than_a_decade_are_short():
    """The top axis of sweep_mu_app.png (v tau / a0 from 0.17 to 0.85) was labelled 2 x 10^-1,
    3 x 10^-1, 4 x 10^-1, 6 x 10^-1, running into each other."""
    from viscontact.plotting.base import compact_log_ticks, pyplot

    fig, ax = pyplot().subplots()
    ax.semilogx([0.17, 0.85], [0, 1])
    compact_log_ticks(ax)
    fig.canvas.draw()
    labels = [t.get_text() for t in ax.get_xticklabels(minor=True) if t.get_text()]
    assert labels and all(len(text) <= 4 for text in labels) and "0.2" in labels, labels
