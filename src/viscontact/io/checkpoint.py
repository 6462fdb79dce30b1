"""Checkpoints of the transient solver state: exact (bit-for-bit) save and restore.

A checkpoint is one ``.npz`` file holding every array and scalar of :class:`~viscontact.solvers.transient.State`
(walked generically through its dataclass fields, dicts and lists: a new field needs no edit here)
plus a fingerprint of the problem, written atomically (temporary file in the same folder, flush,
fsync, ``os.replace``) so that a run killed at any moment leaves either the previous checkpoint or
the new one, never a torn file. Resuming from it continues the same floating-point computation, so
the resumed result equals the uninterrupted one. A checkpoint of ``viscontact run`` holds the
solver state only (a few n x n arrays per retardation mode, whatever the number of steps) and how
many records the result file streamed as the run goes holds (:mod:`viscontact.io.streaming`); one of
the in-memory :func:`viscontact.running.api.run` also holds the records so far.

A state on a device array backend (:mod:`viscontact.numerics.arrays`) is saved through the backend's
``to_host``, each such array marked, and restored to the device with its ``to_device``; the arrays
the state keeps on the host (the wake's columns) stay there. ``solver.device`` is not in the problem's
fingerprint: a checkpoint of either device resumes on the other (:func:`state_from_arrays`).
"""
from __future__ import annotations

import dataclasses
import errno
import hashlib
import importlib
import os
import zipfile
from pathlib import Path
from typing import Any, Callable, Mapping

import numpy as np

from viscontact.errors import ParameterError
from viscontact.io.output_files import write_atomically
from viscontact.io.safe_read import file_kind, regular_input
from viscontact.numerics.arrays import CPU, ArrayBackend, array_backend
from viscontact.problem.problem import Problem, is_integer
from viscontact.solvers.transient import State

FORMAT_VERSION = 2
_ROOT = "state"


#: the settings of rolling (:class:`~viscontact.problem.problem.TangentialLoading`), hashed in rolling only
ROLLING_KEYS = ("rolling_speed", "creepage", "tangential_force")


def problem_fingerprint(problem: Problem) -> str:
    """A hash of everything that shapes the result: the solution and the output settings (which
    steps and fields the records hold). A setting added since checkpoints were first written enters
    it only away from its default (the body's, ``tangential.slip`` in partial slip,
    ``tangential.displacement_history``, ``grid.dimension`` on a line, rolling's keys), so that the
    checkpoints of the problems it does not change still resume. ``solver.device`` does not enter it (it is hashed as ``"cpu"``, as before the GPU):
    the two devices solve the same problem, so a run checkpointed on one resumes on the other
    (:func:`state_from_arrays`)."""
    h = hashlib.sha256()
    tangential = _repr_without(problem.tangential, "slip", "displacement_history", *ROLLING_KEYS)
    solver = dataclasses.replace(problem.solver, device="cpu") if problem.solver.device != "cpu" else problem.solver
    grid = _repr_without(problem.grid, "dimension") if problem.grid.dimension == 2 else problem.grid
    h.update(repr((problem.material, grid, problem.normal, tangential,
                   problem.time, solver, problem.radius, problem.output)).encode())
    h.update(np.ascontiguousarray(problem.gap).tobytes())
    h.update(problem.body.fingerprint())  # nothing for the half-space: its fingerprint stays what it was
    if problem.tangential.incremental_slip:  # the seed's total slip, or no partial slip: as it was
        h.update(repr({"slip": problem.tangential.slip}).encode())
    if problem.tangential.displacement_history is not None:  # a ramp's fingerprint stays what it was
        h.update(repr({"displacement_history": problem.tangential.displacement_history}).encode())
    if problem.tangential.rolls:  # the other modes: as they were
        h.update(repr({key: getattr(problem.tangential, key) for key in ROLLING_KEYS}).encode())
    if problem.adhesion is not None:  # without adhesion, as it was
        h.update(repr({"adhesion": problem.adhesion, "tensile": problem.normal.tensile}).encode())
    return h.hexdigest()


class _Repr(str):
    """A string whose repr is itself (:func:`_repr_without`)."""

    def __repr__(self) -> str:
        return str(self)


def _repr_without(value: Any, *names: str) -> _Repr:
    """The dataclass repr of ``value`` without the fields ``names`` (what it was before they came)."""
    items = ", ".join(f"{f.name}={getattr(value, f.name)!r}" for f in dataclasses.fields(value)
                      if f.repr and f.name not in names)
    return _Repr(f"{type(value).__qualname__}({items})")


#: what a state holds on the host: numpy arrays and scalars, Python scalars and strings
_HOST_TYPES = (np.ndarray, np.generic, bool, int, float, complex, str, bytes)


