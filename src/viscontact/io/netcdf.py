"""netCDF-4 files of results: written atomically (:func:`write_netcdf`) and read back
(:func:`open_result`, streamed results too)."""
from __future__ import annotations

import errno
import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING

from viscontact.errors import ParameterError, check_type
from viscontact.io.results import netcdf_encoding
from viscontact.io.safe_read import regular_input

if TYPE_CHECKING:  # xarray (with pandas, ~60 MiB) loads only where a Dataset is built or read
    import xarray as xr


def write_netcdf(ds: xr.Dataset, path: str | Path, *, force: bool = False) -> Path:
    """Write ``ds`` to ``path`` as netCDF-4 (h5netcdf), atomically.

    The file is encoded in memory, then written under a temporary name in the same folder with its
    size claimed first, flushed to disk and renamed over ``path``
    (:func:`viscontact.io.output_files.write_atomically`): readers see the old file, or the complete
    new one, never a partial one; a full disk is one error naming the size needed; SIGINT / SIGTERM
    arriving meanwhile are delivered once the file is complete. 3-D fields are zlib-compressed in
    chunks of one time step; coordinates have no ``_FillValue``.

    Raises
    ------
    FileExistsError
        ``path`` exists and ``force`` is false (``--force`` on the command line), or it is not a
        regular netCDF file (never replaced).
    OSError
        The file cannot be written (no space left, read-only folder, ...); nothing is left behind.
    TypeError
        ``ds`` is not an xarray.Dataset.
    """
    import xarray as xr

    from viscontact.io.output_files import check_output_path, signals_deferred, write_atomically

    check_type(ds, xr.Dataset, "write_netcdf's ds", "an xarray.Dataset (viscontact.to_dataset of a run's records)")
    check_output_path(path, force=force)
    with signals_deferred(), _local_scheduler():
        data = ds.to_netcdf(engine="h5netcdf", encoding=netcdf_encoding(ds))
        write_atomically(path, data, hint="free some space or write elsewhere (--out)")
    return Path(path)


@contextmanager
def _local_scheduler() -> Iterator[None]:
    """Encode in this process even inside a dask worker: xarray would otherwise ask the distributed
    scheduler for a lock named after the in-memory buffer, which it does not know."""
    try:
        import dask
    except ImportError:  # pragma: no cover - dask is a dependency
        yield
        return
    with dask.config.set(scheduler="synchronous"):
        yield


def open_result(path: str | Path) -> xr.Dataset:
    """Load a result file fully into memory (the file is closed on return). Of a streamed file left
    incomplete by a kill, only the records whole at its last flush (attribute
    :data:`viscontact.io.streaming.FLUSHED`): a kill inside HDF5's flush can tear the last one.

    Raises
    ------
    FileNotFoundError
        ``path`` does not exist.
    ParameterError
        ``path`` is not a regular file (a FIFO, a folder, a link loop), or not a netCDF-4 file written by
        viscontact (``run``, ``steady`` or ``sweep``).
    """
    import xarray as xr

    path = Path(path)
    if not os.path.lexists(path):
        raise FileNotFoundError(errno.ENOENT, "no such file", str(path))
    not_a_result = ParameterError(str(path), "is not a viscontact result file (a netCDF-4 file written by "
                                  "viscontact run, steady or sweep)")
    regular_input(path, str(path), need="a viscontact result file")  # a FIFO would block h5py
    try:
        with xr.open_dataset(path, engine="h5netcdf") as ds:
            ds = ds.load()
    except (OSError, ValueError, KeyError, TypeError):  # not HDF5, not netCDF, or unreadable layout
        raise not_a_result from None
    if not {"version", "case"} <= set(ds.attrs):
        raise not_a_result
    from viscontact.io.streaming import FLUSHED

    flushed = ds.attrs.get(FLUSHED)  # a streamed file left by a kill: its whole records
    if flushed is not None and int(ds.attrs.get("complete", 1)) == 0 and ds.sizes.get("t", 0) > int(flushed):
        ds = ds.isel(t=slice(0, int(flushed)))
    return ds
