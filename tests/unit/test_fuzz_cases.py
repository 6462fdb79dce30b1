"""Config fuzzing: random and mutated case files either load (and validate) or fail with one
ParameterError line naming a key — never a traceback or another exception type.

Mutations change values and structure: keys set, deleted, invented; sections dropped, turned into
arrays or scalars, nested into each other; values wrapped in arrays (up to 300 deep), keys moved
between sections, the text cut or salted with garbage, NULs and byte-order marks.

Bounded for CI: 80 examples against the loader, 40 against the command line (``--dry-run``: full
validation, the guards and the resource estimate, no solve), each example milliseconds; the slow
test runs 600 structural examples through the command line.
"""
from __future__ import annotations

import io
import math
import tomllib
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from viscontact import cli
from viscontact.io.case import Case
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
    if isinstance(v, dict):  # an inline table
        return "{" + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + "}"
    return "[" + ", ".join(_toml_value(x) for x in v) + "]"


def _dump(data: dict) -> str:
    lines = [f"{k} = {_toml_value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    for section, body in data.items():
        if isinstance(body, dict):
            lines.append(f"[{section}]")
            lines += [f"{k} = {_toml_value(v)}" for k, v in body.items()]
    return "\n".join(lines) + "\n"


STRUCTURAL = ["wrap", "deep", "table_to_array", "table_to_scalar", "nest_section", "move_key", "array_of_tables",
              "duplicate_key", "nul", "bom", "truncate"]


def _mutate_structure(draw, data: dict, kind: str) -> dict:
    """``data`` after one structural mutation ``kind``."""
    sections = sorted(k for k, v in data.items() if isinstance(v, dict)) or ["grid"]
    section = draw(st.sampled_from(sections))
    body = data.get(section)
    keys = sorted(body) if isinstance(body, dict) else []
    if kind == "wrap" and keys:
        key = draw(st.sampled_from(keys))
        body[key] = [body[key]] * draw(st.integers(1, 3))
    elif kind == "deep" and keys:
        key = draw(st.sampled_from(keys))
        value = body[key]
        for _ in range(draw(st.sampled_from([2, 10, 100, 300]))):  # 5000 deep: test_hostile_inputs
            value = [value]
        body[key] = value
    elif kind == "table_to_array" and isinstance(body, dict):
        data[section] = [body.get(k) for k in keys if not isinstance(body.get(k), (dict, list))]
    elif kind == "table_to_scalar":
        data[section] = draw(scalars)
    elif kind == "nest_section" and isinstance(body, dict):
        other = draw(st.sampled_from(sections))
        if other != section and isinstance(data.get(other), dict):
            body[other] = dict(data[other])
    elif kind == "move_key" and keys:
        key = draw(st.sampled_from(keys))
        target = draw(st.sampled_from(sections))
        if isinstance(data.get(target), dict):
            data[target][key] = body.pop(key)
        else:
            data[key] = body.pop(key)
    elif kind == "array_of_tables" and isinstance(body, dict):
        data[section] = [dict(body), dict(body)]
    return data


@st.composite
def mutated_cases(draw, structural: bool = False) -> str:
    data = {k: (dict(v) if isinstance(v, dict) else v) for k, v in BASE.items()}
    text_edits = []
    for _ in range(draw(st.integers(1, 4))):
        kinds = ["set", "delete", "unknown", "drop_section"] + (STRUCTURAL if structural else [])
        kind = draw(st.sampled_from(kinds))
        section = draw(st.sampled_from(sorted(k for k, v in data.items() if isinstance(v, dict)) or ["grid"]))
        body = data.setdefault(section, {})
        if kind in STRUCTURAL:
            if kind in ("nul", "bom", "truncate", "duplicate_key"):
                text_edits.append(kind)
            else:
                data = _mutate_structure(draw, data, kind)
        elif kind == "set" and body:
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
    for edit in text_edits:
        if edit == "nul":
            at = draw(st.integers(0, len(text)))
            text = text[:at] + draw(st.sampled_from(["\\u0000", "\x00", "\\u001b"])) + text[at:]
        elif edit == "bom":
            text = "\ufeff" + text
        elif edit == "truncate":
            text = text[: draw(st.integers(0, len(text)))]
        elif edit == "duplicate_key":
            lines = text.splitlines()
            at = draw(st.integers(0, max(len(lines) - 1, 0)))
            text = "\n".join(lines[: at + 1] + lines[at:at + 1] + lines[at + 1:]) + "\n"
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


def _cli_exits_0_or_2_with_one_line(tmp_path, capsys, text) -> None:
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


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                HealthCheck.function_scoped_fixture])
@given(mutated_cases())
def test_cli_exits_0_or_2_with_one_line(tmp_path, capsys, text):
    _cli_exits_0_or_2_with_one_line(tmp_path, capsys, text)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated_cases(structural=True))