def _flatten(key: str, value: Any, out: dict[str, np.ndarray], to_host: Callable[[Any], np.ndarray]) -> None:
    """Store ``value`` under ``key`` as named arrays: dataclasses field by field (with their class),
    dicts (string keys) and lists/tuples item by item, arrays as they are, scalars as 0-d arrays;
    an array of a device backend through ``to_host``, marked ``__device__``."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        cls = type(value)
        out[f"{key}.__class__"] = np.array(f"{cls.__module__}:{cls.__qualname__}")
        for f in dataclasses.fields(value):
            _flatten(f"{key}.{f.name}", getattr(value, f.name), out, to_host)
    elif isinstance(value, Mapping):
        out[f"{key}.__dict__"] = np.array(list(value), dtype=str)
        for k, v in value.items():
            _flatten(f"{key}.{k}", v, out, to_host)
    elif isinstance(value, (list, tuple)):
        out[f"{key}.__{type(value).__name__}__"] = np.array(len(value))
        for i, v in enumerate(value):
            _flatten(f"{key}.{i}", v, out, to_host)
    elif value is None:
        out[f"{key}.__none__"] = np.array(True)
    elif isinstance(value, _HOST_TYPES):
        out[key] = np.asarray(value)
    else:  # a device array
        out[key] = to_host(value)
        out[f"{key}.__device__"] = np.array(True)


def _unflatten(key: str, data, to_device: Callable[[np.ndarray], Any],
               on_device: Callable[[str, np.ndarray], bool] | None = None) -> Any:
    """Inverse of :func:`_flatten` (classes only from this package; the arrays marked ``__device__``
    through ``to_device``, and those for which ``on_device(key, array)`` holds)."""
    if f"{key}.__class__" in data:
        module, name = str(data[f"{key}.__class__"]).split(":")
        if module.split(".")[0] != __name__.split(".")[0]:
            raise ParameterError("--resume", f"checkpoint names a foreign class {module}:{name}")
        cls = getattr(importlib.import_module(module), name)
        # a field added since the checkpoint was written takes its default (e.g. the carried products
        # of the transient state: recomputed where missing)
        return cls(**{f.name: _unflatten(f"{key}.{f.name}", data, to_device, on_device)
                      for f in dataclasses.fields(cls) if _stored(f"{key}.{f.name}", data) or not _has_default(f)})
    if f"{key}.__dict__" in data:
        return {str(k): _unflatten(f"{key}.{k}", data, to_device, on_device) for k in data[f"{key}.__dict__"]}
    for kind in (list, tuple):
        if f"{key}.__{kind.__name__}__" in data:
            return kind(_unflatten(f"{key}.{i}", data, to_device, on_device)
                        for i in range(int(data[f"{key}.__{kind.__name__}__"])))
    if f"{key}.__none__" in data:
        return None
    value = data[key]
    if f"{key}.__device__" in data or (on_device is not None and on_device(key, value)):
        return to_device(value.copy())
    return value.item() if value.ndim == 0 else value.copy()


def _stored(key: str, data) -> bool:
    """Whether :func:`_flatten` stored anything under ``key``."""
    return key in data or any(f"{key}.{tag}" in data for tag in
                              ("__class__", "__dict__", "__list__", "__tuple__", "__none__"))


def _has_default(field_: dataclasses.Field) -> bool:
    return field_.default is not dataclasses.MISSING or field_.default_factory is not dataclasses.MISSING


def state_arrays(state: State, backend: ArrayBackend = CPU) -> dict[str, np.ndarray]:
    """Every field of ``state`` (recursively) as named numpy arrays, those on ``backend``'s device
    copied to the host (module docstring)."""
    out: dict[str, np.ndarray] = {}
    _flatten(_ROOT, state, out, backend.to_host)
    return out


#: the part of a state that a device run keeps on the host: the wake's columns
#: (:meth:`~viscontact.bodies.compliance.Compliance.shifted` copies the dropped history there)
_HOST_PART = f"{_ROOT}.wake."


def state_from_arrays(data, backend: ArrayBackend = CPU) -> State:
    """Inverse of :func:`state_arrays` (bit-exact), the arrays that were on the device moved to
    ``backend``'s. A state saved by a run on the CPU (no array marked) and restored to a device has
    there what a device run keeps there: every array of one or more dimensions but the wake's; one
    saved on a device and restored to the CPU has its marked arrays as numpy arrays."""
    keys = _Keys(data)

    def written_on_the_cpu(key: str, value: np.ndarray) -> bool:
        return value.ndim >= 1 and not key.startswith(_HOST_PART)

    marked = any(name.endswith(".__device__") for name in keys.names)
    return _unflatten(_ROOT, keys, backend.to_device, None if backend.is_cpu or marked else written_on_the_cpu)


class _Keys:
    """Membership tests on an ``NpzFile`` by its member names (``in`` on it reads ``files``)."""

    def __init__(self, data) -> None:
        self.data, self.names = data, set(data.files) if hasattr(data, "files") else set(data)

    def __contains__(self, key: str) -> bool:
        return key in self.names

    def __getitem__(self, key: str) -> np.ndarray:
        return self.data[key]


def save_checkpoint(path: str | Path, problem: Problem, state: State,
                    extra: dict[str, np.ndarray] | None = None, backend: ArrayBackend | None = None) -> None:
    """Write ``state`` (and ``extra`` arrays: how many records the streamed result holds, or the
    records so far) atomically to ``path``; ``backend``: the array backend of the state's fields
    (None: that of ``solver.device``)."""
    path = Path(path)
    arrays = state_arrays(state, backend or array_backend(problem.solver.device))
    arrays["format_version"] = np.array(FORMAT_VERSION)
    arrays["fingerprint"] = np.array(problem_fingerprint(problem))
    for k, v in (extra or {}).items():
        arrays[f"extra__{k}"] = np.asarray(v)
    size = sum(np.asarray(a).nbytes + 512 for a in arrays.values())
    write_atomically(path, lambda f: np.savez(f, **arrays), size=size,
                     hint="free some space, checkpoint less often (--checkpoint-every) or write elsewhere (--out)")


def check_checkpoint_every(every: object, key: str = "checkpoint_every") -> None:
    """Raise :class:`ParameterError` naming ``key`` unless ``every`` (steps between checkpoints; 0:
    none) is an integer >= 0."""
    if not is_integer(every) or every < 0:
        raise ParameterError(key, f"must be an integer >= 0 steps (0: no checkpoint), got {every!r}")


def check_checkpoint_path(path: str | Path) -> None:
    """Refuse, before a run, a checkpoint path that names anything a checkpoint may not replace: a
    folder, or a file that is neither empty nor a viscontact checkpoint (a result, a case file: a
    checkpoint written there would destroy it).

    Raises
    ------
    IsADirectoryError, FileExistsError
        Naming ``path`` and what to do.
    """
    path = Path(path)
    if not os.path.lexists(path):
        return
    if path.is_dir():
        raise IsADirectoryError(errno.EISDIR, "is a folder; give a checkpoint file name (e.g. run.checkpoint.npz)",
                                str(path))
    if not path.is_file():  # a FIFO would block zipfile.is_zipfile, a device never end
        raise FileExistsError(errno.EEXIST, f"exists and is {_what_is(path)}, not a viscontact checkpoint; refusing "
                              "to replace it with one: choose another checkpoint path", str(path))
    if path.stat().st_size == 0:
        return
    ours = False
    if zipfile.is_zipfile(path):  # a checkpoint is an .npz archive; np.load reads a .npy file as an array
        try:
            with np.load(path, allow_pickle=False) as data:
                ours = {"format_version", "fingerprint"} <= set(data.files)
        except (OSError, ValueError, EOFError, zipfile.BadZipFile):
            pass
    if not ours:
        raise FileExistsError(errno.EEXIST, "exists and is not a viscontact checkpoint; refusing to replace it "
                              "with one: choose another checkpoint path", str(path))


def _what_is(path: Path) -> str:
    """What ``path`` (links followed) is, in words: a folder, a FIFO, a link loop..."""
    try:
        return file_kind(path.stat().st_mode)
    except FileNotFoundError:
        return "a symbolic link to a missing file"
    except OSError as exc:
        return "a loop of symbolic links" if exc.errno == errno.ELOOP else f"unreadable ({exc.strerror})"


def load_checkpoint(path: str | Path, problem: Problem,
                    backend: ArrayBackend | None = None) -> tuple[State, dict[str, np.ndarray]]:
    """Read a checkpoint; refuses one written for a different problem. Returns (state, extra arrays),
    the state's device fields on ``backend`` (None: that of ``solver.device``)."""
    path = Path(path)
    if not path.exists():
        raise ParameterError("--resume", f"no checkpoint at {path}")
    regular_input(path, "--resume", need="a viscontact checkpoint (delete it and run without --resume)")
    try:
        with np.load(path, allow_pickle=False) as data:
            version = int(data["format_version"])
            if version != FORMAT_VERSION:
                raise ParameterError("--resume", f"checkpoint {path} has format {version}, "
                                     f"this viscontact reads {FORMAT_VERSION}")
            if str(data["fingerprint"]) != problem_fingerprint(problem):
                raise ParameterError("--resume", f"checkpoint {path} was written for a different case or output "
                                     "settings; run without --resume (or with the original case file and --set)")
            state = state_from_arrays(data, backend or array_backend(problem.solver.device))
            extra = {k[len("extra__"):]: data[k].copy() for k in data.files if k.startswith("extra__")}
    except ParameterError:
        raise
    except (OSError, ValueError, KeyError, TypeError, EOFError, zipfile.BadZipFile) as exc:
        what = f"has no {exc}" if isinstance(exc, KeyError) else f"is unreadable ({exc})"
        raise ParameterError("--resume", f"checkpoint {path} {what}: it is truncated or not a viscontact "
                             "checkpoint; delete it and run without --resume") from None
    return state, extra
