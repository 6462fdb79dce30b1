"""Estimates of what a run will need — result size and peak memory — checked before it starts.

Sizes are upper bounds for float64 data without compression (netCDF compression usually shrinks
the pressure and shear fields, which are zero outside the contact, several times).
"""
from __future__ import annotations

import os
import shutil
import warnings
from dataclasses import dataclass
from pathlib import Path

from .errors import ParameterError, ViscontactWarning
from .problem import Problem

_FIELD_BYTES = {"pressure": 8, "shear_x": 8, "stick": 1, "displacement_z": 8}


@dataclass(frozen=True)
class Estimate:
    """``result_bytes``: the result file (uncompressed); ``peak_memory_bytes``: the process at its peak;
    ``records``: how many time entries the result holds."""

    result_bytes: int
    peak_memory_bytes: int
    records: int


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
    return Estimate(int(result), int(2 * result + solver + 150e6), int(records))


def available_memory() -> int | None:
    """Physical memory available now [bytes], or None where the system does not say."""
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return None


def check_resources(problem: Problem, out: str | Path) -> Estimate:
    """Refuse a run whose result cannot fit on the disk of ``out`` (ParameterError naming
    ``output.every`` / ``output.fields``); warn when its memory estimate exceeds the free RAM."""
    est = estimate(problem)
    folder = Path(out).resolve().parent
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    free = shutil.disk_usage(folder).free
    if est.result_bytes > free:
        raise ParameterError(
            "output.every", f"the result needs about {_size(est.result_bytes)} ({est.records} records of "
            f"{', '.join(problem.output.fields)}) but {folder} has {_size(free)} free: record fewer times "
            "([output] every = k) or fewer fields ([output] fields = [\"pressure\"])")
    ram = available_memory()
    if ram is not None and est.peak_memory_bytes > ram:
        warnings.warn(f"the run may need about {_size(est.peak_memory_bytes)} of memory, {_size(ram)} is free: "
                      "thin the output ([output] every, fields) or use a smaller grid.n", ViscontactWarning,
                      stacklevel=2)
    return est


def describe(problem: Problem, est: Estimate) -> str:
    """One paragraph for ``viscontact run --dry-run``."""
    g, t = problem.grid, problem.time
    return (f"{problem.title or 'case'}: {g.n} x {g.n} cells of {g.spacing * 1e6:.3g} um, {t.n_steps} steps of "
            f"{t.dt:.4g} s ({problem.tangential.mode}, {problem.normal.control} control, scheme {t.scheme}); "
            f"result about {_size(est.result_bytes)} ({est.records} records of {', '.join(problem.output.fields)}), "
            f"peak memory about {_size(est.peak_memory_bytes)}")


def _size(nbytes: float) -> str:
    for unit in ("B", "KiB", "MiB", "GiB", "TiB"):
        if nbytes < 1024 or unit == "TiB":
            return f"{nbytes:.3g} {unit}"
        nbytes /= 1024
    return f"{nbytes:.3g} TiB"
