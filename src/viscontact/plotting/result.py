"""Figures of one result file: a transient run, a single steady state, or a steady speed curve.

Every figure states the result's title and its scales a0, p0, τ; quantities held by the boundary
condition (a constant load or approach) get no panel; panels of one figure share their axes.
"""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import tomllib

from viscontact.plotting.base import (
    FigureFiles,
    Scales,
    cell_limits,
    check_drawable,
    check_format,
    compact_log_ticks,
    draw_contact_maps,
    draw_map,
    fit_title,
    integer_ticks,
    is_line,
    is_periodic,
    is_steady,
    map_axes,
    map_image,
    positive_attr,
    profile,
    pyplot,
    retardation_count,
    set_title,
    time_index,
)
from viscontact.problem.problem import PHASE_GROSS_SLIDING

if TYPE_CHECKING:
    import xarray as xr

    from viscontact.physics.materials import Material

__all__ = ["ROUGH_VARIABLES", "contact_history_figure", "friction_figure", "is_rough", "material_of", "plot_result",
           "plot_speed_curve", "pressure_animation_figure", "pressure_maps_figure", "profiles_figure",
           "rough_contact_figure", "speed_curve_figure", "stick_maps_figure", "subsurface_figure",
           "tangential_loop_figure"]

#: the ratio of the largest to the smallest peak pressure of the maps beyond which each map has its own
#: colour scale (:func:`pressure_maps_figure`)
SHARED_SCALE_RANGE = 3.0
#: frames of the pressure animation at most
MAX_FRAMES = 60
#: the rough-contact histories of a result (:mod:`viscontact.problem.roughness`)
ROUGH_VARIABLES = ("contact_fraction", "contact_patches", "mean_gap", "mean_contact_pressure")


def _time_indices(nt: int, count: int = 6) -> np.ndarray:
    return np.unique(np.linspace(0, nt - 1, min(count, nt)).round().astype(int))


def _picks(ds: xr.Dataset, times: Sequence[float] | None, count: int) -> list[int]:
    """Records nearest to ``times`` [s], else ``count`` records evenly spread in time."""
    if times:
        return list(dict.fromkeys(time_index(ds, t) for t in times))
    return list(_time_indices(ds.sizes["t"], count))


def _held(values: np.ndarray) -> bool:
    """A series the boundary condition holds constant (to round-off)."""
    values = np.asarray(values, dtype=float)
    return values.size > 0 and float(np.ptp(values)) <= 1e-9 * float(np.max(np.abs(values)) or 1.0)


def _steady_label(ds: xr.Dataset) -> str:
    v = float(ds.attrs.get("sliding_speed", 0.0) or 0.0)
    tau, a0 = positive_attr(ds, "retardation_time"), positive_attr(ds, "a0")
    deborah = f", v τ/a0 = {v * tau / a0:.3g}" if tau and a0 else ""
    return f"steady state at v = {v:.3g} m/s{deborah}"


def material_of(ds: xr.Dataset) -> Material | None:
    """The half-space material of a result: from its ``relaxation_moduli`` and ``relaxation_times``
    attributes (the terms the run used), or in older results rebuilt from its case text and checked
    against its attributes (G(0), G(inf); the retardation time of a Zener material and the WLF factor
    ``a_T`` of a Prony one applied; None when they disagree, e.g. a material overridden on the command
    line in a way the text does not show). None when the body is no half-space of constant nu
    (``bulk_modulus``: nu(t); a ``[layer]``), whose contact the Lee & Radok reference does not describe."""
    from viscontact.errors import ParameterError
    from viscontact.physics.materials import Material

    try:
        if "bulk_modulus" in ds.attrs or "layer_thickness" in ds.attrs:
            return None
        nu = float(ds.attrs["poisson_ratio"])
        g0, ginf = float(ds.attrs["shear_modulus_instantaneous"]), float(ds.attrs["shear_modulus_long_term"])
        if "relaxation_times" in ds.attrs:  # the terms the run used (results written since they are kept)
            moduli, times = (np.atleast_1d(ds.attrs[k]).astype(float) for k in ("relaxation_moduli", "relaxation_times"))
            return Material.prony(ginf, moduli, times, nu)
        table = tomllib.loads(str(ds.attrs.get("case", "")))["material"]
        if table["type"] == "zener":
            material = Material.zener(g0, ginf, float(ds.attrs["retardation_time"]), nu)
        elif table["type"] == "elastic":
            material = Material.elastic(g0, nu)
        else:  # the times as the run shifted them (WLF)
            shift = float(ds.attrs.get("a_T", 1.0))
            material = Material.prony(table["g_inf"], table["g"], [shift * t for t in table["tau"]], nu)
    except (KeyError, TypeError, ValueError, ParameterError, tomllib.TOMLDecodeError):
        return None
    same = np.isclose(material.shear_modulus_instantaneous, g0, rtol=1e-9) and \
        np.isclose(material.shear_modulus_long_term, ginf, rtol=1e-9)
    return material if same else None


