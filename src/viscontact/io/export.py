"""Tables out of a result: its scalar series as columns with units, and as a CSV file.

A result's *table* holds every variable that has the dimensions of ``mu_app`` (the one variable
every kind of result holds): of a transient run the scalar time series along ``t`` (``load``,
``delta_z``, ``delta_x``, ``contact_area``, ``mu_app``, ``friction_force``, ...), of a steady speed
curve the steady states along ``speed``, of a sweep the final-state scalars of each run, one row per
run. The coordinates of those dimensions come first (``t`` and ``step``; ``speed`` and
``deborah``; the swept keys). :func:`table` gives the columns as numpy arrays (``pandas.DataFrame(
columns)`` is a data frame), :func:`write_csv` writes them with one header line of names and units,
``t [s],step,load [N],...``, through :func:`viscontact.io.output_files.write_atomically`.

:class:`ResultFile` reads a result file's variables and attributes with h5netcdf, without loading
xarray (what ``viscontact run`` uses to print its summary).
"""
from __future__ import annotations

import csv
import errno
import io
import os
from pathlib import Path
from typing import Any

import numpy as np

from viscontact.errors import ParameterError
from viscontact.io.output_files import check_output_path, link_target, write_atomically

__all__ = ["ResultFile", "check_table_path", "table", "write_csv"]

#: the variable whose dimensions are the rows of a table (every result holds it)
ROW_VARIABLE = "mu_app"


def table(ds: Any) -> tuple[dict[str, np.ndarray], dict[str, str]]:
    """The table of the result ``ds``: its row coordinates and the variables along them.

    Parameters
    ----------
    ds
        A result :class:`xarray.Dataset` (transient, steady or sweep; :func:`viscontact.io.netcdf.open_result`)
        or a :class:`ResultFile`.

    Returns
    -------
    columns : dict of str to numpy.ndarray
        One 1-D array per column (all of one length, the rows), coordinates first; a sweep's
        swept dimensions are flattened in C order.
    units : dict of str to str
        The units of each column ('' for an index or a string).

    Raises
    ------
    ParameterError
        ``ds`` holds no ``mu_app`` (not a result of run, steady or sweep).
    """
    if ROW_VARIABLE not in ds.variables:
        raise ParameterError("result", f"holds no {ROW_VARIABLE}: not a result of viscontact run, steady or sweep")
    dims = tuple(ds[ROW_VARIABLE].dims)
    shape = tuple(ds[ROW_VARIABLE].shape)
    grid = np.indices(shape).reshape(len(shape), -1) if shape else np.zeros((0, 1), dtype=int)
    columns: dict[str, np.ndarray] = {}
    units: dict[str, str] = {}
    coordinates = [name for name in ds.variables if len(ds[name].dims) == 1 and ds[name].dims[0] in dims
                   and (name in dims or name in getattr(ds, "coords", ()))]
    coordinates.sort(key=lambda name: (dims.index(ds[name].dims[0]), name not in dims))
    for name in coordinates:
        axis = dims.index(ds[name].dims[0])
        columns[name] = np.asarray(ds[name].values)[grid[axis]]
        units[name] = str(ds[name].attrs.get("units", ""))
    for name in ds.variables:
        if name not in columns and tuple(ds[name].dims) == dims:
            columns[name] = np.asarray(ds[name].values).reshape(-1)
            units[name] = str(ds[name].attrs.get("units", ""))
    return columns, units


