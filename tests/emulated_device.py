"""A device array library emulated on the CPU with CuPy's rules, to test the array seam without a GPU.

CuPy's arrays live on the GPU. numpy's functions and operators dispatch to them (through
``__array_function__`` and ``__array_ufunc__``), so code written against numpy runs on them, except
where it

* converts a device array to a numpy array implicitly (``np.asarray(a)``, ``np.array(a)``: TypeError;
  the host copy is explicit, ``cupy.asnumpy``);
* mixes a numpy array with device arrays in one operation (TypeError; scalars mix: Python's and numpy's,
  ``np.float64``; the emulation refuses 0-d numpy arrays too, the safe side of CuPy's scalar rules);
* creates a field with numpy from a shape (``np.zeros((n, n))``): a host array, which then mixes;
* passes ``workers`` to an FFT (``cupyx.scipy.fft`` has none) or ``where`` to a reduction.

:data:`BACKEND` (namespace :data:`xp`, FFT module :data:`fft`, :func:`to_host`) follows the same
rules around numpy's own arithmetic: every operation unwraps its device arrays, runs numpy on them
and wraps the result (reductions give 0-d device arrays, as CuPy's do). A run on it does exactly
numpy's arithmetic, so its results equal the numpy run's bit for bit, while any host array that leaks
into the device path, or any of the calls above, raises TypeError.
"""
from __future__ import annotations

import contextlib
import types
from dataclasses import dataclass
from typing import Any, Iterator

import numpy as np
import scipy.fft
from numpy.lib.mixins import NDArrayOperatorsMixin

from viscontact.numerics.arrays import ArrayBackend

#: functions that take a ``where`` keyword on the device (the reductions do not)
_WHERE_ALLOWED = {"copyto", "where"}


@dataclass(frozen=True)
class Transfer:
    """One explicit copy: ``"to_device"`` (``xp.asarray`` of a host value) or ``"to_host"``."""

    direction: str
    shape: tuple[int, ...]
    nbytes: int


#: the open :func:`transfers` logs (each copy is appended to every one)
_LOGS: list[list[Transfer]] = []
#: the open :func:`scalar_reads` counters (one list each, one entry a read)
_READS: list[list[str]] = []


@contextlib.contextmanager
def _recorded(logs: list[list]) -> Iterator[list]:
    """A new log in ``logs`` while the block runs (nested blocks each see theirs)."""
    log: list = []
    logs.append(log)
    try:
        yield log
    finally:
        logs.remove(log)


def scalar_reads() -> contextlib.AbstractContextManager[list[str]]:
    """The reads of device values by the host while the block runs (``float``, ``int``, ``bool``,
    ``tolist``, ``item`` of a device array: on a GPU each waits for the device's queue), by name."""
    return _recorded(_READS)


def _read(name: str) -> None:
    for log in _READS:
        log.append(name)


def transfers() -> contextlib.AbstractContextManager[list[Transfer]]:
    """The host-device copies made while the block runs, in order (nested blocks each see theirs)."""
    return _recorded(_LOGS)


def _logged(direction: str, data: np.ndarray) -> None:
    for log in _LOGS:
        log.append(Transfer(direction, data.shape, data.nbytes))


class HostArrayError(TypeError):
    """A numpy (host) array met a device array, or a device array was converted implicitly."""


class DeviceArray(NDArrayOperatorsMixin):
    """An array "on the device": a numpy array reachable only through numpy's dispatch protocols."""

    __slots__ = ("_data",)

    def __init__(self, data: np.ndarray) -> None:
        self._data = data

    # -- the protocols ---------------------------------------------------------------------------
    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        raise HostArrayError("implicit conversion of a device array to a numpy array (use the backend's to_host)")

    def __array_ufunc__(self, ufunc: np.ufunc, method: str, *inputs: Any, **kwargs: Any) -> Any:
        out = kwargs.get("out")
        if out is not None:
            kwargs["out"] = tuple(_unwrap(o) for o in out)
        result = getattr(ufunc, method)(*_unwrap(inputs), **kwargs)
        if out is not None:  # the caller's own arrays (in-place operators keep their identity)
            return out[0] if len(out) == 1 else out
        return _wrap(result)

    def __array_function__(self, func: Any, types_: Any, args: tuple, kwargs: dict) -> Any:
        if func.__name__ in ("asarray", "array", "ascontiguousarray"):
            # reached only through NEP 35's ``like=`` (np.asarray(host, like=field)), which numpy strips:
            # the explicit copy to the device, as CuPy's asarray
            return _to_device(*args, **kwargs)
        if "where" in kwargs and func.__name__ not in _WHERE_ALLOWED:
            raise TypeError(f"{func.__name__}() takes no 'where' on the device")
        out = kwargs.get("out")
        result = func(*_unwrap(args), **_unwrap(kwargs))
        return out if isinstance(out, DeviceArray) else _wrap(result)

    # -- attributes, indexing, scalars -----------------------------------------------------------
    shape = property(lambda self: self._data.shape)
    dtype = property(lambda self: self._data.dtype)
    ndim = property(lambda self: self._data.ndim)
    size = property(lambda self: self._data.size)
    nbytes = property(lambda self: self._data.nbytes)
    T = property(lambda self: DeviceArray(self._data.T))
    real = property(lambda self: DeviceArray(self._data.real))
    imag = property(lambda self: DeviceArray(self._data.imag))

    def __getattr__(self, name: str) -> Any:
        if name == "flat" or name.startswith("__"):  # no host protocols (__array_interface__, ...)
            raise AttributeError(f"no {name!r} on the device")
        attr = getattr(self._data, name)
        if name in ("tolist", "item"):  # explicit host values: a read of the device
            _read(name)
            return attr
        if not callable(attr):
            return attr

        def method(*args: Any, **kwargs: Any) -> Any:
            if "where" in kwargs:
                raise TypeError(f"{name}() takes no 'where' on the device")
            return _wrap(attr(*_unwrap(args), **_unwrap(kwargs)))
        return method

    def __getitem__(self, key: Any) -> "DeviceArray":
        return _wrap(self._data[_unwrap(key)])

    def __setitem__(self, key: Any, value: Any) -> None:
        self._data[_unwrap(key)] = _unwrap(value)

    def __len__(self) -> int:
        return len(self._data)

    def __iter__(self):
        return (_wrap(row) for row in self._data)

    def __float__(self) -> float:
        _read("float")
        return float(self._data)

    def __int__(self) -> int:
        _read("int")
        return int(self._data)

    def __index__(self) -> int:
        _read("index")
        return self._data.__index__()

    def __bool__(self) -> bool:
        _read("bool")
        return bool(self._data)

    def __repr__(self) -> str:
        return f"DeviceArray({self._data!r})"


