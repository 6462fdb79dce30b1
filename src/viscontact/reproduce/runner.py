"""Running the shipped seed cases of a figure, saving and reusing their results, drawing the figure.

Each case of a figure (:data:`~viscontact.reproduce.figures.FIGURES`) runs from ``cases/``
(``seed_*.toml``; see their header comments for the seed's parameters), is saved as
``<case>.nc`` in the output folder, and the figure is drawn from those Datasets only. A saved
result whose stored case text is that of the case to run (same overrides) is reused instead of
being computed again, so ``fig8`` after ``fig6`` and ``fig7`` costs nothing. Each saved result is
marked as reproduce's own (global attribute :data:`WRITTEN_BY` = :data:`REPRODUCE`), and
``<case>.nc`` replaces only such a result of the same shipped case: any other file there (a
``viscontact run`` of that very case included) is refused, before the first case runs
(:func:`check_outputs`).
"""
from __future__ import annotations

import errno
import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from viscontact.errors import ParameterError
from viscontact.reproduce.figures import FIGURES

if TYPE_CHECKING:
    import xarray as xr

    from viscontact.io.case import Case

__all__ = ["check_outputs", "draw", "find_cases_dir", "load_seed_case", "record_every", "reproduce", "run_seed_cases",
           "stable_steps", "time_scale"]

#: the global attribute marking the results ``reproduce`` saved, and its value: the only files it replaces
WRITTEN_BY, REPRODUCE = "written_by", "viscontact reproduce"

#: progress(case_name, steps_done, steps_total)
Progress = Callable[[str, int, int], None]

#: fewest points wanted on a time curve (mu_app) when fields are recorded sparsely
MIN_CURVE_POINTS = 40
#: largest step of the seed's constant scheme, as a fraction of its stability limit (see stable_steps)
STABLE_FRACTION = 0.5


def find_cases_dir(cases_dir: str | Path | None = None) -> Path:
    """The folder holding ``seed_*.toml``: ``cases_dir``, else ``./cases``, else the cases shipped
    with the package (:func:`viscontact.io.shipped.shipped_cases_dir`)."""
    from viscontact.io.shipped import shipped_cases_dir

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


def stable_steps(case: Case) -> tuple[Case, str]:
    """The case with its time step cut so that the seed's piecewise-constant scheme runs at no more
    than half its stability limit, and a note naming the change ("" when none was needed).

    Past the limit that scheme amplifies any disturbance step by step; close below it the disturbance
    alternates in sign and decays slowly, which draws an oscillating curve (``--n 64`` previews).
    At half the limit it decays by a factor 0.03 (G(0)/G(inf) = 10) to 0.3 (= 3) per step. A case
    whose ``time.dt`` follows the grid gets ``tangential.steps_per_cell`` k times larger, one that
    gives ``time.dt`` a k times smaller one. The linear scheme is stable for every step. Then (either
    scheme) the step is halved until :func:`viscontact.solvers.time_step_error.time_step_error` is under the guards'
    warning limit, so that a coarse preview is neither refused nor warned about.
    """
    from dataclasses import replace

    from viscontact.numerics.schemes import stable_step_limit
    from viscontact.running.guards import TIME_WARNING_LIMIT
    from viscontact.solvers.time_step_error import time_step_error

    dt = case.default_dt()
    k, why = 1, ""
    if case.time.scheme == "constant":
        limit = stable_step_limit(case.material.build().creep, "constant")
        if math.isfinite(limit):
            k = max(1, math.ceil(dt / (STABLE_FRACTION * limit) - 1e-9))
            why = (f"dt = {dt * 1e3:.3g} ms is over {STABLE_FRACTION:g} of the stability limit "
                   f"{limit * 1e3:.3g} ms of time.scheme = 'constant'") if k > 1 else ""
    problem = case.to_problem()
    for _ in range(10):  # then halve dt until the time-step guard (viscontact.running.guards) has nothing to say
        error = time_step_error(replace(problem, time=replace(problem.time, dt=dt / k)))
        if error <= TIME_WARNING_LIMIT:
            break
        k *= 2
        why = why or f"dt = {dt * 1e3:.3g} ms misses the material's response by more than {100 * TIME_WARNING_LIMIT:g} %"
    if k <= 1:
        return case, ""
    if case.time.dt is None:
        key, value = "tangential.steps_per_cell", case.tangential.steps_per_cell * k
    else:
        key, value = "time.dt", case.time.dt / k
    note = f"{key} = {value:g}: {why} (now dt = {dt / k * 1e3:.3g} ms)"
    return case.with_overrides({key: value}), note


