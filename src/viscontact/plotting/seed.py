"""The seed's figures (Wang et al., Friction 2023, Figs. 4 and 6-10) drawn from saved results.

Each function takes the result Datasets of one figure, keyed by case name, and returns the
matplotlib Figure; :mod:`viscontact.reproduce` says which cases and times make which figure and
saves them. Profiles are :func:`~viscontact.plotting.base.profile` (y = 0, indenter coordinate)
normalised by each result's ``a0``/``p0``; times are t/τ with τ the result's ``retardation_time``.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from viscontact.plotting.base import (
    FigureFiles,
    Scales,
    draw_contact_maps,
    phase_name,
    profile,
    pyplot,
    set_title,
    time_index,
)
from viscontact.plotting.result import material_of

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["apparent_friction_figure", "frictional_figure", "material_figure", "profiles_figure",
           "stick_slip_map"]

Runs = Mapping[str, "xr.Dataset"]


def _tau(ds: xr.Dataset) -> float:
    return float(ds.attrs["retardation_time"])


def _at(ds: xr.Dataset, t_tau: float) -> int:
    """Index of the record nearest to t_tau [τ]."""
    return time_index(ds, t_tau * _tau(ds))


def _ratio(ds: xr.Dataset) -> float:
    return float(ds.attrs["shear_modulus_instantaneous"]) / float(ds.attrs["shear_modulus_long_term"])


def _short(name: str) -> str:
    return name.replace("seed_", "").replace("_", " ")


def _title(fig: Any, runs: Runs, title: str) -> None:
    """The figure's title and the scales (a0, p0, τ) of its first run, which the panels share."""
    ref = next(iter(runs.values()))
    set_title(fig, ref.assign_attrs(title=""), title)


def _profile_axes(n: int) -> tuple[Any, Any]:
    """``n`` profile panels sharing both axes, and one more panel for a time curve: in a row, or
    2 x 2 for four panels (Figs. 4, 6, 7: a row of four was 2805 x 654 px, its legends tiny)."""
    if n + 1 == 4:
        fig, grid = pyplot().subplots(2, 2, figsize=(10.5, 8.4))
        axes = grid.flatten()
    else:
        fig, axes = pyplot().subplots(1, n + 1, figsize=(4.7 * (n + 1), 4.4))
    for ax in axes[1:n]:
        ax.sharex(axes[0])
        ax.sharey(axes[0])
    return fig, axes


def _profiles_panel(ax: Any, ds: xr.Dataset, times_tau: Sequence[float], title: str) -> None:
    a0, p0 = float(ds.attrs["a0"]), float(ds.attrs["p0"])
    sc = Scales(ds)
    for t in times_tau:
        k = _at(ds, t)
        x, p = profile(ds, "pressure", k)
        ax.plot(x / a0, p / p0, label=sc.t_label(float(ds["t"].values[k])))
    ax.set(xlabel="x / a0", ylabel="p / p0", title=title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)


def _mu_panel(ax: Any, runs: Runs, labels: Mapping[str, str], title: str) -> None:
    for name, ds in runs.items():
        ax.plot(ds["t"].values / _tau(ds), ds["mu_app"].values, label=labels[name])
    ax.set(xlabel="t / τ", ylabel="μ_app = F_T / W", title=title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)


def profiles_figure(runs: Runs, times_tau: Sequence[float], title: str) -> Any:
    """Fig. 4: p/p0 along y = 0 at ``times_tau`` for each speed, and μ_app(t/τ) of all. Each speed
    is labelled in mm/s and as v τ/a0 with the a0 of its result, the one of the axes and the title
    (the seed's cases give their speeds in units of the a0 of 0.15 N: 1.2 a0/τ there is 1.21 a0/τ
    with the a0 of their 0.148 N)."""
    fig, axes = _profile_axes(len(runs))
    labels = {}
    for i, (name, ds) in enumerate(runs.items()):
        speed = float(ds.attrs["sliding_speed"])
        labels[name] = f"v = {speed * 1e3:.4g} mm/s = {speed * _tau(ds) / float(ds.attrs['a0']):.2f} a0/τ"
        _profiles_panel(axes[i], ds, times_tau, f"({'abcdefgh'[i]}) {labels[name]}")
    _mu_panel(axes[-1], runs, labels, f"({'abcdefgh'[len(runs)]}) apparent friction")
    _title(fig, runs, title)
    fig.tight_layout()
    return fig


def material_figure(runs: Runs, times_tau: Sequence[float], title: str, function: str) -> Any:
    """Figs. 6 and 7: p/p0 along y = 0 at ``times_tau`` for each material, and the material function
    ``"relaxation"`` (G(t)/G(0)) or ``"creep"`` (J(t) G(0)) of the materials of the results
    (:func:`~viscontact.plotting.result.material_of`; a Zener from the attributes otherwise)."""
    from viscontact.physics.materials import Material

    fig, axes = _profile_axes(len(runs))
    t_curve = np.linspace(0.0, 4.0, 200)
    for i, (name, ds) in enumerate(runs.items()):
        ratio = _ratio(ds)
        _profiles_panel(axes[i], ds, times_tau, f"({'abcdefgh'[i]}) G(0)/G(∞) = {ratio:g}")
        g0, ginf = float(ds.attrs["shear_modulus_instantaneous"]), float(ds.attrs["shear_modulus_long_term"])
        mat = material_of(ds) or Material.zener(g0, ginf, _tau(ds), float(ds.attrs["poisson_ratio"]))
        t = t_curve * _tau(ds)
        curve = mat.relaxation_modulus(t) / g0 if function == "relaxation" else mat.creep_compliance(t) * g0
        axes[-1].plot(t_curve, curve, label=f"G(0)/G(∞) = {ratio:g}")
    ylabel, panel = ("G(t) / G(0)", "relaxation modulus") if function == "relaxation" else \
        ("J(t) G(0)", "creep compliance")
    axes[-1].set(xlabel="t / τ", ylabel=ylabel, title=f"({'abcdefgh'[len(runs)]}) {panel}")
    axes[-1].grid(alpha=0.3)
    axes[-1].legend(fontsize=8)
    _title(fig, runs, title)
    fig.tight_layout()
    return fig


