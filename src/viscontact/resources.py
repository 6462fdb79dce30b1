"""Estimates of what a run will need — result size, checkpoint size, peak memory, run time —
checked before it starts.

Sizes are upper bounds for float64 data without compression (netCDF compression usually shrinks
the pressure and shear fields, which are zero outside the contact, several times). A run whose
estimate exceeds what the machine has (free disk, free memory) or :data:`MAX_RUN_SECONDS` is
refused unless forced (``--force``); then it is a warning.
"""
from __future__ import annotations

import math
import os
import shutil
from dataclasses import dataclass
from pathlib import Path

from .errors import ParameterError, warn_caller
from .problem import Problem

_FIELD_BYTES = {"pressure": 8, "shear_x": 8, "stick": 1, "displacement_z": 8}
#: the run time [s] is START_SECONDS + SETUP_SECONDS_PER_CELL n^2 log2(2n) (imports, kernels, the result's
#: layout) plus, for every step, MODE_STEP_FACTOR[mode] (SECONDS_PER_STEP + SECONDS_PER_CELL_STEP n^2
#: log2(2n)) (a fixed part: bookkeeping, the record; and the FFT-bound part). The step's part is fitted
#: to ``viscontact run``'s creep indentation streamed to a file (201 steps) on the 2-core machine,
#: 2026-11-25: 11.1, 16.4, 46.2, 180 ms a step at n = 64, 128, 256, 512 (the fit: 9.7, 16.4, 46.5, 180 ms);
#: the start and the modes' factors to the shipped cases (``benchmarks/bench_estimate.py``, BENCHMARKS.md):
#: starts of 1.0-1.7 s at n <= 256 and 2.3 s at 512; a step of gross sliding 1.4-2.3 times the creep
#: model's, of partial slip 1.5-2.6 times (its coupling iterations), of indentation and frictionless
#: sliding 0.24-1.13 times (a contact smaller than the grid: the support window).
SECONDS_PER_STEP = 7.8e-3
SECONDS_PER_CELL_STEP = 6.56e-8
START_SECONDS = 1.0
SETUP_SECONDS_PER_CELL = 5e-7
MODE_STEP_FACTOR = {"none": 1.0, "frictionless_sliding": 1.0, "gross_sliding": 1.8, "partial_slip": 2.5}
#: runs estimated to take longer than this [s] are refused unless forced
MAX_RUN_SECONDS = 24 * 3600.0
#: a run's memory before its arrays [bytes]: the interpreter with numpy, scipy, h5py, pydantic and
#: the solver imported; a run loads no xarray (108 MiB measured for a 32^2 ``viscontact run``,
#: 2026-11-23; BENCHMARKS.md)
BASE_MEMORY = 115e6
#: HDF5 bookkeeping one streamed record may add (chunk index entries, flushed metadata) [bytes]
RECORD_OVERHEAD = 4096
#: a node of the chunk index of an HDF5 variable (B-tree; about 2 KiB measured) [bytes], an upper bound
INDEX_NODE_BYTES = 4096
#: what finishing a streamed result writes beyond its records (attributes, scale variables) [bytes]
FINISH_BYTES = 64 * 1024
#: a result file's layout before its first record (variables, attributes, the case text) [bytes]
LAYOUT_BYTES = 64 * 1024


