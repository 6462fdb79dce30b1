"""Streamed result files: each recorded step goes to the netCDF-4 file as the run goes.

The file has the layout of :func:`viscontact.io.results.to_dataset` (same variables, coordinates and
attributes: its skeleton is ``to_dataset`` of no records, :func:`~viscontact.io.results.result_layout`,
encoded as xarray encodes it but written with h5netcdf so that a run never loads xarray and pandas;
then each step is appended with h5py) with the time dimension ``t`` unlimited. Fields are chunked one step per chunk,
byte-shuffled and zlib-compressed, as :func:`viscontact.io.netcdf.write_netcdf` writes them; the scalar series are
chunked :data:`~viscontact.io.results.SERIES_CHUNK` steps at a time, uncompressed (a chunk of fixed
size is rewritten in place as it fills, so the chunks the file already points to never move).
Each record is written one step late: its fields are compressed on a thread while the run computes
the next step (zlib releases the GIL: the compression of a 256^2 field, 1-7 ms, leaves the solve's
path), and the record is written whole, and the file flushed, when the next one is appended, before
each checkpoint (:meth:`ResultStream.drain`) and at the end. Its attribute ``complete`` stays 0 until
:meth:`ResultStream.finish`, so a run killed at any moment leaves a file that ``xarray.open_dataset``
reads, holding every step flushed before the kill (all but the last step computed; a checkpoint
never counts a step the file lacks). A kill inside a flush (HDF5's is not atomic) can leave the
record being flushed torn; the attribute :data:`FLUSHED` counts the whole ones, and
:func:`viscontact.io.netcdf.open_result` reads only those. Memory does not grow with the number of steps: nothing of a
record is kept once written.

Safety (:mod:`viscontact.io.output_files`): the disk space the remaining records need (an upper
bound, :func:`stream_bytes`) is claimed when the file is opened
(:class:`~viscontact.io.output_files.SpaceClaim`) and handed back record by record just before each
write, which first checks that its piece is free: a full disk stops the run between two records
with one :class:`OSError` (``ENOSPC``), never inside an HDF5 write. SIGINT and SIGTERM arriving
during a write are held until it is flushed (:func:`~viscontact.io.output_files.signals_deferred`).

Where the file lives while running (:func:`partial_path`): ``viscontact run --out OUT`` streams into
the sibling ``OUT.partial`` and renames it over ``OUT`` when the run ends, so an ``OUT`` replaced
under ``--force`` is kept until the new result is complete. A run that stops cleanly (SIGINT,
SIGTERM, a failed solve, a full disk) ends the file with ``complete = 0`` and ``stopped_by`` and
renames it over ``OUT`` too, unless ``OUT`` holds a complete result: that one is never replaced by
an incomplete one, and the steps done stay in ``OUT.partial``. After a kill (-9, power) the steps
done are in ``OUT.partial``; ``--resume`` continues it from the checkpoint's step (dropping any
later steps), once :func:`check_resumable` has found, reading it only, that it is the streamed file
of the same case (attribute :data:`FINGERPRINT`, kept until the file is complete). The stream holds
the file it writes open: should another process rename its own file over ``OUT.partial`` (the
run's lock file removed under it), nothing is finished or renamed in its place, the run's own file
is copied to ``OUT.orphan-PID.nc`` and the run fails (:class:`~viscontact.errors.OutputReplacedError`).
"""
from __future__ import annotations

import errno
import os
import zlib
from collections.abc import Callable, Sequence
from concurrent.futures import Future, ThreadPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np

from viscontact.errors import OutputReplacedError
from viscontact.io.output_files import (
    SpaceClaim,
    disk_full_error,
    is_same_file,
    link_target,
    move_atomically,
    signals_deferred,
    write_atomically,
)
from viscontact.problem.problem import Problem
from viscontact.problem.records import StepRecord

__all__ = ["FINGERPRINT", "ResultStream", "check_partial_path", "check_resumable", "is_complete_result", "layout_bytes",
           "partial_path"]

#: what to do when the disk fills during a streamed run (the end of the error line)
DISK_FULL_HINT = ("free some space or write elsewhere (--out); the steps done are kept (complete = 0) and "
                  "--resume continues from the last checkpoint (--checkpoint-every)")


