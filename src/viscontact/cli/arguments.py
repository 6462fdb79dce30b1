"""What the command line's argument values mean: ``--set KEY=VALUE`` overrides, comma-separated
positive numbers (``--speeds``, ``--times``), the result file's name, and the command as one line."""
from __future__ import annotations

import shlex
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from viscontact.errors import ParameterError

__all__ = ["check_result_name", "command_line", "parse_overrides", "parse_positive", "parse_value"]


def parse_value(text: str) -> Any:
    """A ``--set`` value as TOML (number, boolean, array, quoted string), else the bare string;
    an empty value removes the key (``--set time.dt=``: its default applies)."""
    import tomllib

    if not text:
        return None
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def parse_overrides(items: Sequence[str]) -> dict[str, Any]:
    """``--set KEY=VALUE`` arguments as dotted keys and values."""
    overrides = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key.strip():
            raise ParameterError("--set", f"expected KEY=VALUE (e.g. tangential.sliding_speed=0.1), got {item!r}")
        try:  # a case file is UTF-8 text, and so is what the result stores of it (title, case text)
            item.encode("utf-8")
        except UnicodeEncodeError:
            raise ParameterError("--set", f"{item!r} holds bytes that are not UTF-8 text (shown as \\udcNN); "
                                 "type it in a UTF-8 terminal or put it in the case file") from None
        overrides[key.strip()] = parse_value(value.strip())
    return overrides


def check_result_name(out: str) -> None:
    """A result file (``--out`` of run, steady, sweep) is netCDF-4: its name must end in ``.nc``."""
    if Path(out).suffix != ".nc":
        raise ParameterError("--out", f"must be a netCDF-4 result file named *.nc, got {out!r}")


def parse_positive(text: str, option: str, unit: str, example: str, zero: bool = False,
                   signed: bool = False) -> list[float]:
    """Comma-separated finite numbers > 0 (``zero``: >= 0; ``signed``: of any sign), each once
    (``--speeds``, ``--times``, ``--creepages``)."""
    from viscontact.io.values import positive_values

    try:
        values = [float(s) for s in text.split(",") if s.strip()]
    except ValueError:
        raise ParameterError(option, f"expected comma-separated numbers in {unit} (e.g. {example}), got {text!r}") from None
    return positive_values(values, option, unit, repr(text), zero=zero, signed=signed)


def command_line(argv: Sequence[str]) -> str:
    """The arguments ``argv`` as one shell-quoted line of valid UTF-8 (what a result's ``history``
    and the log record): a byte of an argument that is not UTF-8 (which Python carries as a lone
    surrogate) is written ``\\xNN``."""
    line = shlex.join(argv)
    try:
        raw = line.encode("utf-8", "surrogateescape")
    except UnicodeEncodeError:  # a lone surrogate that is no escaped byte (an argv given in Python)
        raw = line.encode("utf-8", "backslashreplace")
    return raw.decode("utf-8", "backslashreplace")
