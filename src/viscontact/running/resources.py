"""Estimates of what a run will need — result size, checkpoint size, peak memory, run time —
checked before it starts.

Sizes are upper bounds for float64 data without compression (netCDF compression usually shrinks
the pressure and shear fields, which are zero outside the contact, several times). A run whose
estimate exceeds what the machine has (free disk, free memory) or :data:`MAX_RUN_SECONDS` is
refused unless forced (``--force``); then it is a warning.
"""
from __future__ import annotations

import functools
import math
import os
import shutil
import time
from dataclasses import dataclass
from pathlib import Path

from viscontact.errors import ParameterError, warn_caller
from viscontact.io.output_files import format_size
from viscontact.io.streaming import record_bytes, recorded_steps, stream_bytes
from viscontact.problem.problem import Problem

#: the run time [s] is START_SECONDS + SETUP_TRANSFORMS t plus, for every step, STEP_SECONDS[mode] +
#: (FULL_TRANSFORMS[mode] + WINDOW_TRANSFORMS[mode] share) t (PERIODIC_TRANSFORMS times more on a periodic grid), where t is the
#: time of one forward and inverse transform pair of the run's (padded) grid, measured on the machine
#: that estimates (:func:`transform_seconds`): the step's cost is a number of transform pairs (CG
#: iterations x products, the coupling passes of partial slip) and a fixed part (bookkeeping, the
#: record). The counts are fitted to the shipped cases'
#: ``viscontact run`` on the Zen 5 VM of 2026-11-28 (``benchmarks/bench_estimate.py``, BENCHMARKS.md).
START_SECONDS = 0.7
SETUP_TRANSFORMS = 20.0
#: a step's fixed part [s] by tangential mode (the coupling passes of gross sliding and partial slip
#: each add their own bookkeeping)
STEP_SECONDS = {"none": 3.5e-3, "frictionless_sliding": 3.5e-3, "gross_sliding": 6e-3, "partial_slip": 8e-3,
                "rolling": 8e-3}
#: transform pairs of a step by tangential mode on the whole grid (the check of the support window's
#: solution, the coupling passes' products) and on the support window, counted there in whole-grid
#: pairs times the window's share of the cells ((m/n)^2, :func:`window_cells`); rolling under a held
#: creepage counts as partial slip (not fitted: no shipped case measured it)
FULL_TRANSFORMS = {"none": 1.2, "frictionless_sliding": 1.2, "gross_sliding": 7.0, "partial_slip": 10.0,
                   "rolling": 10.0}
WINDOW_TRANSFORMS = {"none": 8.0, "frictionless_sliding": 14.0, "gross_sliding": 18.0, "partial_slip": 18.0,
                     "rolling": 18.0}
#: a periodic grid's step in its own (unpadded, a quarter of the cells) transform pairs: that many
#: times more of them, a rough surface's many patches taking more CG iterations
PERIODIC_TRANSFORMS = 5.0
#: above this side the transform pair is timed at this side and scaled by n^2 log2(2n) (a dry run of
#: a huge grid allocates no huge field)
TIMED_SIDE_LIMIT = 512
#: runs estimated to take longer than this [s] are refused unless forced
MAX_RUN_SECONDS = 24 * 3600.0
#: runs estimated (on the CPU) to take longer than this [s] are refused even when forced: a year
MAX_FORCED_RUN_SECONDS = 365 * 24 * 3600.0
#: a run's memory before its arrays [bytes]: the interpreter with numpy, scipy.fft, h5py, pydantic and
#: the solver imported; a run loads no xarray, and no scipy.optimize, .linalg, .sparse or .spatial
#: (imported where used: 87 MiB measured for the creep case's 32^2 ``viscontact run`` on 2026-11-28,
#: 112 MiB before; BENCHMARKS.md)
BASE_MEMORY = 91e6
#: what importing SurfaceTopography adds to a run [bytes] (scipy.stats, .signal, .interpolate, .optimize
#: and .io with it), for a case whose surface it made (``indenter.shape = "self_affine"`` or
#: ``"topography"``): the shipped rough periodic case's 32^2 ``viscontact run`` peaks 114 MiB above the
#: creep case's (2026-11-28; 87 MiB while the creep case imported scipy.optimize too)
TOPOGRAPHY_IMPORT_MEMORY = 120e6
#: padded (2n)^2 float64 temporaries a step holds at once beside the kept arrays (the zero-block
#: transforms' half spectra, the CG's products); 2.5 traced (``tracemalloc``) at 512^2 for creep
#: indentation and sliding, 2026-11-28
PADDED_TEMPORARIES = 3
#: n x n work fields of the solver beside the history (warm start, gap, residual, search direction...)
WORK_FIELDS = 16
#: a result file's layout before its first record (variables, attributes, the case text) [bytes]
LAYOUT_BYTES = 64 * 1024