def run_seconds(n: int, steps: int, mode: str) -> float:
    """The run time [s] of ``steps`` steps of tangential ``mode`` on an n x n grid on the reference
    machine, start included (:data:`START_SECONDS` ... :data:`MODE_STEP_FACTOR`): within a factor of 2
    of the shipped cases' runs, less where the contact fills a smaller part of the grid."""
    fft_bound = n * n * math.log2(2 * n)
    step = MODE_STEP_FACTOR[mode] * (SECONDS_PER_STEP + SECONDS_PER_CELL_STEP * fft_bound)
    return START_SECONDS + SETUP_SECONDS_PER_CELL * fft_bound + steps * step



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
    solver state only: the records are in the streamed result); ``seconds``: the run time on the reference
    machine (:func:`run_seconds`)."""

    result_bytes: int
    peak_memory_bytes: int
    records: int
    checkpoint_bytes: int = 0
    seconds: float = 0.0

    def disk_bytes(self, checkpoints: bool) -> int:
        """Disk the run needs at its peak: the result, and with checkpoints the last one twice (the
        new one is written beside the old before it replaces it)."""
        return self.result_bytes + (2 * self.checkpoint_bytes if checkpoints else 0)


def estimate(problem: Problem) -> Estimate:
    """Result size and peak memory of the transient run of ``problem``.

    Result: what :mod:`viscontact.streaming` claims on disk for it (:func:`stream_bytes`) plus the
    file's layout. Memory (``viscontact run`` streams its records: it does not grow with the number
    of steps): the record queued for writing, its shuffled and compressed copies on the compression
    thread, and the record being computed (:mod:`viscontact.streaming`), plus the solver's own arrays: the
    history (2 x retardation modes, more for bodies of several terms:
    :func:`viscontact.substrate.body_size`), a dozen n x n work fields, and per influence kernel its
    (2n)^2 real-space copy, its (2n)(n + 1) complex spectrum, the FFT work arrays and a step's
    padded temporaries (8 (2n)^2 fields), and on a non-periodic grid the support windows' cropped
    self kernels (at most :data:`~viscontact.substrate.WINDOWS_KEPT` sides, each below n) and, with
    ``solver.mixed_precision``, the complex64 spectra of the self kernels, on top of
    :data:`BASE_MEMORY`; with ``output.subsurface_depths``, the subsurface stresses' padded
    transforms and their chunked temporaries (:func:`viscontact.subsurface.working_bytes`), on top
    of it all (measured: the peak RSS of the shipped ``creep_subsurface_stress`` case grows by the
    stresses' own peak). Checkpoint:
    the solver state only (history, the last step's fields and, on a DC-FFT grid, the products and
    the response history the state carries; with ``tangential.slip = "incremental"`` its s_x).
    """
    n = problem.grid.n
    steps = problem.time.n_steps
    records = recorded_steps(problem)
    per_record = record_bytes(problem)
    result = stream_bytes(problem, records) + len(problem.title) + LAYOUT_BYTES
    from .substrate import body_size

    modes, per_component = body_size(problem)  # nu(t), layers: more histories and kernels
    kernels = per_component * (4 if problem.tangential.mode in ("partial_slip", "gross_sliding") else 1)
    kernel_bytes = 4 * n * n * 8 + 2 * n * (n + 1) * 16
    # carried by the state of a DC-FFT grid: the warm start's two products and, for a body of one
    # kernel per component, the response history (M + 1 fields,
    # :meth:`viscontact.substrate.TermSubstrate.initial_response`)
    from .substrate import RESPONSE_MODES

    response = modes + 1 if per_component == 1 and modes <= RESPONSE_MODES else 0
    carried = 0 if problem.grid.periodic else (2 + response) * 8 * n * n
    slip = 8 * n * n if problem.tangential.incremental_slip else 0  # the incremental slip's s_x
    solver = (2 * 2 * modes + 16) * 8 * n * n + 2 * (carried + slip) + kernels * kernel_bytes + 8 * 4 * n * n * 8
    if not problem.grid.periodic:  # support windows: cropped self kernels of the last sides used
        from .substrate import WINDOWS_KEPT

        self_kernels = 2 if problem.tangential.mode == "partial_slip" else 1
        # mixed precision: each self kernel also has a complex64 spectrum, on the grid and the windows
        single_bytes = 2 * n * (n + 1) * 8 if problem.solver.mixed_precision else 0
        solver += (WINDOWS_KEPT + 1) * self_kernels * per_component * single_bytes
        solver += WINDOWS_KEPT * self_kernels * per_component * kernel_bytes
    state = (2 * modes + 8) * 8 * n * n + carried + slip
    depths = problem.output.subsurface_depths
    if depths:  # computed once the steps are done, from the recorded tractions: on top of the run's peak
        from .subsurface import working_bytes

        solver += working_bytes(problem.grid, max(depths))
    seconds = run_seconds(n, steps, problem.tangential.mode)
    return Estimate(int(result), int(3 * per_record + solver + BASE_MEMORY), int(records), int(state), seconds)


def recorded_steps(problem: Problem) -> int:
    """How many time entries the result of ``problem``'s transient run holds (every
    ``output.every``-th step, the last and those at the histories' turning points:
    :meth:`Problem.recorded`)."""
    steps, every = problem.time.n_steps, problem.output.every
    regular = (steps - 1) // every + 1 + (1 if (steps - 1) % every else 0)
    return regular + sum(1 for k in problem.turning_steps if k % every and k != steps - 1)


def record_bytes(problem: Problem) -> int:
    """Upper bound of what one record adds to a streamed result file [bytes]: its fields
    uncompressed, its scalars and :data:`RECORD_OVERHEAD`."""
    from .records import StepRecord

    n = problem.grid.n
    return sum(_FIELD_BYTES.get(f, 8) for f in problem.output.fields) * n * n \
        + 8 * (len(StepRecord.SCALARS) + 2) + RECORD_OVERHEAD


def stream_bytes(problem: Problem, records: int, *, first: int = 0, finishing: bool = True) -> int:
    """Upper bound of what the records ``first .. first + records - 1`` add to a streamed result file
    [bytes]: :func:`record_bytes` each, a new chunk of every time series each
    :data:`~viscontact.results.SERIES_CHUNK` records (and with each, a node of the chunk index of
    every variable along ``t``: :data:`INDEX_NODE_BYTES` each), and with ``finishing``
    :data:`FINISH_BYTES` and the subsurface stresses."""
    from .records import StepRecord
    from .results import SERIES_CHUNK

    chunks = -(-(first + records) // SERIES_CHUNK) - (-(-first // SERIES_CHUNK))
    out = problem.output
    subsurface = 6 * len(out.subsurface_depths) * problem.grid.n * 8 * len(out.subsurface_times or (0,))
    series, fields = len(StepRecord.SCALARS) + 2, len(problem.output.fields)
    return records * record_bytes(problem) \
        + chunks * (series * SERIES_CHUNK * 8 + (series + fields) * INDEX_NODE_BYTES) \
        + (FINISH_BYTES + subsurface if finishing else 0)


def available_memory() -> int | None:
    """Physical memory available now [bytes], or None where the system does not say."""
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return None


def check_resources(problem: Problem, out: str | Path, *, force: bool = False, checkpoints: bool = False,
                    written_bytes: int = 0) -> Estimate:
    """Refuse a run that needs more than the machine has: its result (and, with ``checkpoints``,
    its checkpoints) beyond the free disk of ``out``, its memory beyond the free RAM, its run time
    beyond :data:`MAX_RUN_SECONDS`. :class:`ParameterError` naming the key to change, or with
    ``force`` a warning. ``written_bytes``: what a resumed run's streamed file already holds on
    that disk [bytes] (not needed again)."""
    est = estimate(problem)
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
    if est.seconds > MAX_RUN_SECONDS:
        problems.append(("time.t_end", f"{problem.time.n_steps} steps on {problem.grid.n}^2 cells would take about "
                         f"{_duration(est.seconds)}: check time.t_end and time.dt (and grid.n)"))
    for key, message in problems:
        if not force:
            raise ParameterError(key, f"{message} (--force runs it anyway)")
        warn_caller(f"{key}: {message}")
    return est


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
    """One paragraph for ``viscontact run --dry-run``."""
    g, t = problem.grid, problem.time
    return (f"{problem.title or 'case'}: {g.n} x {g.n} cells of {g.spacing * 1e6:.3g} um, {t.n_steps} steps of "
            f"{t.dt:.4g} s ({problem.tangential.mode}, {problem.normal.control} control, scheme {t.scheme}); "
            f"result about {format_size(est.result_bytes)} ({_records_of(problem, est)}), "
            f"peak memory about {format_size(est.peak_memory_bytes)}, run time about {_duration(est.seconds)}")


def format_size(nbytes: float) -> str:
    """``nbytes`` in B, KiB, MiB, GiB or TiB (3 digits)."""
    for unit in ("B", "KiB", "MiB", "GiB", "TiB"):
        if nbytes < 1024 or unit == "TiB":
            return f"{nbytes:.3g} {unit}"
        nbytes /= 1024
    return f"{nbytes:.3g} TiB"
