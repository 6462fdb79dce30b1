"""Prony-term tables from files: the table pyvisco writes, or a plain CSV.

pyvisco (NREL, https://github.com/NREL/pyvisco) writes its Prony terms (``prony['df_terms']``
through ``out.to_csv(..., index_label='i')``) as a CSV with two header rows, quantities then units,
and an index column::

    i,tau_i,alpha_i,E_0,E_i
    -,s,-,MPa,MPa
    1,1.0e-05,0.0123,2510.0,30.87
    ...

``E`` (tensile) or ``G`` (shear) by the fitted modulus; moduli in Pa, kPa, MPa or GPa, times in s,
alpha_i = E_i / E_0 dimensionless. The relaxation modulus is E(t) = E_0 (1 - sum_i alpha_i
(1 - exp(-t/tau_i))), so its long-term value is E_0 (1 - sum alpha_i).

A plain CSV has one header row with columns ``tau`` [s] and ``g`` [Pa] and one row with
``tau = inf`` whose ``g`` is the long-term modulus.

Terms with a zero modulus (pyvisco leaves some after its bounded fit) are dropped. Every problem
is one :class:`ParameterError` (key ``material.file``) naming the file, the column and the line.
"""
from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass

from viscontact.errors import ParameterError
from viscontact.physics.materials import MODULUS_UNITS

__all__ = ["PronyTable", "parse_prony_table"]

_KEY = "material.file"


@dataclass(frozen=True)
class PronyTable:
    """Prony terms of a relaxation modulus M(t) = long_term + sum_i moduli_i exp(-t/tau_i).

    ``moduli`` and ``long_term`` in Pa, ``relaxation_times`` in s; ``quantity`` is ``"E"``
    (tensile), ``"G"`` (shear) or ``""`` (a plain table: what the case's ``modulus`` says).
    """

    long_term: float
    moduli: tuple[float, ...]
    relaxation_times: tuple[float, ...]
    quantity: str


class _Table:
    """Rows of a CSV with the position (file line) of each, for error messages."""

    def __init__(self, source: str, text: str) -> None:
        self.source = source
        self.rows = [(line, [cell.strip() for cell in row])
                     for line, row in enumerate(csv.reader(io.StringIO(text)), start=1)
                     if any(cell.strip() for cell in row)]
        if not self.rows:
            self.fail("the file is empty")

    def fail(self, what: str) -> None:
        raise ParameterError(_KEY, f"{self.source}: {what}")

    def column(self, header: list[str], names: tuple[str, ...], needed: str) -> int:
        for name in names:
            if header.count(name) > 1:
                self.fail(f"column {name} appears {header.count(name)} times in line 1 (one column each)")
            if name in header:
                return header.index(name)
        self.fail(f"missing column {needed} (columns found: {', '.join(h for h in header if h) or 'none'})")
        raise AssertionError  # unreachable

    def check_widths(self, columns: int) -> None:
        """Refuse a row with a value beyond the ``columns`` of the header (line 1): a value out of its
        column, or a column without a name, is not read silently."""
        for line, row in self.rows[1:]:
            extra = [cell for cell in row[columns:] if cell]
            if extra:
                self.fail(f"line {line} has {len(row)} columns, more than the {columns} named in line 1 "
                          f"({extra[0]!r} is in no named column)")

    def number(self, line: int, row: list[str], col: int, name: str, *, allow_inf: bool = False) -> float:
        if col >= len(row) or not row[col]:
            self.fail(f"column {name}, line {line}: missing value")
        try:
            if "_" in row[col]:  # Python's float reads 1_000; a number in a table has no separators
                raise ValueError(row[col])
            value = float(row[col])
        except ValueError:
            self.fail(f"column {name}, line {line}: {row[col]!r} is not a number")
        written_inf = row[col].strip().lower().lstrip("+") in ("inf", "infinity")
        if math.isnan(value) or (math.isinf(value) and not (allow_inf and written_inf)):
            what = "is out of range (above 1.8e308)" if math.isinf(value) and not written_inf else "is not a finite number"
            self.fail(f"column {name}, line {line}: {row[col]!r} {what}")
        if value < 0:
            self.fail(f"column {name}, line {line}: must be >= 0, got {row[col]}")
        return value


    def add_term(self, line: int, tau_column: str, tau: float, modulus: float, times: list[float],
                 moduli: list[float]) -> None:
        """Append the term (tau [s], modulus [Pa]) unless its modulus is zero; tau must be > 0."""
        if modulus == 0.0:
            return
        if not tau > 0:
            self.fail(f"column {tau_column}, line {line}: relaxation time must be > 0 s, got {tau:g}")
        times.append(tau)
        moduli.append(modulus)


