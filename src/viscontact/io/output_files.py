"""Writing result and checkpoint files without ever losing one.

Three guarantees, used by :func:`viscontact.io.netcdf.write_netcdf`, the checkpoints and the command
line:

* :func:`check_output_path` refuses, before anything is computed, an output path that could not be
  written at the end (read-only folder or mount, immutable file, a path under a regular file) or
  that must not be replaced: an existing file without ``force``, and even with ``force`` anything
  but a regular result file (never an input file of the run, never a device, FIFO or folder);
  :func:`check_output_folder` refuses a figure folder (``--plots``) that could not be made.
* :func:`write_atomically` writes under a temporary name in the destination folder, claims the
  whole size on disk first (``posix_fallocate``), fsyncs and renames over the destination: readers
  see the old file or the complete new one. A full disk is one :class:`OSError` (``ENOSPC``) that
  names the file, the size needed and the space free; no temporary file is left behind.
* :func:`signals_deferred`: SIGINT and SIGTERM arriving while a file is written are held and
  delivered once it is complete, so a finished run is never discarded half-written.
* :func:`output_lock`: an advisory lock (``flock``) on ``OUT.lock`` held for the whole command, taken
  before the output is checked: a second command writing the same file is refused in one line
  naming the process that writes it, instead of replacing that process's file under it. Should the
  lock file be removed under a run all the same, the file it streams is checked to be its own before
  it is renamed (:func:`move_atomically` with ``expected``), and its end leaves the other
  process's lock file alone.
* :class:`SpaceClaim`: the disk space a file growing as the run goes (a streamed result) will
  need, claimed before the run in an unnamed file and handed back piece by piece just before each
  write, which first checks that its piece is free: a full disk stops the run cleanly, between two
  writes, instead of failing inside one.

Symbolic links: an ``--out`` that is a symbolic link is followed; the new file replaces the link's
target (the link itself is kept), and the checks apply to the target.
"""
from __future__ import annotations

import errno
import glob
import os
import shutil
import signal
import stat
import tempfile
import threading
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import BinaryIO

from viscontact.io.safe_read import file_kind

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows: no inode flags, no advisory lock
    fcntl = None  # type: ignore[assignment]

__all__ = ["SpaceClaim", "check_derived_names", "check_output_folder", "check_output_path", "disk_full_error",
           "is_same_file", "link_target", "lock_path", "move_atomically", "output_lock", "remove_temporaries",
           "signals_deferred", "write_atomically"]

#: first bytes of the files a result may be: netCDF-4 (HDF5) and classic netCDF
RESULT_SIGNATURES = (b"\x89HDF\r\n\x1a\n", b"CDF\x01", b"CDF\x02")
#: ``FS_IOC_GETFLAGS`` and the inode flags that forbid replacing a file (Linux ``chattr +i / +a``)
_FS_IOC_GETFLAGS, _FS_IMMUTABLE_FL, _FS_APPEND_FL = 0x80086601, 0x10, 0x20
_DISK_FULL = (errno.ENOSPC, errno.EDQUOT)
#: what :func:`write_atomically` adds to a file's name for its temporary file (``tempfile.mkstemp``
#: appends 8 random characters to the prefix ``NAME.tmp``)
TEMPORARY_SUFFIX = ".tmp"
TEMPORARY_RANDOM = 8
#: the suffix of the lock file of :func:`output_lock`
LOCK_SUFFIX = ".lock"


def link_target(path: Path) -> Path:
    """``path`` with symbolic links followed (the file a write replaces)."""
    return Path(os.path.realpath(path)) if path.is_symlink() else path


def _existing_folder(path: Path) -> Path:
    """The deepest existing ancestor of ``path``; NotADirectoryError when it is not a folder."""
    folder = path.parent
    while not os.path.lexists(folder) and folder != folder.parent:
        folder = folder.parent
    if not folder.is_dir():
        raise NotADirectoryError(errno.ENOTDIR, f"{folder} is a file, not a folder: this path cannot be created",
                                 str(path))
    return folder