def test_loader_survives_structural_mutations(text):
    _load(text)


@pytest.mark.slow
@settings(max_examples=600, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                 HealthCheck.function_scoped_fixture])
@given(mutated_cases(structural=True))
def test_cli_survives_structural_mutations(tmp_path, capsys, text):
    _cli_exits_0_or_2_with_one_line(tmp_path, capsys, text)


@pytest.mark.parametrize("n", [10**6, 2**40, 16385])
def test_huge_grid_is_refused_before_any_allocation(n):
    with pytest.raises(ParameterError) as err:
        Case.from_toml_text(BASE_TEXT.replace("n = 128", f"n = {n}"), ROOT / "cases").to_problem()
    assert err.value.key == "grid.n" and "16384" in err.value.message


# --- issue 34: the files a case names and the files beside a result --------------------------------
#: what a named file may be: each either works or is refused in one line, never a hang or a traceback
FILE_KINDS = ["fifo", "loop", "dangling", "folder", "dev_zero", "dev_null", "empty", "sparse_huge", "npy_huge",
              "npy_malformed", "npy_truncated", "text", "valid"]


def _make_file(path: Path, kind: str, valid: bytes) -> None:
    """Put a file of ``kind`` at ``path`` (``valid``: the content of a good one)."""
    import os

    import numpy as np

    if kind == "fifo":
        os.mkfifo(path)
    elif kind == "loop":
        os.symlink(path.with_name(path.name + ".2"), path)
        os.symlink(path, path.with_name(path.name + ".2"))
    elif kind == "dangling":
        os.symlink(path.with_name("missing"), path)
    elif kind == "folder":
        path.mkdir()
    elif kind in ("dev_zero", "dev_null"):
        os.symlink("/dev/zero" if kind == "dev_zero" else "/dev/null", path)
    elif kind == "sparse_huge":
        with open(path, "wb") as fh:
            fh.truncate(8 << 30)
    elif kind in ("npy_huge", "npy_truncated"):
        with open(path, "wb") as fh:
            np.lib.format.write_array_header_1_0(fh, {"descr": "<f8", "fortran_order": False, "shape": (32, 32)})
            fh.write(b"\0" * 100) if kind == "npy_truncated" else fh.truncate(50 << 30)
    elif kind == "npy_malformed":
        path.write_bytes(b"\x93NUMPY\x01\x00\x20\x00{'descr': 'zzz', 'fortran_order': False, 'shape': (32, 32), }\n")
    elif kind == "text":
        path.write_text("tau,g\ninf,1e5\n0.1,2e5,9\n")
    elif kind == "valid":
        path.write_bytes(valid)
    else:
        path.write_bytes(b"")