#: what :func:`partial_path` adds to the result file's name
PARTIAL_SUFFIX = ".partial"


def partial_path(out: str | Path) -> Path:
    """Where the result ``out`` is streamed while its run goes on: ``OUT.partial`` beside the file
    ``out`` names (beside its target when ``out`` is a symbolic link: the final rename replaces the
    target, and must stay on its filesystem)."""
    out = link_target(Path(out))
    return out.with_name(out.name + PARTIAL_SUFFIX)


def check_partial_path(out: str | Path) -> Path:
    """:func:`partial_path` of ``out``, refused where something other than a file stands there (a
    folder, a FIFO, a device, a socket): a run could neither stream into it nor resume it, and
    nothing there is touched.

    Raises
    ------
    IsADirectoryError, FileExistsError
        One line naming the path, saying what is in the way and what to do.
    """
    partial = partial_path(out)
    if os.path.exists(partial) and not partial.is_file():
        error, code, what = ((IsADirectoryError, errno.EISDIR, "a folder") if partial.is_dir() else
                             (FileExistsError, errno.EEXIST, "not a regular file (a FIFO, device or socket)"))
        raise error(code, f"is {what} in the way: a run streams its steps into this file beside "
                    f"{Path(out).name}; move it away or choose another --out", str(partial))
    return partial


#: threads compressing the queued record's fields while the run computes the next step (zlib releases
#: the GIL; one keeps the second core of a 2-core machine for the compression, the first for the solve)
COMPRESSION_THREADS = 1


FIELD_BYTES = {"pressure": 8, "shear_x": 8, "stick": 1, "displacement_z": 8}
#: HDF5 bookkeeping one streamed record may add (chunk index entries, flushed metadata) [bytes]
RECORD_OVERHEAD = 4096
#: a node of the chunk index of an HDF5 variable (B-tree; about 2 KiB measured) [bytes], an upper bound
INDEX_NODE_BYTES = 4096
#: what finishing a streamed result writes beyond its records (attributes, scale variables) [bytes]
FINISH_BYTES = 64 * 1024


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
    from viscontact.problem.records import StepRecord

    rows, n = problem.grid.shape
    return sum(FIELD_BYTES.get(f, 8) for f in problem.output.fields) * rows * n \
        + 8 * (len(StepRecord.scalars(problem.adhesion is not None, problem.tangential.rolls)) + 2) + RECORD_OVERHEAD