def _protected_flags(path: Path) -> str:
    """'immutable' / 'append-only' when the file carries that inode flag, else ''."""
    if fcntl is None:  # pragma: no cover - Windows
        return ""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    except OSError:
        return ""
    try:
        buf = bytearray(8)
        fcntl.ioctl(fd, _FS_IOC_GETFLAGS, buf)
        flags = int.from_bytes(buf[:4], "little")
    except OSError:  # the filesystem has no such flags
        return ""
    finally:
        os.close(fd)
    return "immutable" if flags & _FS_IMMUTABLE_FL else ("append-only" if flags & _FS_APPEND_FL else "")


def _is_result_file(path: Path) -> bool:
    """Empty, or starts like a netCDF file."""
    with open(path, "rb") as fh:
        head = fh.read(8)
    return not head or any(head.startswith(sig) for sig in RESULT_SIGNATURES)


def _probe_writable(folder: Path, path: Path, option: str = "--out") -> None:
    """Create and remove a file in ``folder``: the only check a read-only mount, an immutable
    folder or missing permissions cannot fool."""
    try:
        fd, probe = tempfile.mkstemp(prefix=".viscontact-probe-", dir=folder)
    except OSError as exc:
        raise OSError(exc.errno, f"cannot write in {folder}: {exc.strerror}; choose another folder ({option})",
                      str(path)) from None
    os.close(fd)
    os.unlink(probe)


def check_output_path(out: str | Path, *, force: bool = False, inputs: Iterable[str | Path] = (),
                      replace: bool = True) -> Path:
    """Refuse (before any computing) an output path the run could not write or must not replace.

    Parameters
    ----------
    out
        The file to be written.
    force
        Replace an existing result file (``--force``). Even then only a regular file that is empty or
        a netCDF file is replaced.
    inputs
        Files the run reads (case file, sweep file, height files): never replaced.
    replace
        False: an existing file is refused whatever ``force`` says.

    Returns
    -------
    Path
        The file a write replaces (``out`` with symbolic links followed).

    Raises
    ------
    OSError
        (``FileExistsError``, ``NotADirectoryError``, ``IsADirectoryError`` ...) naming ``out`` and
        saying why and what to do.
    """
    path = Path(out)
    if path.is_symlink() and not path.exists():
        raise FileNotFoundError(errno.ENOENT, f"is a symbolic link to the missing {os.readlink(path)}; "
                                "remove it or choose another --out", str(path))
    target = link_target(path)
    for name in inputs:
        if os.path.lexists(name) and os.path.exists(target) and os.path.samefile(name, target):
            raise FileExistsError(errno.EEXIST, f"is the input file {name}; refusing to overwrite it, "
                                  "choose another --out", str(path))
    if os.path.lexists(target):
        mode = os.stat(target).st_mode
        if stat.S_ISDIR(mode):
            raise IsADirectoryError(errno.EISDIR, "is a folder; give a file name (e.g. result.nc)", str(path))
        if not stat.S_ISREG(mode):
            raise FileExistsError(errno.EEXIST, "is not a regular file (a device, FIFO or socket); it is never "
                                  "replaced: choose another --out", str(path))
        if not (force and replace):
            raise FileExistsError(errno.EEXIST, "exists; refusing to overwrite it without --force", str(path))
        if not _is_result_file(target):
            raise FileExistsError(errno.EEXIST, "exists and is not a netCDF result file; refusing to replace it "
                                  "even with --force: choose another --out", str(path))
        flag = _protected_flags(target)
        if flag:
            raise PermissionError(errno.EPERM, f"is {flag} (chattr); it cannot be replaced: choose another --out",
                                  str(path))
    _probe_writable(_existing_folder(target), path)
    return target


