"""Reproduce the figures of the seed (Wang et al., Friction 2023, Figs. 4 and 6-10) from the shipped cases.

Each figure runs its cases from ``cases/`` (``seed_*.toml``; see their header comments for the seed's
parameters and the SPEC §1 conversion), saves every result as ``<case>.nc`` in the output folder and
draws the figure from those Datasets only. A saved result whose stored case text is that of the
case to run (same overrides) is reused instead of being computed again, so ``fig8`` after ``fig6``
and ``fig7`` costs nothing.

=======  ==============================================  ===========================================
figure   cases                                           panels
=======  ==============================================  ===========================================
fig4     seed_table1_v{0.4,0.8,1.2} (frictionless, load)  p/p0 along y = 0 at t = 0, 0.5, 1, 2 tau per
                                                         speed; mu_app(t/tau)
fig6     seed_table2_ratio{3,5,10}_displacement           p/p0 at t = 0, 0.5, 1, 2, 4 tau per ratio;
                                                         G(t)/G(0)
fig7     seed_table2_ratio{3,5,10}_load                   p/p0 at t = 0, 0.5, 1, 2, 4 tau per ratio;
                                                         J(t) G(0)
fig8     both sets of Table 2                            mu_app(t/tau): relaxation | creep
fig9     seed_table3_case{1,2,3,4} (displacement)         per t = 0, 0.1, 0.5, 1, 1.5 tau: q_x of cases
                                                         3, 4 with mu_f p and stick zones | p of all
fig10    seed_fig10_case{1,2,3} (load)                    as fig9 at t = 0, 0.1, 0.2, 1, 4 tau (case 3)
=======  ==============================================  ===========================================

Profiles are taken along y = 0 (mean of the two middle rows of the even grid) and plotted against
the distance from the indenter centre, x - frame_offset, normalised by the result's ``a0``/``p0``
(Hertz with G(0); under displacement control a0 = sqrt(R delta)). Times are t/tau with tau the
retardation time. Matplotlib is imported inside the functions (Agg backend).
"""
from __future__ import annotations

import argparse
import math
import sys
import time as _time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from .errors import ParameterError

__all__ = ["FIGURES", "add_reproduce_parser", "cli_reproduce", "draw", "find_cases_dir", "profile",
           "reproduce", "run_seed_cases", "stick_slip_map"]

#: progress(case_name, steps_done, steps_total)
Progress = Callable[[str, int, int], None]

DPI = 150


@dataclass(frozen=True)
class FigureSpec:
    """Cases of one seed figure and the times [in units of tau] its profiles are drawn at."""

    cases: tuple[str, ...]
    times: tuple[float, ...]
    title: str


FIGURES: dict[str, FigureSpec] = {
    "fig4": FigureSpec(("seed_table1_v0.4", "seed_table1_v0.8", "seed_table1_v1.2"), (0.0, 0.5, 1.0, 2.0),
                       "Seed Fig. 4 / Table 1: frictionless sliding under W = 0.148 N"),
    "fig6": FigureSpec(tuple(f"seed_table2_ratio{r}_displacement" for r in (3, 5, 10)), (0.0, 0.5, 1.0, 2.0, 4.0),
                       "Seed Fig. 6 / Table 2: frictionless sliding under a held approach (relaxation)"),
    "fig7": FigureSpec(tuple(f"seed_table2_ratio{r}_load" for r in (3, 5, 10)), (0.0, 0.5, 1.0, 2.0, 4.0),
                       "Seed Fig. 7 / Table 2: frictionless sliding under a held load (creep)"),
    "fig8": FigureSpec(tuple(f"seed_table2_ratio{r}_{c}" for c in ("displacement", "load") for r in (3, 5, 10)),
                       (), "Seed Fig. 8: apparent friction of the Table 2 materials"),
    "fig9": FigureSpec(tuple(f"seed_table3_case{c}" for c in (1, 2, 3, 4)), (0.0, 0.1, 0.5, 1.0, 1.5),
                       "Seed Fig. 9 / Table 3: frictional sliding under a held approach"),
    "fig10": FigureSpec(tuple(f"seed_fig10_case{c}" for c in (1, 2, 3)), (0.0, 0.1, 0.2, 1.0, 4.0),
                        "Seed Fig. 10: frictional sliding under a held load W = 0.15 N"),
}

#: fewest points wanted on a time curve (mu_app) when fields are recorded sparsely
_MIN_CURVE_POINTS = 40