def load_seed_case(name: str, cases_dir: Path, n: int | None, times_tau: Sequence[float],
                   overrides: Mapping[str, Any] | None = None) -> tuple[Case, str]:
    """The shipped case ``name`` with ``overrides`` (dotted keys), ``grid.n = n`` (when given;
    ``time.dt`` follows the grid), a stable step (:func:`stable_steps`) and the ``output.every`` of
    :func:`record_every`; and the note of :func:`stable_steps`."""
    from viscontact.io.case import load_case

    case = load_case(cases_dir / f"{name}.toml")
    if n is not None and "grid.n" in (overrides or {}) and overrides["grid.n"] != n:  # one would be ignored
        raise ParameterError("--set", f"grid.n = {overrides['grid.n']!r} contradicts --n {n}: give the grid "
                             "size once (--n)")
    given = {**(overrides or {}), **({"grid.n": int(n)} if n is not None else {})}
    if given:
        try:
            case = case.with_overrides(given)
        except ParameterError as exc:
            raise ParameterError(exc.key, f"{exc.message} (in case {name})") from None
    case, note = stable_steps(case)
    every = record_every(case, times_tau)
    return (case.with_overrides({"output.every": every}) if every != case.output.every else case), note


def _saved(path: Path) -> xr.Dataset | None:
    """The result saved at ``path``; None when there is no file or it is not a readable result."""
    if not path.is_file():
        return None
    from viscontact.io.netcdf import open_result

    try:
        return open_result(path)
    except (OSError, ValueError):
        return None


def _cached(path: Path, case_text: str) -> xr.Dataset | None:
    """The saved result at ``path`` when it is complete and was computed from ``case_text``."""
    ds = _saved(path)
    if ds is not None and ds.attrs.get("case") == case_text and int(ds.attrs.get("complete", 0)) == 1:
        return ds
    return None


def _own_result(path: Path, shipped_text: str) -> bool:
    """Whether ``path`` is a result ``reproduce`` saved (attribute :data:`WRITTEN_BY`) of the case file
    ``shipped_text``, at any ``--n`` or ``--set`` (its stored case text is that text, the overrides
    appended as comments)."""
    ds = _saved(path)
    return (ds is not None and ds.attrs.get(WRITTEN_BY) == REPRODUCE
            and str(ds.attrs.get("case", "")).startswith(shipped_text.rstrip("\n")))


def check_outputs(out_dir: Path, shipped: Mapping[str, str], inputs: Iterable[Path]) -> dict[str, Path]:
    """Refuse, before the first case runs, what ``reproduce`` must not write into ``out_dir``.

    ``out_dir`` must be a folder or one that can be made. Each case's result ``<case>.nc`` is
    replaced only when ``reproduce`` saved it (attribute :data:`WRITTEN_BY`) from that shipped case,
    at any ``--n`` or ``--set`` (its stored case text starts with the case file's text): any other
    file there, a result of the same case made by ``viscontact run`` included, is never replaced, so
    ``reproduce`` needs no ``--force``. The figures are reproduce's own files and are replaced.

    Parameters
    ----------
    out_dir
        The output folder (``--out``).
    shipped
        Case name -> the text of its case file.
    inputs
        Files the cases read (never replaced).

    Returns
    -------
    dict
        Case name -> the path of its result.

    Raises
    ------
    OSError
        Naming the path and saying why.
    """
    from viscontact.io.output_files import check_output_folder, check_output_path

    check_output_folder(out_dir, option="--out")
    inputs = list(inputs)
    paths = {}
    for name, text in shipped.items():
        path = out_dir / f"{name}.nc"
        if path.is_file() and not _own_result(path, text):
            raise FileExistsError(errno.EEXIST, f"exists and is not a result of the shipped case {name} saved by "
                                  "reproduce; reproduce replaces only its own results: move it or choose another --out",
                                  str(path))
        check_output_path(path, force=True, inputs=inputs)
        paths[name] = path
    return paths


