"""Lists of values typed by a user (``--speeds``, ``--times``, ``run_steady(speeds=...)``), checked
before they become a coordinate of a result."""
from __future__ import annotations

from viscontact.errors import ParameterError
from viscontact.problem.problem import is_number

__all__ = ["positive_values"]


def positive_values(values: object, key: str, unit: str, given: str | None = None, *,
                    zero: bool = False, signed: bool = False) -> list[float]:
    """``values`` (a sequence of numbers) as a list of floats after checking that it is not empty and
    that each is a finite number > 0 (``zero``: >= 0) given once (a coordinate along them, ``speed``
    or a time, would repeat a value): the speeds of a steady speed curve, the times of
    ``plot --times`` (t = 0 included); ``signed``: any finite number (the creepages of a
    traction-creepage curve).

    Raises
    ------
    ParameterError
        Naming ``key`` and ``unit``, quoting ``given`` (the text typed) or the values.
    """
    shown = given if given is not None else repr(values)
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise ParameterError(key, f"must be a list of numbers in {unit}, got {shown}")
    values = list(values)
    if not all(is_number(v) for v in values):
        raise ParameterError(key, f"must be a list of numbers in {unit}, got {shown}")
    values = [float(v) for v in values]
    if not values:
        raise ParameterError(key, f"must list at least one number in {unit}, got {shown}")
    if signed and any(abs(v) == float("inf") or v != v for v in values):
        raise ParameterError(key, f"every value must be a finite number {unit}, got {shown}")
    if not signed and any(not (0 <= v if zero else 0 < v) or v == float("inf") for v in values):
        raise ParameterError(key, f"every value must be a finite number {'>=' if zero else '>'} 0 {unit}, got {shown}")
    twice = sorted({v for v in values if values.count(v) > 1})
    if twice:  # a result along them would have a coordinate with repeated values
        raise ParameterError(key, f"{', '.join(f'{v:g}' for v in twice)} {unit} is listed more than once, got {shown}")
    return values