# --- running the cases ------------------------------------------------------------------------------
def find_cases_dir(cases_dir: str | Path | None = None) -> Path:
    """The folder holding ``seed_*.toml``: ``cases_dir``, else ``./cases``, else the repository's
    ``cases/`` next to ``src/``."""
    candidates = [Path(cases_dir)] if cases_dir is not None else [
        Path.cwd() / "cases", Path(__file__).resolve().parents[2] / "cases"]
    for folder in candidates:
        if (folder / "seed_table1_v0.8.toml").is_file():
            return folder
    raise ParameterError("--cases", "no folder with the shipped seed_*.toml cases found (looked in "
                         + ", ".join(str(c) for c in candidates) + "); pass cases_dir / --cases")


def _record_every(case: Any, times_tau: Sequence[float], partial_slip: bool) -> int:
    """Largest recording stride that hits every requested time and keeps time curves resolved.

    Partial-slip runs record every step so that ``t_gross_sliding`` (first recorded gross-sliding
    time) is exact to one step."""
    if partial_slip or not times_tau:
        return 1
    problem_dt = case.default_dt()
    tau = case.material.retardation_time if hasattr(case.material, "retardation_time") else 0.01
    n_steps = math.floor(case.time.t_end / problem_dt + 1e-9) + 1
    every = 0
    for t in times_tau:
        every = math.gcd(every, round(t * tau / problem_dt))
    every = max(every, 1)
    while every > 1 and n_steps / every < _MIN_CURVE_POINTS:
        every = next(d for d in range(every - 1, 0, -1) if every % d == 0)
    return every


def _load_seed_case(name: str, cases_dir: Path, n: int | None, times_tau: Sequence[float]) -> Any:
    from .case import load_case

    case = load_case(cases_dir / f"{name}.toml")
    overrides: dict[str, Any] = {}
    if n is not None:
        overrides["grid.n"] = int(n)  # time.dt is not in the seed files: it follows the grid
    every = _record_every(case.with_overrides(overrides) if overrides else case, times_tau,
                          case.tangential.mode == "partial_slip")
    if every != case.output.every:
        overrides["output.every"] = every
    return case.with_overrides(overrides) if overrides else case


def _cached(path: Path, case_text: str) -> xr.Dataset | None:
    """The saved result at ``path`` when it is complete and was computed from ``case_text``."""
    if not path.is_file():
        return None
    from .results import open_result

    try:
        ds = open_result(path)
    except (OSError, ValueError):
        return None
    if ds.attrs.get("case") == case_text and int(ds.attrs.get("complete", 0)) == 1:
        return ds
    return None


def run_seed_cases(names: Sequence[str], out_dir: str | Path, *, n: int | None = None,
                   times_tau: Sequence[float] = (), cases_dir: str | Path | None = None,
                   progress: Progress | None = None, reuse: bool = True) -> dict[str, xr.Dataset]:
    """Run (or reuse) the shipped cases ``names`` and save each as ``out_dir/<name>.nc``.

    Parameters
    ----------
    names
        Case names (file stems in ``cases/``).
    out_dir
        Folder for the result files (created).
    n
        Override ``grid.n`` (``time.dt`` follows: one cell of sliding per step).
    times_tau
        Times [tau] at which fields must be recorded (sets ``output.every``).
    cases_dir
        Folder of the case files (see :func:`find_cases_dir`).
    progress
        Called as ``progress(name, steps_done, steps_total)``.
    reuse
        Reuse a complete saved result computed from the same case text.
    """
    from . import api
    from .results import write_netcdf

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    folder = find_cases_dir(cases_dir)
    results: dict[str, xr.Dataset] = {}
    for name in names:
        case = _load_seed_case(name, folder, n, times_tau)
        path = out_dir / f"{name}.nc"
        ds = _cached(path, case.text) if reuse else None
        if ds is None:
            callback = (lambda done, total, _name=name: progress(_name, done, total)) if progress else None
            ds = api.run(case, progress=callback)
            write_netcdf(ds, path, force=True)
        results[name] = ds
    return results


# --- helpers on Datasets ----------------------------------------------------------------------------
def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _tau(ds: xr.Dataset) -> float:
    return float(ds.attrs["retardation_time"])


def _index(ds: xr.Dataset, t_tau: float) -> int:
    """Index of the recorded time nearest to t_tau [tau]."""
    return int(np.argmin(np.abs(ds["t"].values / _tau(ds) - t_tau)))


