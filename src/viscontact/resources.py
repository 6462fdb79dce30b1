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
import warnings
from dataclasses import dataclass
from pathlib import Path

from .errors import ParameterError, ViscontactWarning
from .problem import Problem

_FIELD_BYTES = {"pressure": 8, "shear_x": 8, "stick": 1, "displacement_z": 8}
#: seconds per time step, per cell and per log2(2n) (FFT cost), measured on the 2-core reference
#: machine: creep indentation 256^2 x 201 steps in 19 s (BENCHMARKS.md)
SECONDS_PER_CELL_STEP = 19.0 / (201 * 256**2 * math.log2(512))
#: runs estimated to take longer than this [s] are refused unless forced
MAX_RUN_SECONDS = 24 * 3600.0


@dataclass(frozen=True)
class Estimate:
    """``result_bytes``: the result file (uncompressed); ``peak_memory_bytes``: the process at its peak;
    ``records``: how many time entries the result holds; ``checkpoint_bytes``: one checkpoint at the
    end of the run (solver state and every record); ``seconds``: the run time on the reference
    machine (:data:`SECONDS_PER_CELL_STEP`)."""

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

    Memory: the recorded fields are kept until the file is written (and copied once when the
    Dataset is built), plus the solver's own arrays: the history (2 x retardation modes), a dozen
    n x n work fields, and per influence kernel its (2n)^2 real-space copy, its (2n)(n + 1) complex
    spectrum and the FFT work arrays.
    """
    n = problem.grid.n
    steps = problem.time.n_steps
    every = problem.output.every
    records = (steps - 1) // every + 1 + (1 if (steps - 1) % every else 0)
    per_record = sum(_FIELD_BYTES.get(f, 8) for f in problem.output.fields) * n * n + 200
    result = records * per_record + len(problem.title) + 4096
    modes = problem.material.creep.retardation_times.size
    kernels = 4 if problem.tangential.mode in ("partial_slip", "gross_sliding") else 1
    solver = (2 * 2 * modes + 16) * 8 * n * n + kernels * (4 * n * n * 8 + 2 * n * (n + 1) * 16) \
        + 6 * 4 * n * n * 8
    state = (2 * modes + 8) * 8 * n * n
    seconds = steps * SECONDS_PER_CELL_STEP * n * n * math.log2(2 * n)
    return Estimate(int(result), int(2 * result + solver + 150e6), int(records), int(result + state), seconds)


def available_memory() -> int | None:
    """Physical memory available now [bytes], or None where the system does not say."""
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return None


def check_resources(problem: Problem, out: str | Path, *, force: bool = False, checkpoints: bool = False) -> Estimate:
    """Refuse a run that needs more than the machine has: its result (and, with ``checkpoints``,
    its checkpoints) beyond the free disk of ``out``, its memory beyond the free RAM, its run time
    beyond :data:`MAX_RUN_SECONDS`. :class:`ParameterError` naming the key to change, or with
    ``force`` a warning."""
    est = estimate(problem)
    folder = Path(out).resolve().parent
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    free = shutil.disk_usage(folder).free
    needed = est.disk_bytes(checkpoints)
    what = f"{est.records} records of {', '.join(problem.output.fields)}"
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
        warnings.warn(f"{key}: {message}", ViscontactWarning, stacklevel=2)
    return est


def _duration(seconds: float) -> str:
    for unit, length in (("days", 86400.0), ("h", 3600.0), ("min", 60.0)):
        if seconds >= length:
            return f"{seconds / length:.3g} {unit}"
    return f"{seconds:.2g} s"


def describe(problem: Problem, est: Estimate) -> str:
    """One paragraph for ``viscontact run --dry-run``."""
    g, t = problem.grid, problem.time
    return (f"{problem.title or 'case'}: {g.n} x {g.n} cells of {g.spacing * 1e6:.3g} um, {t.n_steps} steps of "
            f"{t.dt:.4g} s ({problem.tangential.mode}, {problem.normal.control} control, scheme {t.scheme}); "
            f"result about {format_size(est.result_bytes)} ({est.records} records of "
            f"{', '.join(problem.output.fields)}), "
            f"peak memory about {format_size(est.peak_memory_bytes)}, run time about {_duration(est.seconds)}")


def format_size(nbytes: float) -> str:
    """``nbytes`` in B, KiB, MiB, GiB or TiB (3 digits)."""
    for unit in ("B", "KiB", "MiB", "GiB", "TiB"):
        if nbytes < 1024 or unit == "TiB":
            return f"{nbytes:.3g} {unit}"
        nbytes /= 1024
    return f"{nbytes:.3g} TiB"