def stream_bytes(problem: Problem, records: int, *, first: int = 0, finishing: bool = True) -> int:
    """Upper bound of what the records ``first .. first + records - 1`` add to a streamed result file
    [bytes]: :func:`record_bytes` each, a new chunk of every time series each
    :data:`~viscontact.io.results.SERIES_CHUNK` records (and with each, a node of the chunk index of
    every variable along ``t``: :data:`INDEX_NODE_BYTES` each), and with ``finishing``
    :data:`FINISH_BYTES` and the subsurface stresses."""
    from viscontact.io.results import SERIES_CHUNK
    from viscontact.problem.records import StepRecord

    chunks = -(-(first + records) // SERIES_CHUNK) - (-(-first // SERIES_CHUNK))
    out = problem.output
    subsurface = 6 * len(out.subsurface_depths) * problem.grid.n * 8 * len(out.subsurface_times or (0,))
    series = len(StepRecord.scalars(problem.adhesion is not None, problem.tangential.rolls)) + 2
    fields = len(problem.output.fields)
    return records * record_bytes(problem) \
        + chunks * (series * SERIES_CHUNK * 8 + (series + fields) * INDEX_NODE_BYTES) \
        + (FINISH_BYTES + subsurface if finishing else 0)


def chunk_encoder(var: Any) -> Callable[[np.ndarray], tuple[int, bytes]] | None:
    """How one time step of the field dataset ``var`` (h5py, chunks of one step) is encoded for
    h5py's direct chunk write: the dataset's own filter pipeline (HDF5's byte shuffle where it has
    one, then deflate at its level: zlib's format, which HDF5's filter writes and reads), done in
    Python so that it can run on another thread. Returns ``encode(step) -> (filter_mask, bytes)``;
    a chunk that deflate would not shrink is stored as it is, with the filters marked skipped (as
    HDF5 does for an optional filter). None where the chunks or filters are other (then h5py writes
    the step itself)."""
    filters = var.id.get_create_plist().get_nfilters()
    shuffle = bool(var.shuffle)
    if var.chunks != (1, *var.shape[1:]) or var.compression != "gzip" or var.fletcher32 \
            or var.scaleoffset is not None or filters != 1 + shuffle:
        return None
    level, dtype, skipped = int(var.compression_opts), var.dtype, (1 << filters) - 1

    def encode(step: np.ndarray) -> tuple[int, bytes]:
        data = np.ascontiguousarray(step, dtype=dtype)
        ordered = data.view(np.uint8).reshape(-1, dtype.itemsize).T.copy() if shuffle and dtype.itemsize > 1 else data
        packed = zlib.compress(ordered, level)
        return (0, packed) if len(packed) < data.nbytes else (skipped, data.tobytes())

    return encode


def is_complete_result(path: str | Path) -> bool:
    """True when ``path`` is a result file whose attribute ``complete`` is 1."""
    import h5py

    try:
        with h5py.File(path, "r") as f:
            return int(np.asarray(f.attrs.get("complete", 0)).item()) == 1
    except (OSError, ValueError, TypeError):
        return False


def layout_bytes(problem: Problem, *, case_text: str = "", history: str = "",
                 attrs: dict[str, Any] | None = None) -> bytes:
    """The streamed result file of no record (its layout), as bytes: what
    ``to_dataset([], problem).to_netcdf(engine="h5netcdf", unlimited_dims=("t",),
    encoding=netcdf_encoding(ds, streamed=True))`` writes, written with h5netcdf alone. ``history``
    is appended to the attribute ``history``; ``attrs`` are further global attributes.

    xarray's encoding of these variables, done here: booleans stored as ``int8`` with the attribute
    ``dtype = "bool"``, floating data variables with ``_FillValue = NaN``, coordinates with none,
    the attribute ``coordinates`` naming the non-dimension coordinates (``step``) on the variables
    that share their dimensions, dimensions created in the order the variables first use them.
    """
    import io

    import h5netcdf

    from viscontact.io.results import result_layout, scale_variables, variable_encoding

    data_vars, coords, layout_attrs = result_layout([], problem, case_text=case_text)
    attrs = {**layout_attrs, **(attrs or {})}
    attrs["history"] = f"{attrs.get('history', '')} {history}".strip()
    variables = {**data_vars, **coords, **scale_variables(attrs)}  # the order of the Dataset's variables
    auxiliary = {name: dims for name, (dims, _, _) in coords.items() if name not in dims}
    buffer = io.BytesIO()
    with h5netcdf.File(buffer, "w") as f:
        for key, value in attrs.items():
            f.attrs[key] = value
        sizes: dict[str, int] = {}
        for dims, data, _ in variables.values():
            sizes.update((dim, size) for dim, size in zip(dims, np.shape(data)) if dim not in sizes)
        for dim, size in sizes.items():
            f.dimensions[dim] = None if dim == "t" else size
            if dim == "t":
                f.resize_dimension(dim, size)
        for name, (dims, data, var_attrs) in variables.items():
            data, var_attrs = np.asarray(data), dict(var_attrs)
            encoding = variable_encoding(dims, data.shape, coordinate=name in coords, streamed=True)
            shared = [aux for aux, aux_dims in auxiliary.items() if name not in coords and set(aux_dims) <= set(dims)]
            if shared:
                var_attrs["coordinates"] = " ".join(shared)
            if data.dtype == bool:
                data, var_attrs["dtype"] = data.astype(np.int8), "bool"
            fill = np.nan if data.dtype.kind == "f" and "_FillValue" not in encoding else None
            storage = {}
            if data.ndim:
                storage["chunks"] = encoding.get("chunksizes")
                if encoding.get("zlib"):
                    storage.update(compression="gzip", compression_opts=encoding["complevel"],
                                   shuffle=encoding.get("shuffle", False))
            var = f.create_variable(name, dimensions=dims, dtype=data.dtype, fillvalue=fill, **storage)
            for key, value in var_attrs.items():
                var.attrs[key] = value
            if data.size:
                var[...] = data
    return buffer.getvalue()


#: the global attribute of a streamed file that is not complete: the fingerprint of its problem
#: (:func:`viscontact.io.checkpoint.problem_fingerprint`), which a resume checks against its checkpoint's
FINGERPRINT = "problem_fingerprint"
#: the global attribute of a streamed file: how many of its records were whole on disk at the last
#: flush. HDF5's flush is not atomic: a kill inside one can leave the record being flushed torn (its
#: extent on disk, some of its values not); the attribute is set, and flushed again, only after the
#: record's flush has returned, so the records up to it are whole (:func:`viscontact.io.netcdf.open_result`
#: drops the others)
FLUSHED = "records_flushed"


def check_resumable(path: str | Path, problem: Problem, records: int) -> None:
    """Check, reading it only, that ``path`` is the streamed result file of ``problem`` holding at least
    ``records`` records: what :meth:`ResultStream.reopen` continues.

    Raises
    ------
    ParameterError
        (key ``--resume``) One line naming ``path``: missing, unreadable (truncated, not HDF5), not a
        streamed result (a steady result, a foreign netCDF file), written for another case or other
        output settings (its :data:`FINGERPRINT`), or too few records.
    """
    import h5py

    from viscontact.errors import ParameterError
    from viscontact.io.checkpoint import problem_fingerprint

    def refuse(why: str) -> ParameterError:
        return ParameterError("--resume", f"{path}: {why}")

    start_over = "start over with --force instead of --resume (it is then replaced)"
    if not os.path.exists(path):
        raise refuse("is missing: the streamed records of the checkpointed run are not there; run without --resume")
    try:
        with h5py.File(path, "r") as f:
            t = f.get("t")
            if not isinstance(t, h5py.Dataset) or t.maxshape[:1] != (None,) or "step" not in f:
                raise refuse(f"is not the streamed result of a viscontact run; {start_over}")
            if FINGERPRINT not in f.attrs:
                raise refuse(f"is not the unfinished streamed result of a viscontact run (it has no {FINGERPRINT}); "
                             f"{start_over}")
            if _text(f.attrs[FINGERPRINT]) != problem_fingerprint(problem):
                raise refuse(f"was written for another case or other output settings than the checkpoint; {start_over}")
            count = int(t.shape[0])
    except OSError as exc:
        raise refuse(f"cannot be read as a netCDF-4 file ({' '.join(str(exc).split())[:120]}); {start_over}") from None
    if count < records:
        raise refuse(f"holds {count} records, the checkpoint {records}; run without --resume")


def _text(value: Any) -> str:
    """An HDF5 string attribute as ``str`` (h5py returns bytes for some)."""
    return value.decode("utf-8", "replace") if isinstance(value, bytes) else str(value)


class ResultStream:
    """An open streamed result file: written with no step (its layout, :func:`layout_bytes`), then
    appended to with h5py, one time entry at a time.

    Create one with :meth:`create` (a new file) or :meth:`reopen` (continue a file after a resume);
    :meth:`append` each recorded step; :meth:`finish` sets the final attributes and closes it.
    A record is written one append late: its fields are compressed on a thread of the stream
    (:func:`chunk_encoder`) while the run computes the next step, then written whole with the next
    append, :meth:`drain` or :meth:`finish`.

    The stream holds the file written, not only its name: should another process rename its own
    file over :attr:`path` (possible only when the run's lock file was removed under it), this one
    is neither finished nor renamed in its place; it is copied out instead
    (:class:`~viscontact.errors.OutputReplacedError`).

    Attributes
    ----------
    path
        The file written.
    identity
        ``os.fstat`` of the file written.
    count
        Records in the file (the queued one, :attr:`queued`, not counted).
    """

    def __init__(self, path: str | Path, problem: Problem, *, require_space: bool = True) -> None:
        import h5py

        self.path, self.problem, self.broken = Path(path), problem, False
        # no chunk cache: each chunk is written whole and once (a field's step; a series' chunk is
        # rewritten in place, 4 KiB); HDF5's default cache of 1 MiB per variable grew the process by
        # ~20 MiB over the first steps at 256^2 and kept creeping (allocator fragmentation)
        self.file = h5py.File(self.path, "a", rdcc_nbytes=0)
        # a descriptor of the file written (whatever its name becomes, until close()) and its
        # os.fstat: finish() and publish() check that self.path still names it
        self.identity = os.fstat(self.file.id.get_vfd_handle())
        self._own = os.open(self.path, os.O_RDONLY | getattr(os, "O_CLOEXEC", 0))  # not a dup: no HDF5 file lock
        if not os.path.samestat(os.fstat(self._own), self.identity):  # pragma: no cover - replaced this very moment
            os.close(self._own)
            self._own = -1
            self.close()
            raise OutputReplacedError(str(self.path), None, "replaced as it was opened")
        #: every variable along ``t`` by name (the coordinates ``t``, ``step``, the series, the fields)
        self.along_t = {name: var for name, var in self.file.items()
                        if isinstance(var, h5py.Dataset) and var.maxshape[:1] == (None,)}
        self.fields = [name for name in StepRecord.FIELDS if name in self.along_t]
        self.encoders = {name: chunk_encoder(self.along_t[name]) for name in self.fields}
        #: each variable's shape after ``t`` and dtype (read once: h5py's properties ask HDF5 each time)
        self.tails = {name: var.shape[1:] for name, var in self.along_t.items()}
        self.dtypes = {name: var.dtype for name, var in self.along_t.items()}
        self._one = h5py.h5s.create_simple((1,))
        self.pool: ThreadPoolExecutor | None = None
        #: the record appended last, not yet written: (record, its fields, their encodings' futures)
        self.queued: tuple[StepRecord, dict[str, np.ndarray], dict[str, Future]] | None = None
        self._queued_bytes = 0  # what the queued record may take on disk, claimed until it is written
        self.count = int(self.along_t["t"].shape[0])
        self.total = recorded_steps(problem)
        self._hold_metadata_until_flush()
        try:
            self.space = SpaceClaim(self.path, self._needed(), reserve=stream_bytes(problem, 0),
                                    required=require_space, hint=DISK_FULL_HINT)
        except OSError:
            self.close()
            raise

    @classmethod
    def create(cls, path: str | Path, problem: Problem, *, case_text: str = "", history: str = "",
               require_space: bool = True) -> ResultStream:
        """A new file at ``path`` (replaced if there) holding no step yet (``complete = 0``) and the
        fingerprint of ``problem`` (attribute :data:`FINGERPRINT`, checked by :meth:`reopen`);
        ``history`` is appended to its ``history`` attribute. The disk space of every record is
        claimed (``require_space``: or the disk-full error; else go on without a claim).

        Raises
        ------
        OSError
            The file cannot be written, or (``ENOSPC``) the disk cannot hold the result: no file
            is left behind.
        """
        from viscontact.io.checkpoint import problem_fingerprint

        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        write_atomically(path, layout_bytes(problem, case_text=case_text, history=history,
                                            attrs={FINGERPRINT: problem_fingerprint(problem), FLUSHED: 0}),
                         hint=DISK_FULL_HINT)
        try:
            return cls(path, problem, require_space=require_space)
        except BaseException:
            path.unlink(missing_ok=True)
            raise

    @classmethod
    def reopen(cls, path: str | Path, problem: Problem, records: int, *, require_space: bool = True,
               source: str | Path | None = None, history: str = "") -> ResultStream:
        """Continue the file at ``path`` after its first ``records`` records (later ones are dropped).

        The file (``source``, renamed to ``path`` once checked, when given) is first checked read-only
        (:func:`check_resumable`): nothing is changed in a file that is refused. Reopened, it loses
        ``stopped_by`` (the run goes on) and its ``history`` records the resume (with ``history``,
        e.g. the command).

        Raises
        ------
        ParameterError
            (key ``--resume``) No such file, a file that is not the streamed result of ``problem``
            (another case, not a result, unreadable) or that holds fewer than ``records`` records:
            one line naming the file.
        """
        from viscontact.io.results import history_stamp

        path = Path(path)
        source = path if source is None else Path(source)
        check_resumable(source, problem, records)
        if source != path:
            os.replace(source, path)
        stream = cls(path, problem, require_space=require_space)
        with signals_deferred():
            stream._resize(records)
            attrs = stream.file.attrs
            attrs["complete"] = 0
            attrs[FLUSHED] = records
            if "stopped_by" in attrs:
                del attrs["stopped_by"]
            attrs["history"] = f"{_text(attrs.get('history', ''))}; {history_stamp('resumed')} {history}".strip()
            stream.flush()
        return stream

    def _needed(self) -> int:
        """Bytes the records still to come need, finishing included (an upper bound)."""
        return stream_bytes(self.problem, max(self.total - self.count, 0), first=self.count)

    def _hold_metadata_until_flush(self) -> None:
        """Keep every changed HDF5 metadata entry in memory until :meth:`flush` (no eviction between
        two flushes), so the file on disk holds the metadata of the last flush, whatever comes after."""
        config = self.file.id.get_mdc_config()
        config.evictions_enabled = False
        config.incr_mode = config.flash_incr_mode = config.decr_mode = 0  # the H5C_*__off modes
        self.file.id.set_mdc_config(config)

    def _resize(self, count: int) -> None:
        for name, var in self.along_t.items():
            var.id.set_extent((count, *self.tails[name]))
        self.count = count

    def _put(self, name: str, k: int, value: Any) -> None:
        """Write the scalar ``value`` at ``t`` index ``k`` of the 1-D variable ``name`` (h5py's
        low-level write: a tenth of ``var[k] = value``'s overhead, which 24 variables a step add up)."""
        var = self.along_t[name].id
        space = var.get_space()
        space.select_hyperslab((k,), (1,))
        var.write(self._one, space, np.array([value], dtype=self.dtypes[name]))

    def append(self, record: StepRecord) -> None:
        """Queue ``record`` as the next time entry (fields not recorded are written as zeros, as
        :func:`~viscontact.io.results.to_dataset` does): the record queued before is written first
        (:meth:`drain`), then this one's fields start compressing on the stream's thread while the
        run computes the next step. It is written when the next record comes, or at :meth:`drain`
        (the checkpoint writer's) or :meth:`finish`.

        Raises
        ------
        OSError
            ``ENOSPC`` before anything is queued when the disk has not the room this record may
            take (the file stays as it was after the previous record). That room stays claimed
            (:class:`~viscontact.io.output_files.SpaceClaim`) until :meth:`drain` writes the record.
        """
        self.drain()
        nbytes = stream_bytes(self.problem, 1, first=self.count, finishing=False)
        self.space.check(nbytes, needed=self._needed())  # claimed until drain writes it
        self._queued_bytes = nbytes
        steps = {name: (np.zeros(self.tails[name], dtype=self.dtypes[name]) if getattr(record, name) is None
                        else getattr(record, name)) for name in self.fields}
        self.queued = (record, steps, self._encode(steps))

    def drain(self) -> int:
        """Write the queued record, if any, and flush, with SIGINT / SIGTERM held meanwhile: the file
        on disk then holds every record appended. The record's disk claim (kept since :meth:`append`)
        is handed back just before its bytes are written. Returns :attr:`count`.

        Raises
        ------
        OSError
            The write failed (:meth:`_rescue`: the file holds the records before this one).
        """
        if self.queued is None:
            return self.count
        (record, steps, encoded), self.queued, k = self.queued, None, self.count
        with signals_deferred():
            try:
                self.space.release(self._queued_bytes)  # the claim kept until now: the bytes go to disk next
                self._resize(k + 1)
                self._put("t", k, record.t)
                self._put("step", k, record.step)
                for name in StepRecord.scalars(self.problem.adhesion is not None, self.problem.tangential.rolls):
                    self._put(name, k, getattr(record, name))
                for name, step in steps.items():
                    if name in encoded:
                        mask, chunk = encoded[name].result()
                        self.along_t[name].id.write_direct_chunk((k, 0, 0), chunk, mask)
                    else:
                        self.along_t[name][k] = np.asarray(step, dtype=self.dtypes[name])
                self.count = k + 1
                self.flush()
                self.file.attrs[FLUSHED] = self.count  # the record is whole on disk: say so (FLUSHED)
                self.flush()
            except (OSError, RuntimeError) as exc:  # HDF5 reports a failed write as RuntimeError
                self._rescue(exc)
        return self.count

    def _encode(self, steps: dict[str, np.ndarray]) -> dict[str, Future]:
        """Start encoding the fields ``steps`` that have an encoder (:func:`chunk_encoder`) on the
        stream's compression threads; their futures by name."""
        if not any(self.encoders.values()):
            return {}
        if self.pool is None:
            self.pool = ThreadPoolExecutor(COMPRESSION_THREADS, thread_name_prefix="viscontact-compress")
        return {name: self.pool.submit(encode, steps[name]) for name, encode in self.encoders.items() if encode}

    def _rescue(self, exc: BaseException) -> None:
        """A write failed (the disk filled beyond the claim, an I/O error): give back the reserve and
        flush again, so that the file holds the steps before this one and can be finished, then
        raise one :class:`OSError` naming the file. When even that fails, the file is left as its
        last flush wrote it (``complete = 0``) and never touched again (:attr:`broken`). A full disk's
        error measures the free space before the reserve is given back (what this write found)."""
        full = disk_full_error(self.path, self._needed(), DISK_FULL_HINT)
        self.space.close()
        try:
            self._resize(self.count)
            self.flush()
        except (OSError, RuntimeError):
            self.broken = True
        if getattr(exc, "errno", None) in (errno.ENOSPC, errno.EDQUOT) or "No space left" in str(exc):
            raise full from None
        raise OSError(errno.EIO, f"writing the result failed ({' '.join(str(exc).split())[:200]})",
                      str(self.path)) from None

    def flush(self) -> None:
        """Push everything written so far to the operating system: the file on disk is valid as it
        is (a kill after this loses nothing written before)."""
        self.file.flush()

    def finish(self, attrs: dict[str, Any] | None = None) -> Path:
        """Write the queued record (:meth:`drain`), then set ``t_gross_sliding`` and ``complete`` as
        :func:`~viscontact.io.results.to_dataset` does (and ``attrs``, which override them), add the
        subsurface stresses the output asks for, fsync and close, with SIGINT / SIGTERM held
        meanwhile. Returns the path."""
        from viscontact.io.results import SCALES, completeness, t_gross_sliding

        self.drain()
        if not self.owned():
            error = self._replaced()
            self.close()
            if error.kept is not None:
                try:
                    orphan = ResultStream(error.kept, self.problem, require_space=False)
                    try:
                        orphan.finish(attrs)
                    finally:
                        orphan.close()
                except (OSError, RuntimeError, OutputReplacedError):  # the copy holds the records (complete = 0)
                    pass
            raise error
        f = self.file
        self.space.close()  # what is left of the claim is for the finishing writes
        self._stop_threads()
        with signals_deferred():
            if self.along_t["t"].shape[0] != self.count:  # an append interrupted (KeyboardInterrupt) part-way
                self._resize(self.count)
            t, phase, step = (self.along_t[name][:] for name in ("t", "phase", "step"))
            final = {"t_gross_sliding": t_gross_sliding(self.problem.tangential.mode, t, phase),
                     "complete": completeness(step, self.problem), **(attrs or {})}
            for key, value in final.items():
                f.attrs[key] = value
                if key in SCALES and key in f:  # also a scalar variable (to_dataset's scales)
                    f[key][()] = float(value)
            if final["complete"] == 1:  # nothing to resume, nothing torn: in-memory results have neither
                for key in (FINGERPRINT, FLUSHED):
                    if key in f.attrs:
                        del f.attrs[key]
            subsurface = _FileRecords(self.along_t, t) if self.problem.output.subsurface_depths and len(t) else None
            variables, coords = {}, {}
            if subsurface is not None:
                from viscontact.io.results import subsurface_variables

                variables, coords = subsurface_variables(subsurface, self.problem)
            from viscontact.io.results import cycle_variables  # fretting: the energy of each cycle

            cycles, cycle_coords = cycle_variables(t, self.along_t["delta_x"][:], self.along_t["friction_force"][:],
                                                   self.problem.tangential.mode)
            variables, coords = {**variables, **cycles}, {**coords, **cycle_coords}
            f.close()
            if variables:
                _append_variables(self.path, {**coords, **variables})
            os.fsync(self._own)
        return self.path

    def owned(self) -> bool:
        """Whether :attr:`path` still names the file this stream writes."""
        return is_same_file(self.identity, self.path)

    def publish(self, out: str | Path) -> Path:
        """Rename the finished file over ``out`` (:func:`~viscontact.io.output_files.move_atomically`) when
        :attr:`path` still names it, and let it go (:meth:`close`). Returns the file replaced.

        Raises
        ------
        OutputReplacedError
            Another process replaced :attr:`path`: nothing is renamed, and this stream's file is kept
            as a copy (:meth:`_replaced`).
        """
        try:
            return move_atomically(self.path, out, expected=self.identity)
        except OutputReplacedError:
            raise self._replaced() from None
        finally:
            self.close()

    def _replaced(self) -> OutputReplacedError:
        """The error of a file replaced by another process, once this stream's file (flushed: valid as
        it is) is copied to ``NAME.orphan-PID.nc`` beside it (``NAME``: :attr:`path` less
        :data:`PARTIAL_SUFFIX`), read from the descriptor the stream holds."""
        name = self.path.name.removesuffix(PARTIAL_SUFFIX)
        kept = self.path.with_name(f"{name}.orphan-{os.getpid()}.nc")
        size = os.fstat(self._own).st_size

        def copy(fh: Any) -> None:
            offset = 0
            while offset < size:
                chunk = os.pread(self._own, min(size - offset, 1 << 24), offset)
                if not chunk:
                    break
                fh.write(chunk)
                offset += len(chunk)

        try:
            write_atomically(kept, copy, size=size)
        except OSError as exc:
            return OutputReplacedError(str(self.path), None, exc.strerror or str(exc))
        return OutputReplacedError(str(self.path), str(kept))

    def close(self) -> None:
        """Close without finishing (the file stays valid, ``complete = 0``, holding the records
        written: a queued one is dropped, as a kill drops it) and give back the space claimed."""
        self.queued = None
        self._stop_threads()
        if self.file.id.valid:
            self.file.close()
        space = getattr(self, "space", None)
        if space is not None:
            space.close()
        if getattr(self, "_own", -1) >= 0:
            os.close(self._own)
            self._own = -1

    def _stop_threads(self) -> None:
        """Let the compression thread finish what it has and end it."""
        if getattr(self, "pool", None) is not None:
            self.pool.shutdown(wait=True)
            self.pool = None


def _append_variables(path: Path, variables: dict) -> None:
    """Add ``variables`` (name -> (dims, data, attrs), coordinates first) to the netCDF-4 file at
    ``path`` with h5netcdf, their new dimensions with them, no fill value: what xarray's
    ``to_netcdf(mode="a")`` of them writes, without loading xarray in a run."""
    import h5netcdf

    with h5netcdf.File(path, "a") as f:
        for name, (dims, data, attrs) in variables.items():
            dims, data = ((dims,) if isinstance(dims, str) else tuple(dims)), np.asarray(data)
            for dim, size in zip(dims, data.shape):
                if dim not in f.dimensions:
                    f.dimensions[dim] = size
            var = f.create_variable(name, dimensions=dims, data=data)
            for key, value in attrs.items():
                var.attrs[key] = value


class _FileRecord:
    """One record of a streamed file as :func:`viscontact.io.results.subsurface_variables` reads it:
    its time, and its fields read from the file on access."""

    def __init__(self, along_t: dict, t: float, k: int) -> None:
        self._along_t, self.t, self._k = along_t, t, k

    def __getattr__(self, name: str) -> Any:
        if name in StepRecord.FIELDS:
            var = self._along_t.get(name)
            return None if var is None else var[self._k]
        raise AttributeError(name)


class _FileRecords(Sequence):
    """The records of a streamed file, each read only when its fields are used."""

    def __init__(self, along_t: dict, t: np.ndarray) -> None:
        self._along_t, self._t = along_t, t

    def __len__(self) -> int:
        return len(self._t)

    def __getitem__(self, k: int) -> _FileRecord:  # type: ignore[override]
        if not -len(self) <= k < len(self):
            raise IndexError(k)
        return _FileRecord(self._along_t, float(self._t[k]), k % len(self))