# --- along y = 0 ---------------------------------------------------------------------------------------
def profiles_figure(ds: xr.Dataset, times: Sequence[float] | None = None) -> Any:
    """Pressure (and shear, when nonzero) along y = 0 (:func:`~viscontact.plotting.base.profile`)
    against the distance from the indenter centre, at ``times`` [s] (default: about six records;
    a steady state: its one state); returns the Figure."""
    sc = Scales(ds)
    shear = "shear_x" in ds and bool(np.any(ds["shear_x"].values != 0))
    fig, axes = pyplot().subplots(1, 2 if shear else 1, figsize=(11 if shear else 6, 4.4), squeeze=False,
                                  sharex=True)
    ax_p = axes[0, 0]
    mu = float(ds.attrs.get("friction_coefficient", 0.0) or 0.0)
    steady = is_steady(ds)
    for k in ([0] if steady else _picks(ds, times, 6)):
        label = _steady_label(ds) if steady else sc.t_label(float(ds["t"].values[k]))
        x, p = profile(ds, "pressure", k)
        line, = ax_p.plot(x / sc.length[0], p / sc.pressure[0], label=label)
        if shear:
            _, q = profile(ds, "shear_x", k)
            axes[0, 1].plot(x / sc.length[0], q / sc.shear[0], color=line.get_color(), label=label)
            if mu > 0:  # on top of every q_x (in full slip q_x = μ_f p: the line would hide under its own)
                axes[0, 1].plot(x / sc.length[0], mu * p / sc.shear[0], color="k", ls=":", lw=0.9, zorder=3)
    ax_p.set(xlabel=sc.length[1], ylabel=sc.pressure[1], title="pressure")
    ax_p.legend(fontsize=8)
    if shear:
        axes[0, 1].set(xlabel=sc.length[1], ylabel=sc.shear[1],
                       title="shear traction (black dotted: μ_f p)" if mu > 0 else "shear traction")
    for ax in axes[0]:
        ax.grid(alpha=0.3)
    what = f"steady tractions along y = 0 (μ_app = {float(ds['mu_app'][0]):.4g})" if steady else \
        "tractions along y = 0"
    set_title(fig, ds, what)
    fig.tight_layout()
    return fig


# --- against time ------------------------------------------------------------------------------------
def contact_history_figure(ds: xr.Dataset) -> Any:
    """Contact radius, load and approach against time, without the one the boundary condition holds,
    and with Lee & Radok's solution (:mod:`viscontact.physics.reference`) for a sphere indented without
    sliding under a held load (creep) or approach (relaxation), labelled Hertz for an elastic
    material (G(0) = G(∞)), where it is his; returns the Figure."""
    from viscontact.physics.reference import lee_radok_creep, lee_radok_relaxation

    sc = Scales(ds)
    t = ds["t"].values
    line = is_line(ds)  # a line contact: its half-width, and no sphere's reference
    radius = ds["contact_area"].values / 2 if line else np.sqrt(ds["contact_area"].values / np.pi)
    what = "contact half-width A/2" if line else "contact radius √(A/π)"
    panels = [("contact_area", radius / sc.radius[0], f"{what}, {sc.radius[1]}", sc.radius[0])]
    panels += _normal_panels(ds)
    fig, axes = pyplot().subplots(1, len(panels), figsize=(4.4 * len(panels), 3.9), squeeze=False, sharex=True)
    curves = {}
    sphere = positive_attr(ds, "radius")
    material = material_of(ds)
    if ds.attrs.get("tangential_mode") == "none" and sphere and material is not None and not line:
        if ds.attrs.get("normal_control") == "load" and _held(ds["load"].values):
            ref = lee_radok_creep(float(ds["load"].values[0]), sphere, material, t)
            curves = {"contact_area": ref.radius, "delta_z": ref.approach}
        elif ds.attrs.get("normal_control") == "displacement" and _held(ds["delta_z"].values):
            ref = lee_radok_relaxation(float(ds["delta_z"].values[0]), sphere, material, t)
            curves = {"contact_area": ref.radius, "load": ref.load}
    elastic = bool(np.isclose(float(ds.attrs.get("shear_modulus_instantaneous", np.nan)),
                              float(ds.attrs.get("shear_modulus_long_term", np.nan)), rtol=1e-12, atol=0.0))
    for ax, (name, values, label, scale) in zip(axes[0], panels):
        ax.plot(t / sc.time[0], values, label="viscontact")
        if name in curves:
            ax.plot(t / sc.time[0], curves[name] * (1 / sc.radius[0] if name == "contact_area" else scale),
                    "k--", lw=1.0, label="Hertz (1882)" if elastic else "Lee & Radok (1960)")
            ax.legend(fontsize=8)
        ax.set(xlabel=sc.time[1], ylabel=label)
        ax.grid(alpha=0.3)
    set_title(fig, ds, "contact against time" + _held_note(ds))
    fig.tight_layout()
    return fig


#: the normal quantities against time: (variable, scale, axis label)
_NORMAL = (("load", 1.0, "load W [N]"), ("delta_z", 1e6, "approach δ_z [µm]"))


