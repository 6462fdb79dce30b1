"""Config fuzzing: random and mutated case files either load (and validate) or fail with one
ParameterError line naming a key — never a traceback or another exception type.

Bounded for CI: 80 examples against the loader, 40 against the command line (``--dry-run``: full
validation and the resource estimate, no solve), each example milliseconds.
"""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from viscontact import cli
from viscontact.case import Case
from viscontact.errors import ParameterError

ROOT = Path(__file__).resolve().parents[2]
BASE_TEXT = (ROOT / "cases" / "creep_indentation.toml").read_text()
BASE = tomllib.loads(BASE_TEXT)

scalars = st.one_of(
    st.integers(-10**12, 10**12), st.sampled_from([0, 1, 7, 10**6, 2**40, -1]), st.floats(allow_nan=True, allow_infinity=True), st.booleans(),
    st.text(max_size=12), st.sampled_from(["zener", "prony", "elastic", "sphere", "surface", "load",
                                           "displacement", "partial_slip", "linear", "x.npy"]))
values = st.one_of(scalars, st.lists(scalars, max_size=4), st.lists(st.lists(scalars, max_size=3), max_size=3))


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v == math.inf else ("-inf" if v == -math.inf else repr(v)))
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return '"' + v.encode("unicode_escape").decode("ascii").replace('"', '\\"') + '"'
    return "[" + ", ".join(_toml_value(x) for x in v) + "]"


def _dump(data: dict) -> str:
    lines = [f"{k} = {_toml_value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    for section, body in data.items():
        if isinstance(body, dict):
            lines.append(f"[{section}]")
            lines += [f"{k} = {_toml_value(v)}" for k, v in body.items()]
    return "\n".join(lines) + "\n"


@st.composite
def mutated_cases(draw) -> str:
    data = {k: (dict(v) if isinstance(v, dict) else v) for k, v in BASE.items()}
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(["set", "delete", "unknown", "drop_section"]))
        section = draw(st.sampled_from(sorted(k for k, v in data.items() if isinstance(v, dict)) or ["grid"]))
        body = data.setdefault(section, {})
        if kind == "set" and body:
            body[draw(st.sampled_from(sorted(body)))] = draw(values)
        elif kind == "set":
            data["grid"] = {"n": draw(values), "half_width": 2e-3}
        elif kind == "delete" and body:
            body.pop(draw(st.sampled_from(sorted(body))))
        elif kind == "unknown":
            body[draw(st.from_regex(r"[a-z_]{1,12}", fullmatch=True))] = draw(values)
        elif kind == "drop_section":
            data.pop(section, None)
    text = _dump(data)
    if draw(st.booleans()):  # garbage in the text itself
        at = draw(st.integers(0, len(text)))
        text = text[:at] + draw(st.text(max_size=8)) + text[at:]
    return text


def _load(text: str) -> None:
    try:
        Case.from_toml_text(text, ROOT / "cases").to_problem()
    except ParameterError as exc:
        assert exc.key and exc.message and "\n" not in str(exc)


def test_the_shipped_case_round_trips_through_the_fuzzer_dump():
    assert tomllib.loads(_dump(BASE)) == BASE


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated_cases())
def test_loader_accepts_or_names_the_key(text):
    _load(text)


@settings(max_examples=80, deadline=None)
@given(st.text(max_size=200))
def test_loader_on_random_text(text):
    _load(text)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                HealthCheck.function_scoped_fixture])
@given(mutated_cases())
def test_cli_exits_0_or_2_with_one_line(tmp_path, capsys, text):
    case = tmp_path / "case.toml"
    case.write_text(text, encoding="utf-8", errors="surrogatepass")
    code = cli.main(["run", str(case), "--out", str(tmp_path / "r.nc"), "--dry-run", "--force"])
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    errors = [line for line in err if not line.startswith("viscontact: warning:")]
    assert code in (0, 2), err
    assert "Traceback" not in "\n".join(err)
    if code == 2:
        assert len(errors) == 1 and errors[0].startswith("viscontact: error:")
    else:
        assert not errors


@pytest.mark.parametrize("n", [10**6, 2**40, 16385])
def test_huge_grid_is_refused_before_any_allocation(n):
    with pytest.raises(ParameterError) as err:
        Case.from_toml_text(BASE_TEXT.replace("n = 128", f"n = {n}"), ROOT / "cases").to_problem()
    assert err.value.key == "grid.n" and "16384" in err.value.message