def check_output_folder(folder: str | Path, *, option: str, files: Iterable[str | Path] = ()) -> Path:
    """Refuse (before any computing) a folder the figures could not be written into: an existing file
    that is not a folder, a path under a regular file, a folder (or the existing folder above it)
    that cannot be written, or one of ``files``, the other files the command reads or writes (its
    result). A missing folder is fine: it is created when the figures are written.

    Parameters
    ----------
    folder
        The folder for the figures (``--plots DIR``).
    option
        The command-line option that gave it, named in the errors.
    files
        Paths the folder must not be (it would be a file by the time the figures are written).

    Returns
    -------
    Path
        ``folder``.

    Raises
    ------
    OSError
        (``NotADirectoryError``, ``FileExistsError``, ...) naming ``folder`` and saying why.
    """
    path = Path(folder)
    for name in files:
        if os.path.realpath(name) == os.path.realpath(path):
            raise FileExistsError(errno.EEXIST, f"is also the file {name} of this command; give a folder for the "
                                  f"figures ({option})", str(path))
    if os.path.lexists(path) and not path.is_dir():
        raise NotADirectoryError(errno.ENOTDIR, f"exists and is not a folder; give a folder for the figures "
                                 f"({option})", str(path))
    _probe_writable(path if path.is_dir() else _existing_folder(path), path, option)
    return path


def remove_temporaries(path: str | Path) -> list[Path]:
    """Remove what writes of ``path`` killed half way (SIGKILL, power loss) left: ``NAME.tmp*`` beside
    it. Call it only when no other process writes ``path`` (resuming a run or a sweep)."""
    target = link_target(Path(path))
    found = list(target.parent.glob(f"{glob.escape(target.name)}{TEMPORARY_SUFFIX}*")) if target.parent.is_dir() else []
    for tmp in found:
        tmp.unlink(missing_ok=True)
    return found