def profile(ds: xr.Dataset, name: str, k: int) -> tuple[np.ndarray, np.ndarray]:
    """(x - frame_offset [m], field) along y = 0 at record ``k``: the mean of the two middle rows
    (y = +-dx/2) of the even grid, against the distance from the indenter centre."""
    field = np.asarray(ds[name].values[k], dtype=float)
    n = field.shape[0]
    row = field[n // 2] if n % 2 else 0.5 * (field[n // 2 - 1] + field[n // 2])
    offset = float(ds["frame_offset"].values[k]) if "frame_offset" in ds else 0.0
    return ds["x"].values - offset, row


def _label_t(ds: xr.Dataset, k: int) -> str:
    return f"t = {ds['t'].values[k] / _tau(ds):.3g}τ"


def _save(fig: Any, path: Path) -> Path:
    fig.savefig(path, dpi=DPI, bbox_inches="tight")
    _pyplot().close(fig)
    return path


def _short(name: str) -> str:
    return name.replace("seed_", "").replace("_", " ")


# --- figures ---------------------------------------------------------------------------------------
def _profiles_panel(ax: Any, ds: xr.Dataset, times_tau: Sequence[float], title: str) -> None:
    a0, p0 = float(ds.attrs["a0"]), float(ds.attrs["p0"])
    for t in times_tau:
        k = _index(ds, t)
        x, p = profile(ds, "pressure", k)
        ax.plot(x / a0, p / p0, label=_label_t(ds, k))
    ax.set(xlabel="x / a0", ylabel="p / p0", title=title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)


def _mu_panel(ax: Any, runs: dict[str, xr.Dataset], labels: dict[str, str], title: str) -> None:
    for name, ds in runs.items():
        ax.plot(ds["t"].values / _tau(ds), ds["mu_app"].values, label=labels[name])
    ax.set(xlabel="t / τ", ylabel="μ_app = F_T / W", title=title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)


def _ratio(ds: xr.Dataset) -> float:
    return float(ds.attrs["shear_modulus_instantaneous"]) / float(ds.attrs["shear_modulus_long_term"])


def _fig4(runs: dict[str, xr.Dataset], spec: FigureSpec, out_dir: Path) -> list[Path]:
    plt = _pyplot()
    fig, axes = plt.subplots(1, 4, figsize=(19, 4.2))
    labels = {}
    for ax, (name, ds) in zip(axes[:3], runs.items()):
        v = float(ds.attrs["sliding_speed"]) * _tau(ds) / float(ds.attrs["a0"])
        labels[name] = f"v τ/a0 = {v:.2f}"
        _profiles_panel(ax, ds, spec.times, f"({'abc'[len(labels) - 1]}) {labels[name]}")
    _mu_panel(axes[3], runs, labels, "(d) apparent friction")
    fig.suptitle(spec.title)
    fig.tight_layout()
    return [_save(fig, out_dir / "fig4.png")]


def _fig67(runs: dict[str, xr.Dataset], spec: FigureSpec, out_dir: Path, which: str) -> list[Path]:
    plt = _pyplot()
    from .materials import Material

    fig, axes = plt.subplots(1, 4, figsize=(19, 4.2))
    t_curve = np.linspace(0.0, 4.0, 200)
    for i, (name, ds) in enumerate(runs.items()):
        ratio = _ratio(ds)
        _profiles_panel(axes[i], ds, spec.times, f"({'abc'[i]}) G(0)/G(∞) = {ratio:g}")
        g0, ginf = float(ds.attrs["shear_modulus_instantaneous"]), float(ds.attrs["shear_modulus_long_term"])
        mat = Material.zener(g0, ginf, _tau(ds), float(ds.attrs["poisson_ratio"]))
        t = t_curve * _tau(ds)
        if which == "fig6":
            axes[3].plot(t_curve, mat.relaxation_modulus(t) / g0, label=f"G(0)/G(∞) = {ratio:g}")
        else:
            axes[3].plot(t_curve, mat.creep_compliance(t) * g0, label=f"G(0)/G(∞) = {ratio:g}")
    ylabel = "G(t) / G(0)" if which == "fig6" else "J(t) G(0)"
    axes[3].set(xlabel="t / τ", ylabel=ylabel,
                title="(d) relaxation modulus" if which == "fig6" else "(d) creep compliance")
    axes[3].grid(alpha=0.3)
    axes[3].legend(fontsize=8)
    fig.suptitle(spec.title)
    fig.tight_layout()
    return [_save(fig, out_dir / f"{which}.png")]


def _fig8(runs: dict[str, xr.Dataset], spec: FigureSpec, out_dir: Path) -> list[Path]:
    plt = _pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for ax, control, title in ((axes[0], "displacement", "(a) stress relaxation (held approach)"),
                               (axes[1], "load", "(b) creep (held load)")):
        sel = {k: v for k, v in runs.items() if k.endswith(control)}
        _mu_panel(ax, sel, {k: f"G(0)/G(∞) = {_ratio(v):g}" for k, v in sel.items()}, title)
    fig.suptitle(spec.title)
    fig.tight_layout()
    return [_save(fig, out_dir / "fig8.png")]


def _shade_stick(ax: Any, x: np.ndarray, stick: np.ndarray, color: Any) -> None:
    """Shade the x intervals where ``stick`` is true."""
    if not np.any(stick):
        return
    dx = x[1] - x[0]
    edges = np.flatnonzero(np.diff(np.concatenate([[0], stick.astype(int), [0]])))
    for start, stop in zip(edges[::2], edges[1::2]):
        ax.axvspan(x[start] - dx / 2, x[stop - 1] + dx / 2, color=color, alpha=0.15, lw=0)


def _frictional(runs: dict[str, xr.Dataset], spec: FigureSpec, out_dir: Path, which: str,
                shear_cases: Sequence[str]) -> list[Path]:
    plt = _pyplot()
    rows = len(spec.times)
    fig, axes = plt.subplots(rows, 2, figsize=(12, 3.0 * rows), squeeze=False)
    ref = next(iter(runs.values()))
    a0, p0 = float(ref.attrs["a0"]), float(ref.attrs["p0"])
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    case_color = {name: colors[i % len(colors)] for i, name in enumerate(runs)}
    for r, t in enumerate(spec.times):
        ax_q, ax_p = axes[r]
        for name in shear_cases:
            ds = runs[name]
            k = _index(ds, t)
            x, q = profile(ds, "shear_x", k)
            _, p = profile(ds, "pressure", k)
            _, stick = profile(ds, "stick", k)
            mu = float(ds.attrs["friction_coefficient"])
            phase = ("partial slip", "partial slip", "gross sliding")[int(ds["phase"].values[k])]
            c = case_color[name]
            ax_q.plot(x / a0, q / p0, color=c, label=f"{_short(name)}: q_x ({phase})")
            ax_q.plot(x / a0, mu * p / p0, color=c, ls=":", lw=1.0, label=f"{_short(name)}: μ_f p")
            _shade_stick(ax_q, x / a0, stick > 0.5, c)
        ax_q.set(xlabel="x / a0", ylabel="q_x / p0", title=f"t = {t:g}τ: shear traction (shaded: stick)")
        ax_q.grid(alpha=0.3)
        ax_q.legend(fontsize=7)
        for name, ds in runs.items():
            k = _index(ds, t)
            x, p = profile(ds, "pressure", k)
            ax_p.plot(x / a0, p / p0, color=case_color[name], label=_short(name))
        ax_p.set(xlabel="x / a0", ylabel="p / p0", title=f"t = {t:g}τ: pressure")
        ax_p.grid(alpha=0.3)
        ax_p.legend(fontsize=7)
    fig.suptitle(spec.title)
    fig.tight_layout()
    paths = [_save(fig, out_dir / f"{which}.png")]
    for name in shear_cases:
        paths.append(stick_slip_map(runs[name], spec.times, out_dir / f"{which}_{name}_stick_map.png",
                                    title=f"{_short(name)}: slip (orange), stick (blue)"))
    return paths


def stick_slip_map(ds: xr.Dataset, times_tau: Sequence[float], path: str | Path, *,
                   title: str = "contact: slip (orange), stick (blue)") -> Path:
    """Maps of the contact (white: open, orange: slip, blue: stick) at the recorded times nearest to
    ``times_tau`` [tau], one panel each, written as PNG to ``path``. Axes x/a0, y/a0 in the grid frame."""
    plt = _pyplot()
    from matplotlib.colors import ListedColormap

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    a0 = float(ds.attrs["a0"])
    x = ds["x"].values
    half = float(x[-1] + 0.5 * (x[1] - x[0])) / a0
    picks = [_index(ds, t) for t in times_tau]
    fig, axes = plt.subplots(1, len(picks), figsize=(3.2 * len(picks), 3.4), squeeze=False)
    cmap = ListedColormap(["white", "tab:orange", "tab:blue"])
    stick = ds["stick"].values if "stick" in ds else None
    for ax, k in zip(axes[0], picks):
        state = (ds["pressure"].values[k] > 0).astype(int)
        if stick is not None:
            state = state + stick[k].astype(int)
        ax.imshow(state, origin="lower", extent=(-half, half, -half, half), cmap=cmap, vmin=0, vmax=2,
                  interpolation="nearest")
        ax.set(title=_label_t(ds, k), xlabel="x / a0", ylabel="y / a0")
    fig.suptitle(title)
    fig.tight_layout()
    return _save(fig, path)


def draw(figure: str, runs: dict[str, xr.Dataset], out_dir: str | Path) -> list[Path]:
    """Draw ``figure`` from the Datasets ``runs`` (keyed by case name) into ``out_dir``."""
    spec = FIGURES[figure]
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    runs = {name: runs[name] for name in spec.cases}
    if figure == "fig4":
        return _fig4(runs, spec, out_dir)
    if figure in ("fig6", "fig7"):
        return _fig67(runs, spec, out_dir, figure)
    if figure == "fig8":
        return _fig8(runs, spec, out_dir)
    if figure == "fig9":
        return _frictional(runs, spec, out_dir, figure, ("seed_table3_case3", "seed_table3_case4"))
    return _frictional(runs, spec, out_dir, figure, ("seed_fig10_case3",))


def reproduce(figure: str, out_dir: str | Path, *, n: int | None = None, progress: Progress | None = None,
              cases_dir: str | Path | None = None) -> list[Path]:
    """Run the cases of a seed figure and draw it.

    Parameters
    ----------
    figure
        One of ``fig4``, ``fig6``, ``fig7``, ``fig8``, ``fig9``, ``fig10``.
    out_dir
        Folder for the figure(s) (PNG) and the results (``<case>.nc``).
    n
        Override ``grid.n`` for a quick preview (the seed uses 256; ``time.dt`` follows).
    progress
        Called as ``progress(case_name, steps_done, steps_total)`` after each time step.
    cases_dir
        Folder of the ``seed_*.toml`` cases (default: ``./cases`` or the repository's).

    Returns
    -------
    list of Path
        The figure files, then the result files.
    """
    if figure not in FIGURES:
        raise ParameterError("figure", f"must be one of {', '.join(FIGURES)}, got {figure!r}")
    if n is not None and (int(n) != n or n < 8):
        raise ParameterError("--n", f"must be an integer >= 8 (grid cells per side), got {n!r}")
    _pyplot()  # fail before computing when matplotlib is missing
    spec = FIGURES[figure]
    times = spec.times
    if figure == "fig8":
        times = FIGURES["fig6"].times  # same runs as fig6/fig7, so their saved results are reused
    runs = run_seed_cases(spec.cases, out_dir, n=n, times_tau=times, cases_dir=cases_dir, progress=progress)
    figures = draw(figure, runs, out_dir)
    return figures + [Path(out_dir) / f"{name}.nc" for name in spec.cases]


# --- command line ----------------------------------------------------------------------------------
def add_reproduce_parser(subparsers: Any) -> argparse.ArgumentParser:
    """Add ``reproduce FIGURE --out DIR [--n N] [--cases DIR] [--quiet]`` to ``subparsers``."""
    p = subparsers.add_parser("reproduce", help="rerun the seed's cases and draw one of its figures")
    p.add_argument("figure", choices=list(FIGURES), help="seed figure to reproduce")
    p.add_argument("--out", required=True, metavar="DIR", help="folder for the figures and the results (.nc)")
    p.add_argument("--n", type=int, default=None, metavar="N",
                   help="grid cells per side instead of the seed's 256 (quick preview; dt follows)")
    p.add_argument("--cases", default=None, metavar="DIR", help="folder of the seed_*.toml cases")
    p.add_argument("--quiet", action="store_true", help="no progress bar, no summary")
    p.set_defaults(handler=cli_reproduce)
    return p


def cli_reproduce(args: argparse.Namespace) -> int:
    """``viscontact reproduce``: run, draw, list the files written. Errors propagate (ParameterError,
    ConvergenceError, ...) for the caller's handler to turn into one line and an exit status."""
    started = _time.perf_counter()
    bar = None
    progress = None
    if not args.quiet and sys.stderr.isatty():
        from tqdm import tqdm

        bar = tqdm(total=None, file=sys.stderr, unit="step", dynamic_ncols=True, leave=False)

        def progress(name: str, done: int, total: int) -> None:
            if bar.total != total or bar.desc != name:
                bar.reset(total=total)
                bar.set_description(name)
            bar.update(done - bar.n)
    try:
        paths = reproduce(args.figure, args.out, n=args.n, progress=progress,
                          cases_dir=getattr(args, "cases", None))
    finally:
        if bar is not None:
            bar.close()
    if not args.quiet:
        for path in paths:
            print(path)
        print(f"{args.figure}: {len(paths)} files in {args.out} ({_time.perf_counter() - started:.1f} s)")
    return 0