def _named_file_case(folder: Path, key: str, kind: str) -> Path:
    """A 32^2 case whose ``key`` names a file of ``kind`` in ``folder``."""
    import numpy as np

    text = BASE_TEXT.replace("n = 128", "n = 32")
    if key == "material.file":
        text = text.replace('type = "zener"', 'type = "prony"\nfile = "named"\nmodulus = "shear"')
        for line in ("shear_modulus_instantaneous", "shear_modulus_long_term", "retardation_time"):
            text = "\n".join(x for x in text.splitlines() if not x.startswith(line))
        valid = b"tau,g\ninf,193000\n0.04,1737000\n"
    else:
        shape = "surface" if key == "indenter.file" else "topography"
        extra = "" if shape == "surface" else '\nunit = "m"\nphysical_size = [4e-3, 4e-3]'
        text = text.replace('shape = "sphere"\nradius = 0.01', f'shape = "{shape}"\nfile = "named"{extra}')
        x = -2e-3 + (np.arange(32) + 0.5) * 4e-3 / 32
        heights = (x[:, None] ** 2 + x ** 2) / 0.02
        buffer = io.BytesIO()
        np.save(buffer, heights)
        valid = buffer.getvalue() if shape == "surface" else (
            "\n".join(" ".join(f"{-v:.9e}" for v in row) for row in heights) + "\n").encode()
    _make_file(folder / "named", kind, valid)
    case = folder / "case.toml"
    case.write_text(text)
    return case


def _one_line_in_time(capsys, args: list[str], seconds: int = 60) -> int:
    """Run the command line in this process with an alarm: a hang fails the test, never blocks it."""
    import signal

    def hung(signum, frame):
        raise AssertionError(f"viscontact {' '.join(args)} hung")

    previous = signal.signal(signal.SIGALRM, hung)
    signal.alarm(seconds)
    try:
        code = cli.main(args)
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    errors = [line for line in err if not line.startswith("viscontact: warning:")]
    assert code in (0, 2), err
    assert "Traceback" not in "\n".join(err)
    assert len(errors) == (1 if code == 2 else 0) and all(e.startswith("viscontact: error:") for e in errors), err
    return code


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.sampled_from(["material.file", "indenter.file", "indenter.file (topography)"]), st.sampled_from(FILE_KINDS))
def test_the_files_a_case_names_are_read_safely(tmp_path, capsys, key, kind):
    """Every kind of file as the Prony table, the height file or the topography: a dry run works or
    refuses it in one line naming the key, never a hang, a traceback or a read of gigabytes."""
    import tempfile

    folder = Path(tempfile.mkdtemp(dir=tmp_path))
    case = _named_file_case(folder, key, kind)
    code = _one_line_in_time(capsys, ["run", str(case), "--out", str(folder / "r.nc"), "--dry-run"])
    assert code == 0 or kind != "valid", (key, kind)


@settings(max_examples=16, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.sampled_from([".checkpoint.npz", ".lock", ".partial", ""]),
       st.sampled_from(["fifo", "loop", "dangling", "folder", "dev_zero", "dev_null", "empty", "text"]))
def test_the_files_beside_a_result_are_handled_safely(tmp_path, capsys, suffix, kind):
    """Every kind of file named OUT.nc, OUT.nc.checkpoint.npz, OUT.nc.lock or OUT.nc.partial: the run
    works or is refused in one line, never a hang or a traceback, and the file is left as it was."""
    import os
    import tempfile

    folder = Path(tempfile.mkdtemp(dir=tmp_path))
    beside = folder / ("r.nc" + suffix)
    _make_file(beside, kind, b"")
    before = os.lstat(beside)
    _one_line_in_time(capsys, ["run", str(ROOT / "cases" / "creep_indentation.toml"), "--out", str(folder / "r.nc"),
                               "--set", "grid.n=16", "--set", "time.t_end=0.001", "--quiet", "--checkpoint-every", "2"])
    if suffix != ".lock" and os.path.lexists(beside):  # a lock file is the run's to replace
        after = os.lstat(beside)
        assert (after.st_ino, after.st_mode) == (before.st_ino, before.st_mode) or kind in ("empty", "dangling")
