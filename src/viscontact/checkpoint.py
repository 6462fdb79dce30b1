"""Checkpoints of the transient solver state: exact (bit-for-bit) save and restore.

A checkpoint is one ``.npz`` file holding every array and scalar of :class:`~viscontact.transient.State`
plus a fingerprint of the problem, written atomically (temporary file in the same folder, flush,
fsync, ``os.replace``) so that a run killed at any moment leaves either the previous checkpoint or
the new one, never a torn file. Resuming from it continues the same floating-point computation, so
the resumed result equals the uninterrupted one.
"""
from __future__ import annotations

import hashlib
import os
import tempfile
from pathlib import Path

import numpy as np

from .errors import ParameterError
from .history import DirectHistory, PronyHistory
from .problem import Problem
from .sliding import Wake
from .transient import State

FORMAT_VERSION = 1


def problem_fingerprint(problem: Problem) -> str:
    """A hash of everything that determines the solution (not the output settings)."""
    h = hashlib.sha256()
    h.update(repr((problem.material, problem.grid, problem.normal, problem.tangential, problem.time,
                   problem.solver, problem.radius)).encode())
    h.update(np.ascontiguousarray(problem.gap).tobytes())
    return h.hexdigest()


def _history_arrays(prefix: str, hist: PronyHistory | DirectHistory) -> dict[str, np.ndarray]:
    if isinstance(hist, PronyHistory):
        return {f"{prefix}_kind": np.array("prony"), f"{prefix}_internal": hist.internal,
                f"{prefix}_previous": hist.previous}
    prev = hist.previous if hist.previous is not None else np.zeros((hist.n, hist.n))
    incs = np.array(hist.increments) if hist.increments else np.zeros((0, hist.n, hist.n))
    return {f"{prefix}_kind": np.array("direct"), f"{prefix}_increments": incs,
            f"{prefix}_times": np.array(hist.times, dtype=float), f"{prefix}_ramps": np.array(hist.ramps, dtype=bool),
            f"{prefix}_previous": prev, f"{prefix}_has_previous": np.array(hist.previous is not None)}


def _history_from(prefix: str, data) -> PronyHistory | DirectHistory:
    if str(data[f"{prefix}_kind"]) == "prony":
        return PronyHistory(data[f"{prefix}_internal"].copy(), data[f"{prefix}_previous"].copy())
    n = data[f"{prefix}_previous"].shape[0]
    return DirectHistory(n, [a.copy() for a in data[f"{prefix}_increments"]],
                         [float(t) for t in data[f"{prefix}_times"]], [bool(r) for r in data[f"{prefix}_ramps"]],
                         data[f"{prefix}_previous"].copy() if bool(data[f"{prefix}_has_previous"]) else None)


def state_arrays(state: State) -> dict[str, np.ndarray]:
    """Every field of ``state`` as named numpy arrays."""
    n = state.pressure.shape[0]
    m = state.wake.strips[0].shape[0] if state.wake.strips else 0
    out = {
        "step": np.array(state.step), "t": np.array(state.t), "phase": np.array(state.phase),
        "pressure": state.pressure, "shear_x": state.shear_x,
        "pressure_previous": state.pressure_previous if state.pressure_previous is not None else np.zeros((n, n)),
        "shear_previous": state.shear_previous if state.shear_previous is not None else np.zeros((n, n)),
        "delta_z": np.array(state.delta_z), "delta_x": np.array(state.delta_x),
        "sliding_distance": np.array(state.sliding_distance), "substep": np.array(state.substep),
        "t_gross_sliding": np.array(np.nan if state.t_gross_sliding is None else state.t_gross_sliding),
        "wake_strips": np.array(state.wake.strips) if state.wake.strips else np.zeros((0, m, n)),
        "wake_distance": np.array(state.wake.distance, dtype=np.int64),
        "wake_age": np.array(state.wake.age, dtype=np.int64),
    }
    out.update(_history_arrays("history_p", state.history_p))
    out.update(_history_arrays("history_q", state.history_q))
    return out


def state_from_arrays(data) -> State:
    """Inverse of :func:`state_arrays`."""
    tg = float(data["t_gross_sliding"])
    return State(
        step=int(data["step"]), t=float(data["t"]), phase=int(data["phase"]),
        pressure=data["pressure"].copy(), shear_x=data["shear_x"].copy(),
        history_p=_history_from("history_p", data), history_q=_history_from("history_q", data),
        delta_z=float(data["delta_z"]), delta_x=float(data["delta_x"]),
        sliding_distance=float(data["sliding_distance"]), substep=int(data["substep"]),
        t_gross_sliding=None if np.isnan(tg) else tg,
        wake=Wake([s.copy() for s in data["wake_strips"]], [int(d) for d in data["wake_distance"]],
                  [int(a) for a in data["wake_age"]]),
        pressure_previous=data["pressure_previous"].copy(), shear_previous=data["shear_previous"].copy(),
    )


def save_checkpoint(path: str | Path, problem: Problem, state: State,
                    extra: dict[str, np.ndarray] | None = None) -> None:
    """Write ``state`` (and ``extra`` arrays, e.g. the records so far) atomically to ``path``."""
    path = Path(path)
    arrays = state_arrays(state)
    arrays["format_version"] = np.array(FORMAT_VERSION)
    arrays["fingerprint"] = np.array(problem_fingerprint(problem))
    for k, v in (extra or {}).items():
        arrays[f"extra__{k}"] = np.asarray(v)
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".", suffix=".tmp", dir=path.parent or ".")
    try:
        with os.fdopen(fd, "wb") as f:
            np.savez(f, **arrays)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def load_checkpoint(path: str | Path, problem: Problem) -> tuple[State, dict[str, np.ndarray]]:
    """Read a checkpoint; refuses one written for a different problem. Returns (state, extra arrays)."""
    path = Path(path)
    if not path.exists():
        raise ParameterError("--resume", f"no checkpoint at {path}")
    with np.load(path, allow_pickle=False) as data:
        if int(data["format_version"]) != FORMAT_VERSION:
            raise ParameterError("--resume", f"checkpoint {path} has format {int(data['format_version'])}, "
                                 f"this viscontact reads {FORMAT_VERSION}")
        if str(data["fingerprint"]) != problem_fingerprint(problem):
            raise ParameterError("--resume", f"checkpoint {path} was written for a different case; "
                                 "run without --resume (or with the original case file)")
        state = state_from_arrays(data)
        extra = {k[len("extra__"):]: data[k].copy() for k in data.files if k.startswith("extra__")}
    return state, extra