def _is_number(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True


def parse_prony_table(text: str, source: str = "Prony table") -> PronyTable:
    """Parse the text of a Prony table (pyvisco's or a plain CSV); ``source`` names it in errors."""
    table = _Table(source, text.lstrip("\ufeff"))
    header = table.rows[0][1]
    table.check_widths(len(header))
    if "tau_i" in header:
        return _parse_pyvisco(table, header)
    if "tau" in header:
        return _parse_plain(table, header)
    table.fail("missing column tau_i (a pyvisco table: i, tau_i, alpha_i, E_0 or G_0, E_i or G_i, "
               "then a row of units) or tau (a plain table: tau [s], g [Pa])")
    raise AssertionError  # unreachable


#: a pyvisco table's two long-term moduli, E_0 (1 - sum alpha_i) and E_0 - sum E_i, must agree to this
LONG_TERM_AGREEMENT = 1e-3


def _parse_pyvisco(table: _Table, header: list[str]) -> PronyTable:
    c_tau = table.column(header, ("tau_i",), "tau_i")
    c_alpha = table.column(header, ("alpha_i",), "alpha_i")
    c_m0 = table.column(header, ("E_0", "G_0"), "E_0 or G_0")
    quantity = header[c_m0][0]
    c_mi = table.column(header, (f"{quantity}_i",), f"{quantity}_i (with {header[c_m0]})")
    if len(table.rows) < 2 or any(_is_number(cell) for cell in table.rows[1][1] if cell):
        table.fail(f"line 2 must be the row of units under the column names (s for tau_i, - for "
                   f"alpha_i, one of {', '.join(MODULUS_UNITS)} for {quantity}_0 and {quantity}_i)")
    line_units, units = table.rows[1]

    def unit(col: int) -> str:
        return units[col] if col < len(units) else ""

    if unit(c_tau) != "s":
        table.fail(f"column tau_i, line {line_units}: unit must be s, got {unit(c_tau)!r}")
    if unit(c_alpha) not in ("-", ""):
        table.fail(f"column alpha_i, line {line_units}: unit must be - (dimensionless), got {unit(c_alpha)!r}")
    scale = {}
    for col in (c_m0, c_mi):
        if unit(col) not in MODULUS_UNITS:
            table.fail(f"column {header[col]}, line {line_units}: unknown unit {unit(col)!r}; "
                       f"allowed: {', '.join(MODULUS_UNITS)}")
        scale[col] = MODULUS_UNITS[unit(col)]
    if len(table.rows) < 3:
        table.fail("no Prony terms below the two header rows")
    m0 = None
    alpha_sum = 0.0
    moduli, times = [], []
    for line, row in table.rows[2:]:
        tau = table.number(line, row, c_tau, "tau_i")
        alpha = table.number(line, row, c_alpha, "alpha_i")
        m0_row = table.number(line, row, c_m0, header[c_m0]) * scale[c_m0]
        mi = table.number(line, row, c_mi, header[c_mi]) * scale[c_mi]
        if m0 is None:
            if not m0_row > 0:
                table.fail(f"column {header[c_m0]}, line {line}: must be > 0, got {m0_row:g} Pa")
            m0 = m0_row
        elif not math.isclose(m0_row, m0, rel_tol=1e-9):
            table.fail(f"column {header[c_m0]}, line {line}: {m0_row:g} Pa differs from {m0:g} Pa above "
                       f"(one instantaneous modulus per table)")
        if not math.isclose(mi, alpha * m0, rel_tol=1e-6, abs_tol=1e-12 * m0):
            table.fail(f"column {header[c_mi]}, line {line}: {mi:g} Pa is not alpha_i * {header[c_m0]} "
                       f"= {alpha * m0:g} Pa")
        alpha_sum += alpha
        table.add_term(line, "tau_i", tau, mi, times, moduli)
    if not alpha_sum < 1.0:
        table.fail(f"column alpha_i, lines 3-{table.rows[-1][0]}: sum of alpha_i = {alpha_sum:.12g} must be < 1 "
                   f"(long-term modulus {quantity}_0 (1 - sum alpha_i) > 0)")
    long_term = m0 * (1.0 - alpha_sum)
    # the terms' own long-term modulus: alpha_i rounded in the file shift E_0 (1 - sum alpha_i) by the
    # rounding times E_0 / E(inf) (0.5 % at a ratio of 1e5 with 7 digits)
    from_terms = m0 - math.fsum(moduli)
    if not abs(long_term - from_terms) <= LONG_TERM_AGREEMENT * abs(long_term):
        table.fail(f"column alpha_i, lines 3-{table.rows[-1][0]}: the long-term modulus {quantity}_0 (1 - sum alpha_i) "
                   f"= {long_term:.6g} Pa and {quantity}_0 - sum {quantity}_i = {from_terms:.6g} Pa differ by more than "
                   f"{LONG_TERM_AGREEMENT:g} of it: alpha_i rounded? write them at full precision")
    return PronyTable(long_term, tuple(moduli), tuple(times), quantity)


def _parse_plain(table: _Table, header: list[str]) -> PronyTable:
    c_tau = table.column(header, ("tau",), "tau")
    c_g = table.column(header, ("g",), "g")
    long_term = None
    moduli, times = [], []
    for line, row in table.rows[1:]:
        tau = table.number(line, row, c_tau, "tau", allow_inf=True)
        g = table.number(line, row, c_g, "g")
        if math.isinf(tau):
            if long_term is not None:
                table.fail(f"column tau, line {line}: a second row with tau = inf (one long-term modulus)")
            if not g > 0:
                table.fail(f"column g, line {line}: long-term modulus (tau = inf) must be > 0 Pa, got {g:g}")
            long_term = g
            continue
        table.add_term(line, "tau", tau, g, times, moduli)
    if long_term is None:
        table.fail("column tau: no row with tau = inf giving the long-term modulus g [Pa]")
    return PronyTable(long_term, tuple(moduli), tuple(times), "")
