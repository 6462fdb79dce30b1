"""Running the shipped seed cases of a figure, saving and reusing their results, drawing the figure.

Each case of a figure (:data:`~viscontact.reproduce.figures.FIGURES`) runs from ``cases/``
(``seed_*.toml``; see their header comments for the seed's parameters), is saved as
``<case>.nc`` in the output folder, and the figure is drawn from those Datasets only. A saved
result whose stored case text is that of the case to run (same overrides) is reused instead of
being computed again, so ``fig8`` after ``fig6`` and ``fig7`` costs nothing.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import ParameterError
from .figures import FIGURES

if TYPE_CHECKING:
    import xarray as xr

    from ..case import Case

__all__ = ["draw", "find_cases_dir", "load_seed_case", "record_every", "reproduce", "run_seed_cases", "time_scale"]

#: progress(case_name, steps_done, steps_total)
Progress = Callable[[str, int, int], None]

#: fewest points wanted on a time curve (mu_app) when fields are recorded sparsely
MIN_CURVE_POINTS = 40


def find_cases_dir(cases_dir: str | Path | None = None) -> Path:
    """The folder holding ``seed_*.toml``: ``cases_dir``, else ``./cases``, else the cases shipped
    with the package (:func:`viscontact.shipped.shipped_cases_dir`)."""
    from ..shipped import shipped_cases_dir

    candidates = [Path(cases_dir)] if cases_dir is not None else [Path.cwd() / "cases", shipped_cases_dir()]
    for folder in candidates:
        if (folder / "seed_table1_v0.8.toml").is_file():
            return folder
    raise ParameterError("--cases", "no folder with the shipped seed_*.toml cases found (looked in "
                         + ", ".join(str(c) for c in candidates) + "); pass cases_dir / --cases")


def time_scale(case: Case) -> float:
    """tau [s], the unit of the figures' times: the shortest creep retardation time of the case's
    material (the ``retardation_time`` attribute of its results; the Zener retardation time).

    Raises
    ------
    ParameterError
        An elastic material: it has no time scale to draw the seed's times in.
    """
    retardation_times = case.material.build().creep.retardation_times
    if retardation_times.size == 0:
        raise ParameterError("material.type", "the seed's figures are drawn at times in units of the "
                             "retardation time; an elastic material has none")
    return float(retardation_times.min())


def record_every(case: Case, times_tau: Sequence[float]) -> int:
    """Largest recording stride (``output.every``) that records every time of ``times_tau`` [tau,
    see :func:`time_scale`] and keeps at least :data:`MIN_CURVE_POINTS` points on time curves.

    Partial-slip runs record every step so that ``t_gross_sliding`` (first recorded gross-sliding
    time) is exact to one step."""
    if case.tangential.mode == "partial_slip" or not times_tau:
        return 1
    dt = case.default_dt()
    tau = time_scale(case)
    n_steps = math.floor(case.time.t_end / dt + 1e-9) + 1
    every = 0
    for t in times_tau:
        every = math.gcd(every, round(t * tau / dt))
    every = max(every, 1)
    while every > 1 and n_steps / every < MIN_CURVE_POINTS:
        every = next(d for d in range(every - 1, 0, -1) if every % d == 0)
    return every


def load_seed_case(name: str, cases_dir: Path, n: int | None, times_tau: Sequence[float]) -> Case:
    """The shipped case ``name`` with ``grid.n = n`` (when given; ``time.dt`` follows the grid) and
    the ``output.every`` of :func:`record_every`."""
    from ..case import load_case

    case = load_case(cases_dir / f"{name}.toml")
    if n is not None:
        case = case.with_overrides({"grid.n": int(n)})
    every = record_every(case, times_tau)
    return case.with_overrides({"output.every": every}) if every != case.output.every else case


def _cached(path: Path, case_text: str) -> xr.Dataset | None:
    """The saved result at ``path`` when it is complete and was computed from ``case_text``."""
    if not path.is_file():
        return None
    from ..results import open_result

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
    from .. import api
    from ..results import write_netcdf

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    folder = find_cases_dir(cases_dir)
    cases = {name: load_seed_case(name, folder, n, times_tau) for name in names}  # every error first
    results: dict[str, xr.Dataset] = {}
    for name, case in cases.items():
        path = out_dir / f"{name}.nc"
        ds = _cached(path, case.text) if reuse else None
        if ds is None:
            callback = (lambda done, total, _name=name: progress(_name, done, total)) if progress else None
            ds = api.run(case, progress=callback)
            write_netcdf(ds, path, force=True)
        results[name] = ds
    return results


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
    from ..plotting import pyplot

    if figure not in FIGURES:
        raise ParameterError("figure", f"must be one of {', '.join(FIGURES)}, got {figure!r}")
    if n is not None and (int(n) != n or n < 8):
        raise ParameterError("--n", f"must be an integer >= 8 (grid cells per side), got {n!r}")
    pyplot()  # fail before computing when matplotlib is missing
    spec = FIGURES[figure]
    runs = run_seed_cases(spec.cases, out_dir, n=n, times_tau=spec.times_recorded, cases_dir=cases_dir,
                          progress=progress)
    return draw(figure, runs, out_dir) + [Path(out_dir) / f"{name}.nc" for name in spec.cases]


def draw(figure: str, runs: dict[str, Any], out_dir: str | Path) -> list[Path]:
    """Draw ``figure`` from saved results ``runs`` (keyed by case name) into ``out_dir``."""
    spec = FIGURES[figure]
    return spec.render({name: runs[name] for name in spec.cases}, spec, Path(out_dir))