def check_derived_names(out: str | Path, suffixes: Iterable[str] = (), plain: Iterable[str] = ()) -> None:
    """Refuse, before any computing, an ``out`` whose files written beside it would be longer than
    the folder's longest file name (``NAME_MAX``): ``out`` followed by each of ``suffixes`` (e.g.
    ``.partial``; ``out`` itself too), each written atomically (:func:`write_atomically`: plus its
    temporary suffix), and by each of ``plain`` (written as they are).

    Raises
    ------
    OSError
        ``ENAMETOOLONG`` naming ``out``, the longest suffix and the limit.
    """
    path = Path(out)
    target = link_target(path)
    try:
        limit = os.pathconf(_existing_folder(target), "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):  # no such limit known (or not POSIX): the usual one
        limit = 255
    temporary = f"{TEMPORARY_SUFFIX}{'X' * TEMPORARY_RANDOM}"
    endings = [f"{suffix}{temporary}" for suffix in ("", *suffixes)] + list(plain)
    longest = max(endings, key=lambda ending: len(os.fsencode(ending)))
    size = len(os.fsencode(target.name + longest))
    if size > limit:
        raise OSError(errno.ENAMETOOLONG, f"is too long: the run also writes its name followed by {longest!r} "
                      f"({size} bytes) where the folder allows {limit}; choose a shorter --out", str(path))


def lock_path(out: str | Path) -> Path:
    """The lock file of :func:`output_lock`: ``OUT.lock`` beside the file ``out`` names (beside its
    target when ``out`` is a symbolic link, as the streamed ``OUT.partial``)."""
    target = link_target(Path(out))
    return target.with_name(target.name + LOCK_SUFFIX)


#: the lock files this process holds (:func:`output_lock` is re-entrant within a process)
_HELD: dict[str, int] = {}


@contextmanager
def output_lock(out: str | Path, derived: Iterable[str] = ()) -> Iterator[Path | None]:
    """Hold an exclusive advisory lock on the output ``out`` while the body runs: ``flock`` on
    :func:`lock_path` (created, holding this process's id, and removed at the end). Take it before
    ``out`` (or the files beside it) is checked or written, so that what the checks see stays true.
    First the names of the lock file and of the files ``derived`` (suffixes of ``out``, e.g.
    ``.partial``) written beside ``out`` are checked (:func:`check_derived_names`).

    A second process asking for the lock of the same ``out`` is refused at once; within one process
    the lock is re-entrant. A lock file left by a killed process holds no lock and is reused. A
    folder of ``out`` that does not exist is created for the lock file (and removed at the end when
    left empty). Without ``fcntl`` (Windows) nothing is locked. Yields the lock file (None when
    nothing is locked).

    Raises
    ------
    BlockingIOError
        Another process holds the lock: ``"is being written by another viscontact process (pid N)"``,
        naming ``out``.
    OSError
        The lock file cannot be created (read-only folder, a path under a regular file), or a name
        is too long (``ENAMETOOLONG``), naming ``out``.
    """
    path = Path(out)
    check_derived_names(path, derived, plain=(LOCK_SUFFIX,))
    lock = lock_path(path)
    key = os.path.abspath(lock)
    if fcntl is None:  # pragma: no cover - Windows
        yield None
        return
    if key in _HELD:  # this process holds it already
        _HELD[key] += 1
        try:
            yield lock
        finally:
            _HELD[key] -= 1
        return
    existing = _existing_folder(link_target(path))
    _probe_writable(existing, path)
    lock.parent.mkdir(parents=True, exist_ok=True)
    fd = _acquire(lock, path)
    _HELD[key] = 1
    try:
        yield lock
    finally:
        del _HELD[key]
        if is_same_file(os.fstat(fd), lock):  # never the lock file of another process (ours was removed)
            lock.unlink(missing_ok=True)  # while still held: a process waiting on this file retries (_acquire)
        os.close(fd)
        folder = lock.parent
        while folder != existing and folder.is_dir() and not any(folder.iterdir()):
            try:
                folder.rmdir()
            except OSError:  # another process writes there now
                break
            folder = folder.parent


def _acquire(lock: Path, out: Path) -> int:
    """Open and ``flock`` the lock file ``lock`` of ``out``; its file descriptor. A file removed or
    replaced between the open and the lock (its holder ended) is opened again."""
    while True:
        fd = os.open(lock, os.O_RDWR | os.O_CREAT | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0), 0o644 & ~_umask())
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):  # flock of a FIFO or a device fails with EINVAL
            os.close(fd)
            raise FileExistsError(errno.EEXIST, f"its lock file {lock} is {file_kind(mode)}, not a lock file: remove "
                                  "it or choose another --out", str(out))
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            try:
                holder = os.read(fd, 32).decode("ascii", "replace").strip() or "unknown"
            finally:
                os.close(fd)
            raise BlockingIOError(errno.EWOULDBLOCK, f"is being written by another viscontact process (pid {holder}); "
                                  "wait for it to end or choose another --out", str(out)) from None
        except BaseException:
            os.close(fd)
            raise
        if is_same_file(os.fstat(fd), lock):
            os.ftruncate(fd, 0)
            os.write(fd, f"{os.getpid()}\n".encode())
            return fd
        os.close(fd)  # the holder removed it after we opened it: lock the file at that path now


def is_same_file(identity: os.stat_result, path: str | Path) -> bool:
    """Whether ``path`` still names the file ``identity`` (``os.fstat`` of an open file) is of: False
    when another file was renamed over it, or it was removed."""
    try:
        return os.path.samestat(identity, os.stat(path))
    except FileNotFoundError:
        return False


def disk_full_error(path: Path, needed: int, what: str = "") -> OSError:
    """The one-line error of a full disk: which file, how much it needs, how much is free, what to do."""
    try:
        free = format_size(shutil.disk_usage(path.parent).free)
    except OSError:
        free = "unknown"
    hint = what or "free some space or write elsewhere (--out)"
    return OSError(errno.ENOSPC, f"no space left on device: the file needs about {format_size(needed)}, "
                   f"{free} free in {path.parent}; {hint}", str(path))