def _unwrap(value: Any) -> Any:
    """numpy's view of ``value`` (containers walked); a host array (0-d too) raises."""
    if isinstance(value, DeviceArray):
        return value._data
    if isinstance(value, np.ndarray):
        raise HostArrayError(f"a numpy array of shape {value.shape} mixed with device arrays")
    if isinstance(value, (list, tuple)):
        return type(value)(_unwrap(v) for v in value)
    if isinstance(value, dict):
        return {k: _unwrap(v) for k, v in value.items()}
    return value


def _wrap(value: Any) -> Any:
    """numpy results as device arrays (numpy scalars as 0-d arrays, as CuPy's reductions return)."""
    if isinstance(value, np.ndarray):
        return DeviceArray(value)
    if isinstance(value, np.generic):
        return DeviceArray(np.asarray(value))
    if isinstance(value, (list, tuple)):
        return type(value)(_wrap(v) for v in value)
    return value


def _to_device(value: Any, dtype: Any = None, copy: Any = None, **kwargs: Any) -> DeviceArray:
    """``xp.asarray``/``xp.array``: the explicit host-to-device copy (device arrays pass through)."""
    if isinstance(value, DeviceArray):
        data = value._data
        if dtype is not None:
            data = data.astype(dtype, copy=bool(copy))
        elif copy:
            data = data.copy()
        return DeviceArray(data)
    data = np.array(value, dtype=dtype, **kwargs)
    _logged("to_device", data)
    return DeviceArray(data)


class _Namespace(types.ModuleType):
    """numpy's functions on device arrays (constants, dtypes and classes as numpy's)."""

    def __getattr__(self, name: str) -> Any:
        if name == "ndarray":
            return DeviceArray
        if name in ("asarray", "array", "ascontiguousarray"):
            return _to_device
        attr = getattr(np, name)
        if isinstance(attr, type) or not callable(attr):
            return attr

        def function(*args: Any, **kwargs: Any) -> Any:
            if "where" in kwargs and name not in _WHERE_ALLOWED:
                raise TypeError(f"{name}() takes no 'where' on the device")
            return _wrap(attr(*_unwrap(args), **_unwrap(kwargs)))
        function.__name__ = name
        return function


class _FFT(types.ModuleType):
    """scipy.fft's transforms on device arrays, without ``workers`` (as ``cupyx.scipy.fft``)."""

    def __getattr__(self, name: str) -> Any:
        attr = getattr(scipy.fft, name)
        if name == "next_fast_len" or not callable(attr):
            return attr

        def transform(*args: Any, **kwargs: Any) -> Any:
            if "workers" in kwargs:
                raise TypeError(f"{name}() got an unexpected keyword argument 'workers' (cupyx.scipy.fft has none)")
            if args and not isinstance(args[0], DeviceArray):
                raise HostArrayError(f"fft.{name} of a host array")
            return _wrap(attr(*_unwrap(args), **_unwrap(kwargs)))
        transform.__name__ = name
        return transform


def to_host(array: Any) -> np.ndarray:
    """The explicit device-to-host copy (``cupy.asnumpy``)."""
    if not isinstance(array, DeviceArray):
        raise HostArrayError(f"to_host of a {type(array).__name__}, not a device array")
    _logged("to_host", array._data)
    return array._data.copy()


#: the emulated namespace and FFT module
xp = _Namespace("emulated_device.xp")
fft = _FFT("emulated_device.fft")
#: the emulated device as a viscontact array backend
BACKEND = ArrayBackend("emulated", xp, fft, to_host)