def run_seconds(steps: int, mode: str, transform: float, periodic: bool = False, share: float = 1.0) -> float:
    """The run time [s] of ``steps`` steps of tangential ``mode`` on a grid (``periodic`` or not) whose
    transform pair takes ``transform`` seconds (:func:`transform_seconds`) and whose support windows
    hold ``share`` of the cells, start included (:data:`START_SECONDS` ... :data:`PERIODIC_TRANSFORMS`)."""
    pairs = (FULL_TRANSFORMS[mode] + WINDOW_TRANSFORMS[mode] * share) * (PERIODIC_TRANSFORMS if periodic else 1.0)
    return START_SECONDS + SETUP_TRANSFORMS * transform + steps * (STEP_SECONDS[mode] + pairs * transform)


@functools.lru_cache(maxsize=32)
def _timed_pair(n: int, periodic: bool, workers: int, rows: int | None = None) -> float:
    """Best of a few forward + inverse transform pairs of an n x n field (``rows`` x n: a line grid's
    one row) on the run's grid [s]."""
    import numpy as np
    import scipy.fft

    from viscontact.numerics.fftbackends import ZeroBlockTransforms, fft_keywords

    rows = n if rows is None else rows
    field = np.random.default_rng(0).random((rows, n))
    if periodic:
        kw = fft_keywords(scipy.fft, workers, n * n)

        def pair():
            scipy.fft.irfft2(scipy.fft.rfft2(field, **kw), s=(n, n), overwrite_x=True, **kw)
    else:
        transforms = ZeroBlockTransforms(n, workers, rows=rows)

        def pair():
            transforms.inverse(transforms.forward(field))
    pair()  # the plan
    best, spent = math.inf, 0.0
    for rep in range(5):
        start = time.perf_counter()
        pair()
        took = time.perf_counter() - start
        best, spent = min(best, took), spent + took
        if rep >= 2 and spent > 0.03:
            break
    return best


def transform_seconds(problem: Problem) -> float:
    """One forward and inverse transform pair of ``problem``'s grid on this machine [s]: timed (a few
    pairs, the best; cached per size in the process) with ``scipy.fft`` and the run's threads
    (``solver.workers``; the pyFFTW backend's plans are not made for it), on the padded DC-FFT grid or
    the periodic one; above :data:`TIMED_SIDE_LIMIT` timed there and scaled by n^2 log2(2n)."""
    n, periodic, workers = problem.grid.n, problem.grid.periodic, problem.solver.workers
    if problem.grid.dimension == 1:  # a line grid's 1-D transforms: timed at its own size
        return _timed_pair(n, periodic, workers, 1)
    side = min(n, TIMED_SIDE_LIMIT)
    work = (n * n * math.log2(2 * n)) / (side * side * math.log2(2 * side))
    return _timed_pair(side, periodic, workers) * work