def apparent_friction_figure(runs: Runs, title: str) -> Any:
    """Fig. 8: μ_app(t/τ) under a held approach (cases ending in ``displacement``) | a held load."""
    fig, axes = pyplot().subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for ax, control, panel in ((axes[0], "displacement", "(a) stress relaxation (held approach)"),
                               (axes[1], "load", "(b) creep (held load)")):
        sel = {k: v for k, v in runs.items() if k.endswith(control)}
        _mu_panel(ax, sel, {k: f"G(0)/G(∞) = {_ratio(v):g}" for k, v in sel.items()}, panel)
    _title(fig, runs, title)
    fig.tight_layout()
    return fig


def _shade_stick(ax: Any, x: np.ndarray, stick: np.ndarray, color: Any) -> None:
    """Shade the x intervals where ``stick`` is true."""
    if not np.any(stick):
        return
    dx = x[1] - x[0]
    edges = np.flatnonzero(np.diff(np.concatenate([[0], stick.astype(int), [0]])))
    for start, stop in zip(edges[::2], edges[1::2]):
        ax.axvspan(x[start] - dx / 2, x[stop - 1] + dx / 2, color=color, alpha=0.15, lw=0)


def frictional_figure(runs: Runs, times_tau: Sequence[float], title: str, shear_cases: Sequence[str]) -> Any:
    """Figs. 9 and 10: one row per time; left q_x/p0 of ``shear_cases`` with μ_f p and the stick
    zones (shaded), labelled with the phase of the run; right p/p0 of every case."""
    plt = pyplot()
    fig, axes = plt.subplots(len(times_tau), 2, figsize=(12, 3.0 * len(times_tau)), squeeze=False, sharex=True,
                             sharey="col")
    ref = next(iter(runs.values()))
    a0, p0 = float(ref.attrs["a0"]), float(ref.attrs["p0"])
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    case_color = {name: colors[i % len(colors)] for i, name in enumerate(runs)}
    # cases that coincide (fig9: case 4 on case 3) stay apparent: the later ones thinner and dashed
    # over the earlier, each with its own markers
    marks = {name: dict(marker="osD^v"[i % 5], markevery=(i, 6), ms=3.5, zorder=2 + i) for i, name in enumerate(runs)}
    lines = {name: dict(ls=("-", "--", "-.", (0, (1, 1)))[i % 4], lw=2.4 - 0.45 * (i % 4)) for i, name in enumerate(runs)}
    for (ax_q, ax_p), t in zip(axes, times_tau):
        for name in shear_cases:
            ds = runs[name]
            k = _at(ds, t)
            x, q = profile(ds, "shear_x", k)
            _, p = profile(ds, "pressure", k)
            _, stick = profile(ds, "stick", k)
            mu = float(ds.attrs["friction_coefficient"])
            c = case_color[name]
            ax_q.plot(x / a0, q / p0, color=c, lw=2.0 - 0.6 * (name != shear_cases[0]), **marks[name],
                      label=f"{_short(name)}: q_x ({phase_name(ds['phase'].values[k])})")
            ax_q.plot(x / a0, mu * p / p0, color=c, ls=":", lw=1.0, label=f"{_short(name)}: μ_f p")
            _shade_stick(ax_q, x / a0, stick > 0.5, c)
        ax_q.set(xlabel="x / a0", ylabel="q_x / p0", title=f"t = {t:g}τ: shear traction (shaded: stick)")
        ax_q.grid(alpha=0.3)
        ax_q.legend(fontsize=7)
        for name, ds in runs.items():
            x, p = profile(ds, "pressure", _at(ds, t))
            ax_p.plot(x / a0, p / p0, color=case_color[name], **marks[name], **lines[name], label=_short(name))
        ax_p.set(xlabel="x / a0", ylabel="p / p0", title=f"t = {t:g}τ: pressure")
        ax_p.grid(alpha=0.3)
        ax_p.legend(fontsize=7)
    _title(fig, runs, title)
    fig.tight_layout()
    return fig


def stick_slip_map(ds: xr.Dataset, times_tau: Sequence[float], files: FigureFiles, stem: str, *,
                   title: str = "contact: slip (orange), stick (blue)") -> Path:
    """Maps of the contact (white: open, orange: slip, blue: stick) at the recorded times nearest to
    ``times_tau`` [τ], one panel each, written as ``stem`` by ``files``. Axes x/a0, y/a0 in the
    indenter frame."""
    sc = Scales(ds)
    picks = [_at(ds, t) for t in times_tau]
    titles = [sc.t_label(float(ds["t"].values[k])) for k in picks]
    return files.save(draw_contact_maps(ds, picks, titles, title), stem)
