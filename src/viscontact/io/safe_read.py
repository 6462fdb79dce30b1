"""One safe way to open the files a case or a command names: every input goes through here.

A name given by a user may point at anything: a folder, a FIFO (opening it blocks until a writer
comes), a device (``/dev/zero`` never ends), a symbolic link loop, a sparse file of terabytes, or a
``.npy`` file whose header is malformed or claims another size. Each is refused here with one
sentence (a :class:`~viscontact.errors.ParameterError` naming the key), before anything is read
whole:

* :func:`regular_input`: a regular file (links followed) of at most ``max_bytes``; what it is
  otherwise, in words (:func:`file_kind`).
* :func:`read_text_input`: the text of a small input (a case, sweep or Prony table), at most
  :data:`MAX_INPUT_BYTES`; a pipe with a writer (``<(...)``) or a device is read, without blocking
  and for at most :data:`PIPE_TIMEOUT` s of silence, a FIFO with no writer refused.
* :func:`npy_layout`: the shape, dtype and data offset of a ``.npy`` file, its header parsed
  with every failure caught and the size it declares checked against the file's.
"""
from __future__ import annotations

import errno
import math
import os
import select
import stat
from pathlib import Path

import numpy as np

from viscontact.errors import ParameterError

__all__ = ["MAX_INPUT_BYTES", "PIPE_TIMEOUT", "file_kind", "npy_layout", "read_text_input", "regular_input",
           "size_in_words"]

#: largest text input file read [bytes]: a case, sweep or Prony table is a few kB; a name that points
#: at a result file or a device must not be read into memory whole
MAX_INPUT_BYTES = 16 << 20
#: longest wait [s] for the next bytes of a pipe or device named as a text input
PIPE_TIMEOUT = 10.0