def available_cores() -> int:
    """Cores available to this process (its CPU affinity where the system has one)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


@dataclass(frozen=True)
class Estimate:
    """``result_bytes``: the result file (uncompressed); ``peak_memory_bytes``: the process at its peak;
    ``records``: how many time entries the result holds; ``checkpoint_bytes``: one checkpoint (the
    solver state only: the records are in the streamed result); ``seconds``: the run time on this machine
    (:func:`run_seconds`); ``device_bytes``: the solver's arrays alone (kernels, histories, work fields,
    support windows: what ``solver.device = "gpu"`` holds on the device), without the interpreter and
    the records."""

    result_bytes: int
    peak_memory_bytes: int
    records: int
    checkpoint_bytes: int = 0
    seconds: float = 0.0
    device_bytes: int = 0

    def disk_bytes(self, checkpoints: bool) -> int:
        """Disk the run needs at its peak: the result, and with checkpoints the last one twice (the
        new one is written beside the old before it replaces it)."""
        return self.result_bytes + (2 * self.checkpoint_bytes if checkpoints else 0)


def estimate(problem: Problem, *, topography: bool | None = None, transform: float | None = None) -> Estimate:
    """Result size and peak memory of the transient run of ``problem``.

    Result: what :mod:`viscontact.io.streaming` claims on disk for it (:func:`stream_bytes`) plus the
    file's layout. Memory (``viscontact run`` streams its records; the peak still grows over the
    first part of a run as the contact grows and the support windows with it), named terms on top of
    :data:`BASE_MEMORY`:

    * the records: the one queued for writing, its shuffled and compressed copies on the
      compression thread, and the one being computed (:mod:`viscontact.io.streaming`);
    * the history (2 x retardation modes, more for bodies of several terms:
      :meth:`viscontact.bodies.base.Body.size`) and :data:`WORK_FIELDS` n x n work fields;
    * per influence kernel :func:`kernel_bytes` (its (2n)^2 real-space copy, its (2n)(n + 1) complex
      spectrum, its preconditioner), and :data:`PADDED_TEMPORARIES` padded (2n)^2 temporaries of a step;
    * on a DC-FFT grid, the products and response history the state carries, and the support
      windows: the cropped self kernels of the :data:`~viscontact.bodies.compliance.WINDOWS_KEPT` sides used
      last and of one more being built (with its crops), each side at most the box of the widest
      contact foreseen (:func:`window_cells`) and, with ``solver.mixed_precision``, the complex64
      spectra of the self kernels;
    * with ``topography`` (default ``problem.surface_topography``: the problem of a case whose
      surface SurfaceTopography makes), :data:`TOPOGRAPHY_IMPORT_MEMORY`;
    * with ``output.subsurface_depths``, the subsurface stresses' padded transforms (the pressure's,
      and q_x's where the mode has a shear traction) and their chunked temporaries
      (:func:`viscontact.physics.subsurface.working_bytes`), on top of it all (measured:
      the peak RSS of the shipped ``creep_subsurface_stress`` case grows by the stresses' own peak).

    Measured (``benchmarks/bench_memory.py``, ``viscontact run``'s VmHWM, 2026-11-28): creep
    indentation 254 MiB at 512^2 x 161 steps and 686 MiB at 1024^2 x 641 (estimated 273, 763), seed
    Table 1's sliding 276 MiB at 512^2 x 321 and 813 MiB at 1024^2 x 641 (294, 848), the rough
    periodic case 333 and 756 MiB at 512^2 and 1024^2 (355, 819): 4-11 % above.

    Run time: :func:`run_seconds` with the transform pair timed here (:func:`transform_seconds`) or
    ``transform`` [s].

    Checkpoint: the solver state only (history, the last step's fields and, on a DC-FFT grid, the
    products and the response history the state carries; with ``tangential.slip = "incremental"``
    its s_x).
    """
    n = problem.grid.n
    cells = problem.grid.rows * n  # n x n, or a line grid's n
    steps = problem.time.n_steps
    records = recorded_steps(problem)
    per_record = record_bytes(problem)
    result = stream_bytes(problem, records) + len(problem.title) + LAYOUT_BYTES
    modes, per_component = problem.body.size()  # nu(t), layers: more histories and kernels
    kernels = per_component * (4 if problem.tangential.mode in ("partial_slip", "gross_sliding", "rolling") else 1)
    # carried by the state of a DC-FFT grid: the warm start's two products and, for a body of one
    # kernel per component, the response history (M + 1 fields,
    # :meth:`viscontact.bodies.compliance.Compliance.initial_response`)
    from viscontact.bodies.compliance import RESPONSE_MODES

    response = modes + 1 if per_component == 1 and modes <= RESPONSE_MODES else 0
    carried = 0 if problem.grid.periodic else (2 + response) * 8 * cells
    # the incremental slip's s_x, rolling's u_x
    slip = 8 * cells if problem.tangential.incremental_slip or problem.tangential.rolls else 0
    solver = (2 * 2 * modes + WORK_FIELDS) * 8 * cells + 2 * (carried + slip) \
        + kernels * kernel_bytes(n, problem.grid.rows) + PADDED_TEMPORARIES * 4 * cells * 8
    if not problem.grid.periodic and problem.grid.dimension == 2:  # support windows: cropped self kernels
        from viscontact.bodies.compliance import WINDOWS_KEPT

        self_kernels = 2 if problem.tangential.mode in ("partial_slip", "rolling") else 1
        # mixed precision: each self kernel also has a complex64 spectrum, on the grid and the windows
        single_bytes = 2 * n * (n + 1) * 8 if problem.solver.mixed_precision else 0
        solver += (WINDOWS_KEPT + 1) * self_kernels * per_component * single_bytes
        # the windows kept, and a new one built before the oldest is dropped, with its cropped kernels
        m = window_cells(problem)
        solver += (WINDOWS_KEPT + 1) * self_kernels * per_component * kernel_bytes(m) \
            + self_kernels * per_component * 4 * m * m * 8
    arrays = solver
    if topography is None:
        topography = problem.surface_topography
    if topography:  # the case's surface (self-affine, a measured topography) imports SurfaceTopography
        solver += TOPOGRAPHY_IMPORT_MEMORY
    state = (2 * modes + 8) * 8 * cells + carried + slip
    depths = problem.output.subsurface_depths
    if depths:  # computed once the steps are done, from the recorded tractions: on top of the run's peak
        from viscontact.physics.subsurface import working_bytes

        solver += working_bytes(problem.grid, max(depths), 2 if problem.tangential.has_shear else 1)
        arrays += working_bytes(problem.grid, max(depths), 2 if problem.tangential.has_shear else 1)
    if transform is None:
        transform = transform_seconds(problem)
    share = 1.0 if problem.grid.periodic or problem.grid.dimension == 1 else ((window_cells(problem) or n) / n) ** 2
    seconds = run_seconds(steps, problem.tangential.mode, transform, problem.grid.periodic, share)
    return Estimate(int(result), int(3 * per_record + solver + BASE_MEMORY), int(records), int(state), seconds,
                    int(arrays))


def kernel_bytes(m: int, rows: int | None = None) -> int:
    """What one influence kernel of an m x m grid (or support window) holds [bytes]: its centred (2m)^2
    real-space copy, its (2m)(m + 1) complex spectrum and its preconditioner's m (m/2 + 1) symbol; of a
    line grid (``rows = 1``): its 2m offsets, its (m + 1) spectrum, its (m/2 + 1) symbol."""
    if rows == 1:
        return 2 * m * 8 + (m + 1) * 16 + (m // 2 + 1) * 8
    return 4 * m * m * 8 + 2 * m * (m + 1) * 16 + m * (m // 2 + 1) * 8


def window_cells(problem: Problem) -> int:
    """Side [cells] of the largest support window a run of ``problem`` keeps: the box
    (:func:`viscontact.numerics.support_window.window_side`) of the widest contact that
    :func:`viscontact.running.guards.contact_estimate` foresees (its ``largest`` radius, a diameter of
    cells), or :data:`~viscontact.numerics.support_window.FULL_FRACTION` of the grid where it foresees none;
    0 where the box of that contact is the whole grid (no window is made)."""
    from viscontact.numerics.support_window import FULL_FRACTION, window_side
    from viscontact.running.guards import contact_estimate

    n = problem.grid.n
    contact = contact_estimate(problem)
    if contact is None or not math.isfinite(contact.largest):
        return int(FULL_FRACTION * n)
    cells = 2 * contact.largest / problem.grid.spacing  # beyond 2 n (or not finite) the box is the whole grid
    return window_side(math.ceil(cells), n) or 0 if cells < 2 * n else 0


def available_memory() -> int | None:
    """Physical memory available now [bytes], or None where the system does not say."""
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return None


def check_resources(problem: Problem, out: str | Path, *, force: bool = False, checkpoints: bool = False,
                    written_bytes: int = 0, topography: bool | None = None) -> Estimate:
    """Refuse a run that needs more than the machine has: its result (and, with ``checkpoints``,
    its checkpoints) beyond the free disk of ``out``, its memory beyond the free RAM (with
    ``solver.device = "gpu"`` its arrays, :attr:`Estimate.device_bytes`, beyond the device's free
    memory as well), its run time beyond :data:`MAX_RUN_SECONDS`. :class:`ParameterError` naming the key to change, or with
    ``force`` a warning; with ``solver.device = "gpu"`` the memory and the run time (the CPU run's,
    :func:`describe`) only warn. ``written_bytes``: what a resumed run's streamed file already holds on
    that disk [bytes] (not needed again). ``topography``: the case's surface imports SurfaceTopography
    (:func:`estimate`; default ``problem.surface_topography``)."""
    est = estimate(problem, topography=topography)
    folder = Path(out).resolve().parent
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    free = shutil.disk_usage(folder).free
    needed = max(est.disk_bytes(checkpoints) - written_bytes, 0)
    what = _records_of(problem, est)
    if checkpoints:
        what += f", and checkpoints of about {format_size(est.checkpoint_bytes)} written beside each other"
    problems = []
    if needed > free:
        problems.append(("output.every", f"the result needs about {format_size(needed)} ({what}) but {folder} has "
                         f"{format_size(free)} free: record fewer times ([output] every = k) or fewer fields "
                         "([output] fields = [\"pressure\"])"))
    ram = available_memory()
    if ram is not None and est.peak_memory_bytes > ram:
        problems.append(("grid.n", f"the run may need about {format_size(est.peak_memory_bytes)} of memory, "
                         f"{format_size(ram)} is "
                         "free: thin the output ([output] every, fields) or use a smaller grid.n"))
    device_problems = []  # what the device itself lacks: refused like the CPU's (--force warns)
    if problem.solver.device == "gpu":  # its free memory (None: no CuPy or no device, refused by the machine check)
        from viscontact.numerics.arrays import device_free_memory

        device_free = device_free_memory()
        if device_free is not None and est.device_bytes > device_free:
            device_problems.append(("grid.n", (
                f"the run may need about {format_size(est.device_bytes)} of GPU memory, {format_size(device_free)} "
                "is free on the device: use a smaller grid.n, free the device, or solver.device = 'cpu'")))
    if est.seconds > MAX_RUN_SECONDS:
        problems.append(("time.t_end", f"{problem.time.n_steps} steps on {_cells_text(problem.grid)} would take about "
                         f"{_duration(est.seconds)}: check time.t_end and time.dt (and grid.n)"))
    # a GPU run's memory and time are not estimated: the CPU run's, which hold its fields in host memory
    # and take 5-11 times as long at 1024^2 and above (docs/gpu.md), refuse nothing; the disk is the same
    cpu_only = {"grid.n", "time.t_end"} if problem.solver.device == "gpu" else set()
    if est.seconds > MAX_FORCED_RUN_SECONDS and problem.solver.device != "gpu":
        raise ParameterError("time.t_end", f"{problem.time.n_steps} steps on {_cells_text(problem.grid)} would take about "
                             f"{_duration(est.seconds)}, more than a year, which not even --force runs: check "
                             "time.t_end and time.dt (and grid.n)")
    for key, message in problems + device_problems:
        if key in cpu_only and (key, message) not in device_problems:
            warn_caller(f"{key}: {message} (the CPU run's estimate: solver.device = 'gpu' runs it)")
        elif not force:
            raise ParameterError(key, f"{message} (--force runs it anyway)")
        else:
            warn_caller(f"{key}: {message}")
    return est


def _cells_text(grid) -> str:
    """``256^2 cells``, or ``4096 cells of a line contact``."""
    return f"{grid.n}^2 cells" if grid.dimension == 2 else f"{grid.n} cells of a line contact"


def _duration(seconds: float) -> str:
    for unit, length in (("days", 86400.0), ("h", 3600.0), ("min", 60.0)):
        if seconds >= length:
            return f"{seconds / length:.3g} {unit}"
    return f"{seconds:.2g} s"


def _records_of(problem: Problem, est: Estimate) -> str:
    """``161 records of pressure, shear_x``, or ``of the histories only`` (``output.fields = []``)."""
    fields = ", ".join(problem.output.fields) or "the histories only (output.fields = [])"
    return f"{est.records} records of {fields}"


def describe(problem: Problem, est: Estimate) -> str:
    """One paragraph for ``viscontact run --dry-run`` (its memory and run time those of a CPU run)."""
    g, t = problem.grid, problem.time
    return (f"{problem.title or 'case'}: {g.n} x {g.rows} cells of {g.spacing * 1e6:.3g} um, {t.n_steps} steps of "
            f"{t.dt:.4g} s ({problem.tangential.mode}, {problem.normal.control} control, scheme {t.scheme}); "
            f"result about {format_size(est.result_bytes)} ({_records_of(problem, est)}), "
            f"peak memory about {format_size(est.peak_memory_bytes)}, run time about {_duration(est.seconds)}"
            + ("; memory and run time are the CPU run's (solver.device = 'gpu': not estimated for the GPU, "
               "see docs/gpu.md)" if problem.solver.device == "gpu" else ""))