def check_table_path(out: str | Path, *, force: bool = False, inputs: Any = ()) -> Path:
    """Refuse (before reading anything) a table file ``out`` that could not or must not be written:
    a name not ending in ``.csv``, an existing file without ``force``, anything but a regular
    ``*.csv`` file even with it, one of the ``inputs`` (:func:`viscontact.io.output_files.check_output_path`).

    Returns
    -------
    Path
        The file a write replaces (``out`` with symbolic links followed).
    """
    path = Path(out)
    if path.suffix.lower() != ".csv":
        raise ParameterError("--csv", f"must be a table file named *.csv, got {str(out)!r}")
    target = link_target(path)
    if force and target.is_file():  # a table written before: replaced, unless it is an input
        for name in inputs:
            if os.path.exists(name) and os.path.samefile(name, target):
                raise FileExistsError(errno.EEXIST, f"is the input file {name}; refusing to overwrite it, "
                                      "choose another --csv", str(path))
        return target
    return check_output_path(path, inputs=inputs)


def write_csv(ds: Any, path: str | Path, *, force: bool = False) -> Path:
    """Write the :func:`table` of the result ``ds`` to ``path`` as CSV, atomically.

    The first line names the columns with their units in brackets (``t [s],step,load [N],...``;
    none for an index or a string), then one line per row; numbers in the fewest digits that read back
    exactly, NaN as ``nan``.

    Raises
    ------
    FileExistsError
        ``path`` exists and ``force`` is false, or it is not a regular ``*.csv`` file
        (:func:`check_table_path`).
    OSError
        The file cannot be written (no space left, read-only folder, ...); nothing is left behind.
    """
    check_table_path(path, force=force)
    columns, units = table(ds)
    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow([f"{name} [{units[name]}]" if units[name] else name for name in columns])
    cells = [[_cell(v) for v in data] for data in columns.values()]
    writer.writerows(zip(*cells))
    write_atomically(path, text.getvalue().encode("utf-8"), hint="free some space or write elsewhere (--csv)")
    return Path(path)


def _cell(value: Any) -> str:
    """One value of a table as CSV text: an integer as it is, a float in the fewest digits that read
    back exactly (``repr``)."""
    if isinstance(value, (np.integer, int, np.bool_, bool)):
        return str(int(value))
    if isinstance(value, (np.floating, float)):
        return repr(float(value))
    return str(value)


class _Variable:
    """One variable of a :class:`ResultFile`: ``dims``, ``attrs``, ``shape``, ``values`` (read on
    access) and ``[index]`` (a part of it, read from the file)."""

    def __init__(self, var: Any) -> None:
        self._var = var
        self.dims: tuple[str, ...] = tuple(var.dimensions)
        self.attrs: dict[str, Any] = dict(var.attrs)
        self.shape: tuple[int, ...] = tuple(var.shape)

    @property
    def values(self) -> np.ndarray:
        return np.asarray(self._var[...])

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        return self.values if dtype is None else self.values.astype(dtype)

    def __getitem__(self, index: Any) -> np.ndarray:
        if isinstance(index, int) and index < 0:  # h5py reads no negative index
            index += self.shape[0]
        return np.asarray(self._var[index])


class ResultFile:
    """A result file read with h5netcdf (no xarray): what :func:`table` and
    :func:`viscontact.running.summary.summary` read of a Dataset, ``attrs``, ``variables`` (names),
    ``name in f`` and ``f[name]``, of the variables of the file's root. Use it as a context manager;
    the file is open until its end."""

    def __init__(self, path: str | Path) -> None:
        import h5netcdf

        self.path = Path(path)
        self._file = h5netcdf.File(self.path, "r")
        self.attrs: dict[str, Any] = {k: _attribute(v) for k, v in self._file.attrs.items()}
        self.variables: tuple[str, ...] = tuple(self._file.variables)

    def __contains__(self, name: object) -> bool:
        return name in self.variables

    def __getitem__(self, name: str) -> _Variable:
        return _Variable(self._file.variables[name])

    def close(self) -> None:
        self._file.close()

    def __enter__(self) -> ResultFile:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _attribute(value: Any) -> Any:
    """A netCDF attribute as xarray reads it: a one-element array as its scalar, bytes as text."""
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if isinstance(value, np.ndarray) and value.size == 1:
        return value.reshape(()).item()
    return value