_KINDS = ((stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISSOCK, "a socket"),
          (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"))


def file_kind(mode: int) -> str:
    """What a file of ``st_mode`` ``mode`` is, in words (``"a regular file"``, ``"a FIFO (named pipe)"``, ...)."""
    for test, kind in _KINDS:
        if test(mode):
            return kind
    return "a regular file" if stat.S_ISREG(mode) else "not a regular file"


def size_in_words(nbytes: float) -> str:
    """A size [bytes] as a person reads it: ``"17 MiB"``, ``"8 GiB"``."""
    for unit, shift in (("TiB", 40), ("GiB", 30), ("MiB", 20), ("kiB", 10)):
        if nbytes >= 1 << shift:
            return f"{nbytes / (1 << shift):.3g} {unit}"
    return f"{int(nbytes)} bytes"


def _stat(path: Path, key: str) -> os.stat_result:
    """``os.stat`` of ``path`` (links followed), its failures as one :class:`ParameterError`."""
    try:
        return os.stat(path)
    except FileNotFoundError:
        if os.path.islink(path):
            raise ParameterError(key, f"{path} is a symbolic link to a missing file") from None
        raise ParameterError(key, f"no such file: {path}") from None
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise ParameterError(key, f"{path} is a loop of symbolic links, not a file") from None
        raise ParameterError(key, f"cannot read {path}: {exc.strerror}") from None


def regular_input(path: str | Path, key: str, *, max_bytes: float | None = None, need: str = "a file") -> int:
    """The size [bytes] of the input file ``path``, after refusing anything but a regular file of at
    most ``max_bytes`` (None: any size).

    Parameters
    ----------
    path
        The file (symbolic links followed).
    key
        The case key or option naming it, for the error.
    max_bytes
        The largest size accepted [bytes].
    need
        What the input must be, in words (``"a .npy file"``), for the error.

    Raises
    ------
    ParameterError
        Missing, a symbolic link loop, a folder, FIFO, socket or device, unreadable, or larger than
        ``max_bytes``: one sentence saying which.
    """
    path = Path(path)
    info = _stat(path, key)
    if not stat.S_ISREG(info.st_mode):
        raise ParameterError(key, f"{path} is {file_kind(info.st_mode)}, not a regular file: give {need}")
    if not os.access(path, os.R_OK):
        raise ParameterError(key, f"cannot read {path}: permission denied")
    if max_bytes is not None and info.st_size > max_bytes:
        raise ParameterError(key, f"{path} holds {size_in_words(info.st_size)}, more than the "
                             f"{size_in_words(max_bytes)} such an input can take (is it the right file?)")
    return info.st_size


def _read_stream(fd: int, path: Path, key: str, limit: int, fifo: bool) -> bytes:
    """Up to ``limit`` bytes of the non-blocking ``fd`` (a pipe or device), waiting at most
    :data:`PIPE_TIMEOUT` s for each chunk."""
    chunks, total = [], 0
    while total < limit:
        try:
            chunk = os.read(fd, min(1 << 20, limit - total))
        except BlockingIOError:
            ready, _, _ = select.select([fd], [], [], PIPE_TIMEOUT)
            if not ready:
                raise ParameterError(key, f"{path} is {'a pipe' if fifo else 'a device'} that sent nothing for "
                                     f"{PIPE_TIMEOUT:g} s: give a regular file") from None
            continue
        if not chunk:
            break
        chunks.append(chunk)
        total += len(chunk)
    if fifo and not chunks:
        raise ParameterError(key, f"{path} is a FIFO (named pipe) with no writer (nothing to read): give a regular "
                             "file")
    return b"".join(chunks)


def read_text_input(path: str | Path, key: str, max_bytes: int = MAX_INPUT_BYTES) -> str:
    """The UTF-8 text (a byte-order mark skipped) of a small input file: a case, sweep or Prony table.

    A regular file larger than ``max_bytes`` is refused unread; a pipe with a writer (``<(...)``) or a
    readable device is read without blocking, at most ``max_bytes`` of it and waiting at most
    :data:`PIPE_TIMEOUT` s for each chunk; a FIFO with no writer, a folder or a socket is refused.

    Raises
    ------
    ParameterError
        Key ``key``: missing, not a file, too large, silent, unreadable or not UTF-8, in one sentence.
    """
    path = Path(path)
    info = _stat(path, key)
    mode = info.st_mode
    if stat.S_ISDIR(mode) or stat.S_ISSOCK(mode):
        raise ParameterError(key, f"{path} is {file_kind(mode)}, not a file: give a text file")
    too_large = ParameterError(key, f"{path} holds more than {max_bytes >> 20} MiB: a text input is a few kB (is "
                               "it the right file?)")
    if stat.S_ISREG(mode) and info.st_size > max_bytes:
        raise too_large
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        raise ParameterError(key, f"cannot read {path}: {exc.strerror}") from None
    try:
        if stat.S_ISREG(mode):
            with os.fdopen(os.dup(fd), "rb") as fh:
                data = fh.read(max_bytes + 1)
        else:
            data = _read_stream(fd, path, key, max_bytes + 1, stat.S_ISFIFO(mode))
    except OSError as exc:
        raise ParameterError(key, f"cannot read {path}: {exc.strerror or exc}") from None
    finally:
        os.close(fd)
    if len(data) > max_bytes:
        raise too_large
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ParameterError(key, f"cannot read {path}: {exc}") from None


def npy_layout(path: str | Path, key: str, need: str = "a .npy file") -> tuple[tuple[int, ...], np.dtype, bool, int]:
    """(shape, dtype, fortran_order, data offset [bytes]) of the ``.npy`` file ``path``, a regular file
    (:func:`regular_input`) whose size is exactly what its header declares.

    Raises
    ------
    ParameterError
        Key ``key``: not a regular file, a header that is not a ``.npy`` header (any parse failure,
        a malformed dtype or shape), or a file shorter (truncated) or longer than its header says.
    """
    path = Path(path)
    size = regular_input(path, key, need=need)
    try:
        with open(path, "rb") as fh:
            if fh.read(6) != b"\x93NUMPY":
                raise ParameterError(key, f"{path} is not a .npy file (it does not start as numpy writes one)")
            fh.seek(0)
            version = np.lib.format.read_magic(fh)
            header = np.lib.format.read_array_header_1_0 if version == (1, 0) else np.lib.format.read_array_header_2_0
            shape, fortran, dtype = header(fh)
            offset = fh.tell()
    except ParameterError:
        raise
    except Exception as exc:  # noqa: BLE001 - the header parser raises anything (tokenize.TokenError, SyntaxError...)
        reason = " ".join(str(exc).split())[:200] or type(exc).__name__
        raise ParameterError(key, f"cannot read {path} as a .npy array: its header is malformed ({reason})") from None
    if not all(isinstance(d, int) and d >= 0 for d in shape):
        raise ParameterError(key, f"cannot read {path} as a .npy array: its header gives the shape {shape}")
    expected = offset + (0 if dtype.hasobject else dtype.itemsize * math.prod(shape))
    if size < expected:
        raise ParameterError(key, f"{path} is shorter than its header says (truncated)")
    if size > expected and not dtype.hasobject:
        raise ParameterError(key, f"{path} holds {size_in_words(size)}, more than its header's {tuple(shape)} "
                             f"array of {dtype} ({size_in_words(expected)}): it is not a .npy file as written by numpy")
    return tuple(shape), dtype, bool(fortran), offset