def _normal_panels(ds: xr.Dataset) -> list[tuple[str, np.ndarray, str, float]]:
    """(name, scaled values, label, scale) of the load and the approach, without the one held (a line
    contact's load per unit length, N/m)."""
    return [(name, ds[name].values * scale, label.replace("[N]", "[N/m]") if is_line(ds) else label, scale)
            for name, scale, label in _NORMAL if not _held(ds[name].values)]


def _held_note(ds: xr.Dataset) -> str:
    """`` (load held)``, `` (approach held)`` or nothing."""
    held = [name.replace("delta_z", "approach") for name, _, _ in _NORMAL if _held(ds[name].values)]
    return f" ({' and '.join(held)} held)" if held else ""


def _draw_friction(ax: Any, ds: xr.Dataset, sc: Scales) -> None:
    """μ_app and, when nonzero, the dry friction Σ q_x ΔA / W against time on ``ax``, with the onset
    of gross sliding after partial slip."""
    t = ds["t"].values / sc.time[0]
    ax.plot(t, ds["mu_app"].values, label="μ_app = F_T / W (hysteresis)")
    if np.any(ds["friction_force"].values != 0):
        load = np.where(ds["load"].values > 0, ds["load"].values, np.nan)
        ax.plot(t, ds["friction_force"].values / load, ls="--", label="Σ q_x ΔA / W (dry)")
    _mark_gross_sliding(ax, ds, sc, label="gross sliding")
    ax.set(xlabel=sc.time[1], ylabel="friction coefficient [-]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)


def _mark_gross_sliding(ax: Any, ds: xr.Dataset, sc: Scales, label: str | None = None) -> None:
    """A dotted vertical line at the onset of gross sliding after partial slip."""
    t_gs = positive_attr(ds, "t_gross_sliding")
    if t_gs and ds.attrs.get("tangential_mode") == "partial_slip":
        ax.axvline(t_gs / sc.time[0], color="grey", lw=0.8, ls=":", label=label)


def friction_figure(ds: xr.Dataset) -> Any:
    """The apparent friction μ_app (and the dry friction Σ q_x ΔA / W) against time; returns the Figure."""
    fig, ax = pyplot().subplots(figsize=(6.4, 4.4))
    _draw_friction(ax, ds, Scales(ds))
    set_title(fig, ds, "friction against time")
    fig.tight_layout()
    return fig


def is_rough(ds: xr.Dataset) -> bool:
    """A rough-contact result: it has the :data:`ROUGH_VARIABLES` against time and is periodic or
    has more than one contact patch at some record."""
    if not all(name in ds and ds[name].dims == ("t",) for name in ROUGH_VARIABLES):
        return False
    return is_periodic(ds) or bool(np.max(ds["contact_patches"].values, initial=0) > 1)


def rough_contact_figure(ds: xr.Dataset) -> Any:
    """Rough contact against time: μ_app (when sliding; with the dry friction), the real contact area
    fraction A_r / A_0, the number of contact patches, the mean gap, and the load or approach unless
    held; the onset of gross sliding marked; returns the Figure."""
    sc = Scales(ds)
    t = ds["t"].values / sc.time[0]
    sliding = ds.attrs.get("tangential_mode", "none") != "none"
    panels = [(name, ds[name].values * scale, label) for name, scale, label in
              (("contact_fraction", 1.0, "real contact area fraction A_r / A_0 [-]"),
               ("contact_patches", 1.0, "contact patches [-]"), ("mean_gap", 1e6, "mean gap [µm]"))]
    panels += [(name, values, label) for name, values, label, _ in _normal_panels(ds)]
    count = len(panels) + sliding
    fig, flat = _panel_grid(count)
    if sliding:
        _draw_friction(flat[0], ds, sc)
    for ax, (name, values, label) in zip(flat[sliding:], panels):
        if name == "contact_patches":
            ax.step(t, values, where="mid")
            integer_ticks(ax.yaxis)  # a count: no fractional ticks
        else:
            ax.plot(t, values)
        _mark_gross_sliding(ax, ds, sc)
        ax.set(xlabel=sc.time[1], ylabel=label)
        ax.grid(alpha=0.3)
    set_title(fig, ds, "rough contact against time" + _held_note(ds))
    fig.tight_layout()
    return fig


def _panel_grid(count: int) -> tuple[Any, list[Any]]:
    """A figure of ``count`` panels sharing their x axis, in rows of 2 (up to 4 panels) or 3, the
    last row centred when it is not full (no empty panel); returns (Figure, the panels in order)."""
    cols = 2 if count <= 4 else 3
    rows = -(-count // cols)
    fig = pyplot().figure(figsize=(4.2 * cols, 3.4 * rows))
    grid = fig.add_gridspec(rows, 2 * cols)
    axes: list[Any] = []
    for i in range(count):
        row, col = divmod(i, cols)
        left = (cols - (count - row * cols)) if row == rows - 1 else 0  # half-columns: the last row centred
        axes.append(fig.add_subplot(grid[row, left + 2 * col:left + 2 * col + 2], sharex=axes[0] if axes else None))
    return fig, axes


def _cattaneo_mindlin_references(ds: xr.Dataset) -> list[tuple[Any, str, str]]:
    """(:class:`~viscontact.physics.reference.CattaneoMindlin`, legend label, line style) of the elastic
    references of a sphere's partial slip: under a held load W those for G(0) and G(∞) at W; under a
    held approach δ_z the one curve Q/(μ_f W) against δ_x that every modulus gives there (a = √(R δ_z)
    and δ* = μ_f a² (2 - ν) / (2 R (1 - ν)) do not depend on G), which a viscoelastic body follows
    only for a tangential ramp fast or slow against its relaxation (the load relaxes under the
    held approach; in between, the shear held from when the load was higher reaches μ_f W(t)
    earlier). None under a varying load or approach, nor without a sphere."""
    from viscontact.physics.reference import cattaneo_mindlin, hertz_from_approach

    sphere = positive_attr(ds, "radius")
    mu = float(ds.attrs.get("friction_coefficient", 0.0) or 0.0)
    if not sphere or mu <= 0 or is_line(ds):  # a line contact: not the sphere's references
        return []
    nu = float(ds.attrs["poisson_ratio"])
    control = ds.attrs.get("normal_control")
    if control == "load" and _held(ds["load"].values):
        load = float(ds["load"].values[0])
        return [(cattaneo_mindlin(load, sphere, mu, float(ds.attrs[key]), nu), f"Cattaneo-Mindlin, elastic {name}",
                 style) for key, name, style in (("shear_modulus_instantaneous", "G(0)", "k--"),
                                                 ("shear_modulus_long_term", "G(∞)", "k:"))]
    if control == "displacement" and _held(ds["delta_z"].values):
        g0 = float(ds.attrs["shear_modulus_instantaneous"])
        hertz = hertz_from_approach(float(ds["delta_z"].values[0]), sphere, g0, nu)
        return [(cattaneo_mindlin(float(hertz.load), sphere, mu, g0, nu),
                 "Cattaneo-Mindlin, elastic at the held approach (any G)", "k--")]
    return []


def tangential_loop_figure(ds: xr.Dataset) -> Any:
    """The tangential force Q = Σ q_x ΔA over μ_f times the load W(t) of the same record (held or
    relaxing) against the tangential displacement δ_x of partial slip since the first contact (a
    normal history that starts at zero touches after the indenter has moved), 1 at the onset of gross
    sliding, with the elastic Cattaneo-Mindlin curves of :func:`_cattaneo_mindlin_references`
    (exact for ν = 0.5, where the normal and tangential problems do not couple); a δ_x that reverses
    (``tangential.displacement_history``) is drawn whole, loops of both signs
    (:func:`_fretting_loop_figure`); returns the Figure."""
    mu = float(ds.attrs.get("friction_coefficient", 0.0) or 0.0)
    load = ds["load"].values
    delta_x = ds["delta_x"].values
    if np.any(np.diff(delta_x) < 0):  # a displacement history that reverses: fretting loops
        return _fretting_loop_figure(ds, mu)
    touched = np.flatnonzero(ds["contact_area"].values > 0)
    delta_x = delta_x - (delta_x[touched[0]] if touched.size else 0.0)
    references = _cattaneo_mindlin_references(ds)
    # up to 1.5 times the onset of gross sliding (or the elastic one, the largest): the loop, not the sliding
    sliding = np.flatnonzero(ds["phase"].values == PHASE_GROSS_SLIDING)
    onset = [float(delta_x[sliding[0]])] if sliding.size else [float(np.max(delta_x))]
    end = 1.5 * max(onset + [cm.sliding_displacement for cm, _, _ in references])
    keep = (delta_x >= 0) & (delta_x <= end)
    with np.errstate(divide="ignore", invalid="ignore"):  # no load (no contact): no ratio
        ratio = np.where(load[keep] > 0, ds["friction_force"].values[keep] / (mu * load[keep]), np.nan)
    fig, ax = pyplot().subplots(figsize=(6.4, 4.6))
    ax.plot(delta_x[keep] * 1e6, ratio, "o-", ms=2.5, label="viscontact")
    d = np.linspace(0.0, end, 300)
    for cm, name, style in references:
        ax.plot(d * 1e6, cm.force(d) / (mu * cm.load), style, lw=1.0, label=name)
    ax.set(xlabel="tangential displacement since first contact δ_x [µm]", ylim=(0, 1.1),
           ylabel="Q / (μ_f W)" if _held(load) else "Q(t) / (μ_f W(t))")
    if not _held(load):
        ax.set_title("W(t): the load at the same step", fontsize=9)
    ax.grid(alpha=0.3)
    nu = float(ds.attrs.get("poisson_ratio", 0.5))
    ax.legend(fontsize=8, title_fontsize=8, loc="lower right",
              title=f"Cattaneo-Mindlin exact for ν = 0.5 (here {nu:g})" if references and nu != 0.5 else None)
    set_title(fig, ds, "tangential force against displacement" + _held_note(ds))
    fig.tight_layout()
    return fig


def _fretting_loop_figure(ds: xr.Dataset, mu: float) -> Any:
    """:func:`tangential_loop_figure` of a displacement history that reverses: Q / (μ_f W(t)) against
    the indenter's δ_x along the whole path (both signs: the hysteresis loops), with the elastic
    Mindlin-Deresiewicz loops between ±max |δ_x| of :func:`_cattaneo_mindlin_references` (exact for
    ν = 0.5) where that amplitude is below their gross slip. The whole path is drawn in grey, each
    full cycle (:func:`~viscontact.io.results.fretting_cycles`) over it in its own colour, named with
    the energy it dissipates (the result's ``energy_per_cycle``, else computed from its series)."""
    from viscontact.io.results import energy_per_cycle, fretting_cycles

    load, delta_x = ds["load"].values, ds["delta_x"].values
    with np.errstate(divide="ignore", invalid="ignore"):  # no load (no contact): no ratio
        ratio = np.where(load > 0, ds["friction_force"].values / (mu * load), np.nan)
    fig, ax = pyplot().subplots(figsize=(7.4, 5.2))
    cycles = fretting_cycles(delta_x)
    ax.plot(delta_x * 1e6, ratio, "o-", ms=1.5, lw=0.8, color="0.65",
            label="viscontact" + (" (grey: outside the full cycles)" if cycles else ""))
    energies = ds["energy_per_cycle"].values if "energy_per_cycle" in ds else \
        energy_per_cycle(delta_x, ds["friction_force"].values)
    colors = pyplot().get_cmap("plasma")(np.linspace(0.0, 0.8, max(len(cycles), 1)))
    for i, ((a, b), energy) in enumerate(zip(cycles, energies)):
        ax.plot(delta_x[a:b + 1] * 1e6, ratio[a:b + 1], "o-", ms=2.0, lw=1.2, color=colors[i],
                label=f"cycle {i + 1}: {energy * 1e6:.4g} µJ dissipated")
    amplitude = float(np.max(np.abs(delta_x)))
    up = np.linspace(-amplitude, amplitude, 200)
    for cm, name, style in _cattaneo_mindlin_references(ds):
        if amplitude < cm.sliding_displacement:
            loop = np.concatenate([cm.unloading_force(up[::-1], amplitude), cm.reloading_force(up, amplitude)])
            ax.plot(np.concatenate([up[::-1], up]) * 1e6, loop / (mu * cm.load), style, lw=1.0,
                    label=name.replace("Cattaneo-Mindlin", "Mindlin-Deresiewicz"))
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.axvline(0.0, color="0.6", lw=0.6)
    ax.set(xlabel="tangential displacement δ_x [µm]", ylim=(-1.1, 1.1),
           ylabel="Q / (μ_f W)" if _held(load) else "Q(t) / (μ_f W(t))")
    ax.grid(alpha=0.3)
    nu = float(ds.attrs.get("poisson_ratio", 0.5))
    ax.legend(fontsize=7.5, title_fontsize=8, loc="lower right",
              title=f"Mindlin-Deresiewicz exact for ν = 0.5 (here {nu:g})" if nu != 0.5 else None)
    set_title(fig, ds, "fretting loops: tangential force against displacement" + _held_note(ds))
    fig.tight_layout()
    return fig


# --- maps ----------------------------------------------------------------------------------------------
def pressure_maps_figure(ds: xr.Dataset, times: Sequence[float] | None = None) -> Any:
    """Maps of p/p0 in the indenter frame at ``times`` [s] (default: four records; a steady state:
    its one state): one colour scale, said in the title, unless the peaks of the maps differ by more
    than :data:`SHARED_SCALE_RANGE` times, when each map has its own (a creeping contact's later
    maps were washed out); returns the Figure."""
    sc = Scales(ds)
    picks = [0] if is_steady(ds) else _picks(ds, times, 4)
    pressure = ds["pressure"].values
    peaks = [float(pressure[k].max()) / sc.pressure[0] for k in picks]
    own = len(picks) > 1 and min(peaks) > 0 and max(peaks) > SHARED_SCALE_RANGE * min(peaks)
    fig, axes = map_axes(len(picks))
    if own:  # room for a colour bar under each map, the title above
        fig.set_size_inches(fig.get_size_inches()[0], 4.6)
        fig.subplots_adjust(top=0.80, bottom=0.08)
    for ax, k, peak in zip(axes[0], picks, peaks):
        top = (peak if own else max(peaks)) or 1.0
        image = draw_map(ax, ds, k, pressure[k] / sc.pressure[0], sc, vmin=0, vmax=top, cmap="viridis")
        ax.set(title=_steady_label(ds) if is_steady(ds) else sc.t_label(float(ds["t"].values[k])),
               xlabel=sc.length[1])
        if own:
            fig.colorbar(image, ax=ax, orientation="horizontal", location="bottom", pad=0.22, shrink=0.9,
                         label=sc.pressure[1])
    axes[0, 0].set_ylabel(sc.length[1].replace("x", "y"))
    if not own:
        fig.colorbar(image, ax=list(axes[0]), label=sc.pressure[1], shrink=0.85)
    set_title(fig, ds, "pressure" + (", each map its own colour scale" if own else
                                     ", one colour scale" if len(picks) > 1 else ""))
    return fig


def stick_maps_figure(ds: xr.Dataset, times: Sequence[float] | None = None) -> Any:
    """Maps of the contact (open, slip, stick) at ``times`` [s] (default: three records of partial
    slip and the first of gross sliding); returns the Figure."""
    sc = Scales(ds)
    phase = ds["phase"].values
    if times:
        picks = _picks(ds, times, 0)
    else:
        sliding = np.flatnonzero(phase == PHASE_GROSS_SLIDING)
        before = np.flatnonzero(phase < PHASE_GROSS_SLIDING)
        picks = list(before[_time_indices(before.size, 4 if sliding.size == 0 else 3)]) + list(sliding[:1])
    titles = [sc.t_label(float(ds["t"].values[k])) + (" (gross sliding)" if phase[k] == PHASE_GROSS_SLIDING else "")
              for k in picks]
    return draw_contact_maps(ds, picks or [0], titles, "contact: slip (orange), stick (blue)")


def pressure_animation_figure(ds: xr.Dataset) -> tuple[Any, Any, int]:
    """The frames of ``pressure.gif``: (Figure, ``frame(i)`` drawing the i-th, count), at most
    :data:`MAX_FRAMES` records evenly spread, one colour scale. The frames are saved at the figure's
    size, so the title is wrapped to its width (:func:`~viscontact.plotting.base.fit_title`) and the
    map placed below it."""
    sc = Scales(ds)
    picks = _time_indices(ds.sizes["t"], MAX_FRAMES)
    pressure = ds["pressure"].values
    fig, ax = pyplot().subplots(figsize=(5.2, 4.4))
    image = draw_map(ax, ds, int(picks[0]), pressure[picks[0]] / sc.pressure[0], sc, vmin=0,
                     vmax=float(pressure.max()) / sc.pressure[0] or 1.0, cmap="viridis")
    fig.colorbar(image, ax=ax, label=sc.pressure[1])
    ax.set(xlabel=sc.length[1], ylabel=sc.length[1].replace("x", "y"))
    title = set_title(fig, ds, "pressure")
    title.set_y(0.99)
    height = fit_title(fig, title)
    fig.subplots_adjust(top=0.99 - height - 0.09, bottom=0.11)

    def frame(i: int) -> tuple[Any]:
        k = picks[i]
        data, extent = map_image(ds, k, pressure[k] / sc.pressure[0], sc)
        image.set_data(data)
        image.set_extent(extent)
        if is_periodic(ds):
            ax.set_xlim(*cell_limits(ds, sc))
        ax.set_title(sc.t_label(float(ds["t"].values[k])))
        return (image,)

    frame(0)
    return fig, frame, len(picks)


def _pressure_animation(ds: xr.Dataset, files: FigureFiles) -> Path:
    fig, frame, count = pressure_animation_figure(ds)
    return files.save_animation(fig, frame, count, "pressure")


#: recorded subsurface times drawn at most (rows of ``subsurface_stress``, evenly spread)
MAX_SUBSURFACE_TIMES = 6
#: the subsurface stresses drawn: (variable, panel title)
_SUBSURFACE = (("von_mises_stress", "von Mises"), ("max_shear_stress", "maximum shear"))


def _cell_edges(centres: np.ndarray, *, clipped: bool = False) -> np.ndarray:
    """The edges of the cells around ``centres`` (increasing, two at least): half-way between two
    centres, and half a gap beyond the outer ones; ``clipped``: the outer edges at the first and last
    centres instead (nothing drawn beyond the values computed)."""
    middle = 0.5 * (centres[1:] + centres[:-1])
    if clipped:
        return np.concatenate([centres[:1], middle, centres[-1:]])
    return np.concatenate([[2 * centres[0] - middle[0]], middle, [2 * centres[-1] - middle[-1]]])


def subsurface_figure(ds: xr.Dataset) -> Any:
    """Von Mises and maximum shear stress in the section y = 0, one row per recorded subsurface time
    (``t_sub``; at most :data:`MAX_SUBSURFACE_TIMES`, evenly spread, the title saying how many of how
    many): maps in x-z with the depth z downwards (the surface on top), from the first depth computed
    to the last (each depth's band reaching half-way to its neighbours'), each with its own colour
    scale and its largest value marked (+), scaled by p0 (else MPa) and x, z by a0 (else mm). A single
    depth: the stresses against x, one line per time. Returns the Figure."""
    plt = pyplot()
    sc = Scales(ds)
    (l_scale, l_label), (p_scale, p_label) = sc.length, sc.pressure
    count = ds.sizes["t_sub"]
    picks = _time_indices(count, MAX_SUBSURFACE_TIMES)
    times = ds["t_sub"].values
    x = ds["x"].values / l_scale
    z = ds["z"].values / l_scale
    stress_unit = p_label.replace("p", "σ", 1)
    depth_label = "depth " + l_label.replace("x", "z", 1)

    def at_depth(value: float) -> str:  # z/a0 = 0.5, or z = 0.3 mm
        return f"z/a0 = {value:.3g}" if l_label.startswith("x /") else f"z = {value:.3g} mm"

    stress_of = " p0" if p_label.startswith("p /") else " MPa"  # after a scaled stress

    if z.size > 1:
        order = np.argsort(z, kind="stable")  # the depths as the case listed them: drawn downwards
        z = z[order]
        x_edges, z_edges = _cell_edges(x), _cell_edges(z, clipped=True)
        fig, axes = plt.subplots(picks.size, 2, figsize=(10, 0.7 + 3.3 * picks.size), squeeze=False, sharex=True,
                                 sharey=True, constrained_layout=True)
        for row, k in zip(axes, picks):
            for ax, (name, title) in zip(row, _SUBSURFACE):
                data = ds[name].values[k][order] / p_scale
                mesh = ax.pcolormesh(x_edges, z_edges, data, shading="flat", cmap="viridis")
                fig.colorbar(mesh, ax=ax, label=stress_unit)
                iz, ix = np.unravel_index(int(np.argmax(data)), data.shape)
                ax.plot(x[ix], z[iz], "w+", ms=9, mew=1.5)
                ax.set_title(f"{title}, {sc.t_label(float(times[k]))}: largest {data[iz, ix]:.3g}{stress_of} "
                             f"at {at_depth(z[iz])}", fontsize=10)
            row[0].set_ylabel(depth_label)
        axes[0, 0].invert_yaxis()  # once: the panels share the axis, and a second call flips it back
    else:
        fig, axes = plt.subplots(1, 2, figsize=(10, 4), squeeze=False, sharex=True, sharey=True,
                                 constrained_layout=True)
        for ax, (name, title) in zip(axes[0], _SUBSURFACE):
            for k in picks:
                ax.plot(x, ds[name].values[k][0] / p_scale, label=sc.t_label(float(times[k])))
            ax.set_title(f"{title} at {at_depth(z[0])}", fontsize=10)
            ax.legend(fontsize=8)
            ax.grid(alpha=0.3)
        axes[0, 0].set_ylabel(stress_unit)
    for ax in axes[-1]:
        ax.set_xlabel(l_label)
    shown = f", {picks.size} of {count} recorded times" if picks.size < count else ""
    set_title(fig, ds, f"stresses in the section y = 0{shown}")
    return fig


def _warn_incomplete(ds: xr.Dataset) -> None:
    """A :class:`~viscontact.errors.ViscontactWarning` when ``ds`` holds a run that did not reach its
    end (attribute ``complete = 0``): its figures stop at its last record and could pass for a
    whole run's."""
    try:
        complete = int(ds.attrs.get("complete", 1))
    except (TypeError, ValueError):
        complete = 1
    if complete == 0:
        from viscontact.errors import warn_caller

        stopped = ds.attrs.get("stopped_by")
        why = f", stopped by {stopped}" if stopped else ""
        where = ds.encoding.get("source") or "the result"
        warn_caller(f"{where} holds an incomplete run (complete = 0{why}): its figures end at its last record, "
                    f"t = {float(ds['t'].values[-1]):.4g} s, not at the case's time.t_end")


def _histories_drawn(ds: xr.Dataset, mode: str) -> tuple[str, ...]:
    """The variables against time that the figures of :func:`plot_result` read (the fields, the
    rough-contact series and the subsurface stresses are drawn where present)."""
    if is_steady(ds):
        return ()
    names = [] if is_periodic(ds) else ["contact_area", "load", "delta_z"]  # contact_history
    if mode != "none":
        names += ["mu_app", "friction_force", "load"]  # friction
    if mode == "partial_slip":
        names += ["load", "delta_x", "contact_area", "phase", "friction_force"]  # tangential_loop
    return tuple(dict.fromkeys(names))


def plot_result(ds: xr.Dataset, out_dir: str | Path, *, times: Sequence[float] | None = None, fmt: str = "png",
                dpi: int | None = None) -> list[Path]:
    """Figures of a transient (or single steady) result, written into ``out_dir``.

    ``pressure_profiles``: pressure (and shear, when nonzero) along y = 0; ``pressure_maps``: p/p0
    maps at ``times`` [s] (default: four records). A line contact (one row) has its profiles only:
    no maps, stick maps or animation, and its contact history shows the half-width A/2. A transient adds ``contact_history`` (contact
    radius, load and approach against time; Lee & Radok, or Hertz when elastic, for held indentation;
    not on a periodic domain), for a rough contact (:func:`is_rough`) ``rough_contact`` (μ_app, real
    contact area fraction, contact patches, mean gap against time), ``pressure.gif`` (an animation
    of the pressure field), when sliding ``friction`` (apparent friction against time) and in
    partial slip ``tangential_loop`` (Q / μ_f W(t) against δ_x, with Cattaneo-Mindlin) and
    ``stick_map`` (stick/slip maps); with subsurface output ``subsurface_stress`` (von Mises and
    maximum shear maps in the section y = 0, depth downwards, a row per recorded time). A steady
    state is drawn as one state, with no time histories.

    Parameters
    ----------
    ds
        A result Dataset (:func:`viscontact.io.netcdf.open_result`).
    out_dir
        Folder for the files (created).
    times
        Times [s] of the profiles and maps (the nearest records).
    fmt, dpi
        File format (``png``, ``pdf``, ``svg``) and resolution [dots per inch] of the figures.

    Returns
    -------
    list of Path
        The files written.
    """
    check_format(fmt, dpi)
    mode = ds.attrs.get("tangential_mode", "none")
    check_drawable(ds, "t", _histories_drawn(ds, mode))
    _warn_incomplete(ds)
    files = FigureFiles(Path(out_dir), fmt, dpi)
    figures: dict[str, Any] = {}
    maps = not is_line(ds)  # a line contact's one row: its profiles, no maps
    if "pressure" in ds:
        figures["pressure_profiles"] = profiles_figure(ds, times)
        if maps:
            figures["pressure_maps"] = pressure_maps_figure(ds, times)
    if not is_steady(ds):
        if not is_periodic(ds):  # a contact radius means nothing for the many spots of a period
            figures["contact_history"] = contact_history_figure(ds)
        if is_rough(ds):
            figures["rough_contact"] = rough_contact_figure(ds)
        if mode != "none":
            figures["friction"] = friction_figure(ds)
        if mode == "partial_slip":
            figures["tangential_loop"] = tangential_loop_figure(ds)
            if "stick" in ds and "pressure" in ds and maps:
                figures["stick_map"] = stick_maps_figure(ds, times)
    if "von_mises_stress" in ds and ds.sizes.get("t_sub", 0):
        figures["subsurface_stress"] = subsurface_figure(ds)
    paths = [files.save(fig, name) for name, fig in figures.items()]
    if "pressure" in ds and not is_steady(ds) and ds.sizes["t"] > 1 and maps:
        paths.append(_pressure_animation(ds, files))
    return paths


# --- speed curves -------------------------------------------------------------------------------------
def speed_curve_figure(ds: xr.Dataset) -> Any:
    """μ_app, peak pressure, contact area and contact shift of a steady speed sweep (dimension
    ``speed``) against the Deborah number v τ / a0 (log axis; speed in m/s on the top axis), or
    against v [m/s] when τ or a0 is unknown; returns the Figure."""
    sc = Scales(ds)
    order = np.argsort(ds["speed"].values)
    speed = ds["speed"].values[order]
    tau, a0 = positive_attr(ds, "retardation_time"), positive_attr(ds, "a0")
    k = tau / a0 if tau and a0 else None
    x = speed * k if k else speed
    if is_line(ds):  # a line contact: its width per unit length against 2 a0
        area_scale, area_label = (2 * a0, "contact width A / (2 a0)") if a0 else (1e-3, "contact width [mm]")
    else:
        area_scale, area_label = (np.pi * a0**2, "contact area A / (π a0²)") if a0 else (1e-6, "contact area [mm²]")
    panels = (("mu_app", 1.0, "μ_app = F_T / W [-]"), ("peak_pressure", sc.pressure[0], f"peak {sc.pressure[1]}"),
              ("contact_area", area_scale, area_label),
              ("contact_shift", sc.length[0], f"contact shift {sc.length[1].replace('x', 'x_c')}"))
    fig, axes = pyplot().subplots(2, 2, figsize=(10.5, 7.4), sharex=True)
    for ax, (name, scale, label) in zip(axes.flat, panels):
        ax.semilogx(x, ds[name].values[order] / scale, "o-", ms=4)
        ax.set(ylabel=label)
        ax.grid(alpha=0.3, which="both")
    deborah = "Deborah number v τ / a0" + (", τ the shortest retardation time" if retardation_count(ds) > 1 else "")
    for ax in axes[1]:
        ax.set_xlabel(deborah if k else "sliding speed v [m/s]")
    compact_log_ticks(*axes[1])
    if k:
        for ax in axes[0]:
            top = ax.secondary_xaxis("top", functions=(lambda d, k=k: d / k, lambda v, k=k: v * k))
            top.set_xlabel("sliding speed v [m/s]")
            compact_log_ticks(top)
    set_title(fig, ds.assign_attrs(title=without_speed(str(ds.attrs.get("title", "")))), "steady sliding against speed")
    fig.tight_layout()
    return fig


def without_speed(title: str) -> str:
    """A case's ``title`` without the one speed it names (``frictionless sliding at v = 0.8 a0/tau,
    W = 0.148 N`` -> ``frictionless sliding, W = 0.148 N``): the title of a curve over speeds."""
    import re

    return re.sub(r"\s*,?\s*\b(?:at\s+)?v\s*=\s*[^,;:]+", "", title).strip()


def plot_speed_curve(ds: xr.Dataset, out_dir: str | Path, *, fmt: str = "png", dpi: int | None = None) -> list[Path]:
    """:func:`speed_curve_figure` as ``speed_curve.<fmt>`` in ``out_dir``."""
    check_format(fmt, dpi)
    check_drawable(ds, "speed", ("mu_app", "peak_pressure", "contact_area", "contact_shift"))
    return [FigureFiles(Path(out_dir), fmt, dpi).save(speed_curve_figure(ds), "speed_curve")]