class SpaceClaim:
    """Disk space claimed ahead in the folder of ``path`` for a file that grows as a run goes.

    The claim is an unnamed file (``O_TMPFILE``: nothing is left behind, even after ``kill -9``)
    of ``size`` bytes allocated at once (``posix_fallocate``). :meth:`check` says, keeping the claim,
    whether a piece can be written, :meth:`release` hands it back just before it is written
    (:meth:`take`: both at once); the last ``reserve`` bytes stay
    claimed until :meth:`close`, for the file's last write (finishing it, or saving it when a write
    failed). Where the filesystem cannot make unnamed or allocated files, nothing is claimed and
    :meth:`take` only checks the free space.

    Parameters
    ----------
    path
        The growing file (named in the errors).
    size
        Bytes the file will need from now on (an upper bound), ``reserve`` included.
    reserve
        Bytes kept claimed until :meth:`close`.
    required
        True: a disk that cannot hold ``size`` now is an error; False (``--force``): go on with
        ``reserve`` alone claimed (when free), each :meth:`take` checking the free space.
    hint
        What to do when the disk is full (the end of the error line).

    Raises
    ------
    OSError
        ``ENOSPC`` (:func:`disk_full_error`) when ``required`` and ``size`` is not free.
    """

    def __init__(self, path: str | Path, size: int, *, reserve: int = 0, required: bool = True,
                 hint: str = "") -> None:
        self.path, self.hint, self.claimed, self._fd = Path(path), hint, 0, -1
        try:
            self.block = os.statvfs(self.path.parent).f_frsize or 4096
        except OSError:
            self.block = 4096
        self.reserve = self._blocks(reserve)
        try:
            fd = os.open(self.path.parent, os.O_TMPFILE | os.O_RDWR, 0o600)
        except (OSError, AttributeError):  # no unnamed files here (or not Linux): free space checked per write
            return
        for claim in dict.fromkeys((self._blocks(max(size, reserve)), self.reserve)):
            try:
                if claim:
                    os.posix_fallocate(fd, 0, claim)
                self._fd, self.claimed = fd, claim
                return
            except OSError as exc:
                if exc.errno not in _DISK_FULL:
                    break  # the filesystem cannot allocate: free space checked per write
                if required:
                    os.close(fd)
                    raise disk_full_error(self.path, size, hint) from None
        os.close(fd)

    def take(self, nbytes: int, *, needed: int | None = None) -> None:
        """:meth:`check` then :meth:`release` ``nbytes``: for a write that happens at once.

        Raises
        ------
        OSError
            ``ENOSPC`` (:meth:`check`): the write must not be attempted.
        """
        self.check(nbytes, needed=needed)
        self.release(nbytes)

    def check(self, nbytes: int, *, needed: int | None = None) -> None:
        """Check, keeping the claim, that ``nbytes`` can be written: the claim above the reserve holds
        them, or the folder has what the claim lacks free. The free space is measured with the claim
        still held (what another program sees), so that the error says what is free for this write.

        Raises
        ------
        OSError
            ``ENOSPC`` naming the file, ``needed`` (what it still needs, default ``nbytes``) and the
            space free: the write must not be attempted.
        """
        held = max(self.claimed - self.reserve, 0) if self._fd >= 0 else 0
        if held >= nbytes:
            return
        if shutil.disk_usage(self.path.parent).free + held < nbytes:
            raise disk_full_error(self.path, needed or nbytes, self.hint)

    def release(self, nbytes: int) -> None:
        """Hand back ``nbytes`` of the claim (whole blocks, down to the reserve), just before the
        write that uses them: until then another program filling the disk cannot take them."""
        if self._fd >= 0 and self.claimed > self.reserve:
            self.claimed = max(self.claimed - self._blocks(nbytes), self.reserve)  # whole blocks: all freed
            os.ftruncate(self._fd, self.claimed)

    def _blocks(self, nbytes: int) -> int:
        """``nbytes`` rounded up to whole blocks of the filesystem."""
        return -(-max(nbytes, 0) // self.block) * self.block

    def close(self) -> None:
        """Give back what is left of the claim, the reserve included."""
        if self._fd >= 0:
            os.close(self._fd)
            self._fd, self.claimed = -1, 0


@contextmanager
def signals_deferred(signals: Iterable[int] = (signal.SIGINT, signal.SIGTERM)) -> Iterator[list[int]]:
    """Hold ``signals`` while the body runs and deliver them (to the handlers in place before) once
    it is done, normally or not. Yields the list of signals received. Outside the main thread (where
    handlers cannot be set) it does nothing."""
    received: list[int] = []
    if threading.current_thread() is not threading.main_thread():
        yield received
        return

    def hold(signum: int, frame: object) -> None:  # noqa: ARG001
        received.append(signum)

    previous = {sig: signal.signal(sig, hold) for sig in signals}
    try:
        yield received
    finally:
        for sig, old in previous.items():
            signal.signal(sig, old)
        for sig in dict.fromkeys(received):
            signal.raise_signal(sig)


def write_atomically(path: str | Path, content: bytes | memoryview | Callable[[BinaryIO], None], *,
                     size: int | None = None, hint: str = "") -> Path:
    """Write ``content`` (bytes, or a function writing into a binary file) to ``path`` atomically.

    The bytes go to a temporary file in the destination folder whose size (``len(content)`` or
    ``size``, when known) is claimed first; it is then flushed, fsynced and renamed over ``path``
    (over its target when ``path`` is a symbolic link). SIGINT / SIGTERM are held until the rename
    is done. Nothing but ``path`` is left on disk, whatever happens.

    Raises
    ------
    OSError
        ``ENOSPC`` with the size needed and the space free (``hint``: what to do), or any other
        error of the filesystem, always naming ``path``.
    """
    path = Path(path)
    target = link_target(path)
    if isinstance(content, (bytes, bytearray, memoryview)):
        size = memoryview(content).nbytes
    with signals_deferred():
        target.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f"{target.name}{TEMPORARY_SUFFIX}", dir=target.parent)
        try:
            with os.fdopen(fd, "wb") as fh:
                if size:
                    try:
                        os.posix_fallocate(fh.fileno(), 0, size)
                    except OSError as exc:
                        if exc.errno in _DISK_FULL:
                            raise
                if callable(content):
                    content(fh)
                else:
                    fh.write(content)
                fh.flush()
                os.fsync(fh.fileno())
                os.fchmod(fh.fileno(), 0o644 & ~_umask())
            os.replace(tmp, target)
        except OSError as exc:
            Path(tmp).unlink(missing_ok=True)
            if exc.errno in _DISK_FULL:
                raise disk_full_error(target, size or 0, hint) from None
            if exc.filename is None:
                raise OSError(exc.errno, exc.strerror or str(exc), str(path)) from None
            raise
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
    return target