def run_seed_cases(names: Sequence[str], out_dir: str | Path, *, n: int | None = None,
                   overrides: Mapping[str, Any] | None = None, times_tau: Sequence[float] = (),
                   cases_dir: str | Path | None = None, progress: Progress | None = None,
                   notify: Callable[[str], None] | None = None, reuse: bool = True) -> dict[str, xr.Dataset]:
    """Run (or reuse) the shipped cases ``names`` and save each as ``out_dir/<name>.nc``.

    Parameters
    ----------
    names
        Case names (file stems in ``cases/``).
    out_dir
        Folder for the result files (created), each marked as reproduce's (attribute
        :data:`WRITTEN_BY`). An existing ``<name>.nc`` is replaced only when reproduce saved it from
        the same shipped case; anything else is refused before the first case runs
        (:func:`check_outputs`).
    n
        Override ``grid.n`` (``time.dt`` follows: one cell of sliding per step).
    overrides
        Dotted case keys set in every case (``{"tangential.friction_coefficient": 0.5}``).
    times_tau
        Times [tau] at which fields must be recorded (sets ``output.every``).
    cases_dir
        Folder of the case files (see :func:`find_cases_dir`).
    progress
        Called as ``progress(name, steps_done, steps_total)``.
    notify
        Called with a line naming each case whose time step was cut (:func:`stable_steps`).
    reuse
        Reuse a complete saved result computed from the same case text.
    """
    from viscontact.io.case import read_input_file
    from viscontact.io.netcdf import write_netcdf
    from viscontact.running import api

    out_dir = Path(out_dir)
    folder = find_cases_dir(cases_dir)
    cases = {name: load_seed_case(name, folder, n, times_tau, overrides) for name in names}  # errors first
    shipped = {name: read_input_file(folder / f"{name}.toml", "case file") for name in names}
    inputs = [folder / f"{name}.toml" for name in names]
    inputs += [path for case, _ in cases.values() for path in case.input_files().values()]
    paths = check_outputs(out_dir, shipped, inputs)  # every output, before the first case runs
    out_dir.mkdir(parents=True, exist_ok=True)
    for name, (_, note) in cases.items():
        if note and notify is not None:
            notify(f"{name}: {note}")
    results: dict[str, xr.Dataset] = {}
    for name, (case, _) in cases.items():
        path = paths[name]
        ds = _cached(path, case.text) if reuse else None
        if ds is None:
            callback = (lambda done, total, _name=name: progress(_name, done, total)) if progress else None
            ds = api.run(case, progress=callback)
            ds.attrs[WRITTEN_BY] = REPRODUCE
            write_netcdf(ds, path, force=True)
        results[name] = ds
    return results


def reproduce(figure: str, out_dir: str | Path, *, n: int | None = None, overrides: Mapping[str, Any] | None = None,
              progress: Progress | None = None, notify: Callable[[str], None] | None = None,
              cases_dir: str | Path | None = None, fmt: str = "png", dpi: int | None = None) -> list[Path]:
    """Run the cases of a seed figure and draw it.

    Parameters
    ----------
    figure
        One of ``fig4``, ``fig6``, ``fig7``, ``fig8``, ``fig9``, ``fig10``.
    out_dir
        Folder for the figure(s) (PNG) and the results (``<case>.nc``; see :func:`check_outputs`).
    n
        Override ``grid.n`` for a quick preview (the seed uses 256; ``time.dt`` follows, cut where the
        seed's scheme would be over half its stability limit or miss the material's response by more
        than the time-step guard's warning limit: :func:`stable_steps`).
    overrides
        Dotted case keys set in every case of the figure.
    progress
        Called as ``progress(case_name, steps_done, steps_total)`` after each time step.
    notify
        Called with a line naming each case whose time step was cut.
    cases_dir
        Folder of the ``seed_*.toml`` cases (default: ``./cases`` or the repository's).
    fmt, dpi
        File format (``png``, ``pdf``, ``svg``) and resolution of the figures.

    Returns
    -------
    list of Path
        The figure files, then the result files.
    """
    from viscontact.plotting import check_format, pyplot

    if figure not in FIGURES:
        raise ParameterError("figure", f"must be one of {', '.join(FIGURES)}, got {figure!r}")
    if n is not None and (int(n) != n or n < 8):
        raise ParameterError("--n", f"must be an integer >= 8 (grid cells per side), got {n!r}")
    pyplot()  # fail before computing when matplotlib is missing
    spec = FIGURES[figure]
    check_format(fmt, dpi)
    runs = run_seed_cases(spec.cases, out_dir, n=n, overrides=overrides, times_tau=spec.times_recorded,
                          cases_dir=cases_dir, progress=progress, notify=notify)
    return draw(figure, runs, out_dir, fmt=fmt, dpi=dpi) + [Path(out_dir) / f"{name}.nc" for name in spec.cases]


def draw(figure: str, runs: Mapping[str, Any], out_dir: str | Path, *, fmt: str = "png",
         dpi: int | None = None) -> list[Path]:
    """Draw ``figure`` from saved results ``runs`` (keyed by case name) into ``out_dir``."""
    from viscontact.plotting import FigureFiles

    spec = FIGURES[figure]
    return spec.render({name: runs[name] for name in spec.cases}, spec, FigureFiles(Path(out_dir), fmt, dpi))