def move_atomically(source: str | Path, path: str | Path, *, expected: os.stat_result | None = None) -> Path:
    """Rename the finished file ``source`` (in the same folder) over ``path`` (over its target when
    ``path`` is a symbolic link) with SIGINT / SIGTERM held, and fsync the folder so that the
    rename outlives a crash. Returns the file replaced.

    Parameters
    ----------
    source, path
        The file renamed and its new name.
    expected
        ``os.fstat`` of the file the caller wrote as ``source``: when ``source`` names another file
        now (another process replaced it), nothing is renamed.

    Raises
    ------
    OutputReplacedError
        ``source`` is not the file ``expected`` is of (its data is not kept: the caller keeps it).
    """
    from viscontact.errors import OutputReplacedError

    target = link_target(Path(path))
    with signals_deferred():
        if expected is not None and not is_same_file(expected, source):
            raise OutputReplacedError(str(source), None)
        os.replace(source, target)
        try:
            fd = os.open(target.parent, os.O_RDONLY)
        except OSError:
            return target
        try:
            os.fsync(fd)
        except OSError:  # some filesystems cannot fsync a folder
            pass
        finally:
            os.close(fd)
    return target


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def format_size(nbytes: float) -> str:
    """``nbytes`` in B, KiB, MiB, GiB or TiB (3 digits)."""
    for unit in ("B", "KiB", "MiB", "GiB", "TiB"):
        if nbytes < 1024 or unit == "TiB":
            return f"{nbytes:.3g} {unit}"
        nbytes /= 1024
    return f"{nbytes:.3g} TiB"
