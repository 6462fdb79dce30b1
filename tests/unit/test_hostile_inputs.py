"""Hostile input files (issue 14 items 4 and 6): one line and exit 2, never a traceback or a hang,
and resume refuses a checkpoint that does not match what the result would be."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from viscontact import cli
from viscontact.errors import ParameterError

ROOT = Path(__file__).resolve().parents[2]
CREEP_TEXT = (ROOT / "cases" / "creep_indentation.toml").read_text()
SMALL = ["--set", "grid.n=32", "--set", "time.t_end=0.005"]


def _main(capsys, *args) -> tuple[int, list[str]]:
    code = cli.main(list(map(str, args)))
    return code, [line for line in capsys.readouterr().err.splitlines() if line.strip()]


def _one_line(code: int, err: list[str], key: str) -> None:
    assert code == 2 and len(err) == 1, err
    assert err[0].startswith(f"viscontact: error: {key}"), err[0]


def _surface_case(tmp_path: Path, heights: str = "h.npy") -> Path:
    text = CREEP_TEXT.replace('shape = "sphere"\nradius = 0.01                         # m',
                              f'shape = "surface"\nfile = "{heights}"')
    assert text != CREEP_TEXT
    case = tmp_path / "case.toml"
    case.write_text(text.replace("n = 128", "n = 32"))
    return case


def _sphere_heights(n: int = 32, half_width: float = 2e-3) -> np.ndarray:
    x = -half_width + (np.arange(n) + 0.5) * 2 * half_width / n
    xx, yy = np.meshgrid(x, x)
    return (xx**2 + yy**2) / (2 * 0.01)


def test_a_sphere_height_file_runs_as_a_dry_run(tmp_path, capsys):
    np.save(tmp_path / "h.npy", _sphere_heights())
    code, err = _main(capsys, "run", _surface_case(tmp_path), "--out", tmp_path / "r.nc", "--dry-run")
    assert code == 0, err


@pytest.mark.parametrize("content", ["empty", "huge_header", "complex", "truncated", "object"])
def test_bad_height_files_are_one_line(tmp_path, capsys, content):
    path = tmp_path / "h.npy"
    if content == "empty":
        path.write_bytes(b"")
    elif content == "huge_header":  # claims 10^10 elements: must not try to allocate 80 GB
        with open(path, "wb") as fh:
            header = {"descr": "<f8", "fortran_order": False, "shape": (100000, 100000)}
            np.lib.format.write_array_header_1_0(fh, header)
    elif content == "complex":  # used to drop the imaginary part silently
        np.save(path, _sphere_heights() * (1 + 1j))
    elif content == "truncated":
        np.save(path, _sphere_heights())
        path.write_bytes(path.read_bytes()[:-100])
    else:
        np.save(path, np.array([["a"] * 32] * 32, dtype=object), allow_pickle=True)
    code, err = _main(capsys, "run", _surface_case(tmp_path), "--out", tmp_path / "r.nc", "--dry-run")
    _one_line(code, err, "indenter.file")


def test_fifo_as_height_file_does_not_hang(tmp_path):
    os.mkfifo(tmp_path / "h.npy")
    proc = subprocess.run([sys.executable, "-m", "viscontact.cli", "run", str(_surface_case(tmp_path)), "--out",
                           str(tmp_path / "r.nc"), "--dry-run"], capture_output=True, text=True, timeout=120)
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 2 and len(lines) == 1 and "indenter.file" in lines[0] and "regular file" in lines[0]


def test_deeply_nested_arrays_are_one_line(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(CREEP_TEXT.replace("[material]", "junk = " + "[" * 5000 + "]" * 5000 + "\n[material]", 1))
    code, err = _main(capsys, "run", case, "--out", tmp_path / "r.nc", "--dry-run")
    _one_line(code, err, "case file")


def test_nul_in_the_title_is_refused_up_front(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(CREEP_TEXT.replace('title = "Creep', 'title = "Cre\\u0000ep'))
    code, err = _main(capsys, "run", case, "--out", tmp_path / "r.nc", *SMALL)
    _one_line(code, err, "title")
    assert not (tmp_path / "r.nc").exists()


def test_utf8_bom_case_file_is_accepted(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_bytes(b"\xef\xbb\xbf" + CREEP_TEXT.encode())
    code, err = _main(capsys, "run", case, "--out", tmp_path / "r.nc", "--dry-run")
    assert code == 0, err


def test_prony_with_a_vanishing_long_term_modulus_is_one_line(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(CREEP_TEXT.replace(
        'type = "zener"\nshear_modulus_instantaneous = 1.93e6  # Pa, G(0)\n'
        'shear_modulus_long_term = 0.193e6     # Pa, G(inf)\nretardation_time = 0.01               # s',
        'type = "prony"\ng_inf = 1e-300\ng = [1.737e6]\ntau = [0.001]'))
    code, err = _main(capsys, "run", case, "--out", tmp_path / "r.nc", "--dry-run", "--set", "time.scheme=\"linear\"")
    _one_line(code, err, "material.g_inf")


# --- resume ----------------------------------------------------------------------------------------
@pytest.fixture
def stopped_run(tmp_path, capsys):
    """A run stopped by its checkpoint writer after step 5 (as a kill would), leaving its checkpoint."""
    case = tmp_path / "case.toml"
    case.write_text(CREEP_TEXT)
    out = tmp_path / "r.nc"
    from viscontact.running import api

    calls = []

    def stop() -> str | None:
        calls.append(1)
        return "SIGTERM" if len(calls) == 6 else None

    with pytest.raises(Exception):
        api.run(api.load_case(case).with_overrides({"grid.n": 32, "time.t_end": 0.005}),
                checkpoint=api.checkpoint_path(out), checkpoint_every=2, should_stop=stop)
    assert api.checkpoint_path(out).exists()
    return case, out


@pytest.mark.parametrize("change", ["output.fields=[\"pressure\"]", "output.every=2"])
def test_resume_refuses_changed_output_settings(stopped_run, capsys, change):
    case, out = stopped_run
    code, err = _main(capsys, "run", case, "--out", out, "--resume", *SMALL, "--set", change)
    _one_line(code, err, "--resume")
    assert "output settings" in err[0]


def test_resume_with_the_same_settings_completes(stopped_run, capsys):
    case, out = stopped_run
    code, err = _main(capsys, "run", case, "--out", out, "--resume", "--quiet", *SMALL)
    assert code == 0, err
    assert xr.open_dataset(out).attrs["complete"] == 1


@pytest.mark.parametrize("damage", ["truncated", "keyless", "garbage"])
def test_damaged_checkpoint_is_one_line(stopped_run, capsys, damage):
    case, out = stopped_run
    ckpt = Path(str(out) + ".checkpoint.npz")
    if damage == "truncated":
        ckpt.write_bytes(ckpt.read_bytes()[: ckpt.stat().st_size // 2])
    elif damage == "keyless":
        np.savez(ckpt, step=np.array(3))
    else:
        ckpt.write_bytes(b"not a checkpoint")
    code, err = _main(capsys, "run", case, "--out", out, "--resume", *SMALL)
    _one_line(code, err, "--resume")
    assert str(ckpt) in err[0]


def test_a_byte_that_is_not_utf8_in_the_command_line_is_escaped_in_history(tmp_path, capsys):
    """A file name or --set value with a byte that is not UTF-8 (Python carries it as a lone
    surrogate) is written into the result's history as \\xNN, not a UnicodeEncodeError."""
    out = tmp_path / "\udcff.nc"  # the file name b"\xff.nc"
    code, err = _main(capsys, "run", ROOT / "cases" / "creep_indentation.toml", "--out", out, *SMALL, "--quiet")
    assert code == 0, err
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert f"--out '{tmp_path}/\\xff.nc' --set" in ds.attrs["history"]


@pytest.mark.parametrize("command", ["run", "steady"])
def test_a_set_value_that_is_not_utf8_is_one_line(tmp_path, capsys, command):
    """``--set title=caf\\xe9`` from a Latin-1 terminal reached the result's title attribute and ended in
    a UnicodeEncodeError traceback from h5py; it is refused in one line before anything is written."""
    case = ROOT / "cases" / ("creep_indentation.toml" if command == "run" else "seed_table1_v0.8.toml")
    out = tmp_path / "r.nc"
    code, err = _main(capsys, command, case, "--out", out, "--set", "title=caf\udce9", "--quiet")
    assert code == 2 and len(err) == 1 and err[0].startswith("viscontact: error: --set: ") and "UTF-8" in err[0]
    assert list(tmp_path.iterdir()) == []


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="needs /dev/zero")
def test_an_endless_input_file_is_refused_before_it_fills_the_memory(capsys, tmp_path):
    """/dev/zero as the case file or the Prony table was read until the process was killed for
    memory; a large file named by mistake is refused too."""
    code, err = _main(capsys, "run", "/dev/zero", "--out", str(tmp_path / "r.nc"), "--dry-run")
    _one_line(code, err, "case file")
    assert "holds more than 16 MiB" in err[0]
    prony = CREEP_TEXT.replace('type = "zener"', 'type = "prony"\nfile = "/dev/zero"\nmodulus = "shear"')
    for key in ("shear_modulus_instantaneous", "shear_modulus_long_term", "retardation_time"):
        prony = "\n".join(line for line in prony.splitlines() if not line.startswith(key))
    (tmp_path / "c.toml").write_text(prony)
    code, err = _main(capsys, "run", str(tmp_path / "c.toml"), "--out", str(tmp_path / "r.nc"), "--dry-run")
    _one_line(code, err, "material.file")
    big = tmp_path / "big.toml"
    with open(big, "wb") as fh:
        fh.truncate(17 << 20)  # sparse: 17 MiB of zeros
    code, err = _main(capsys, "run", str(big), "--out", str(tmp_path / "r.nc"), "--dry-run")
    _one_line(code, err, "case file")


# --- issue 34: every named file through one safe reader ------------------------------------------
MALFORMED_NPY = b"\x93NUMPY\x01\x00\x20\x00{'descr': 'zzz', 'fortran_order': False, 'shape': (32, 32), }\n"


def _hostile_file(tmp_path: Path, kind: str, name: str | None = None) -> Path:
    """A file of ``kind`` in ``tmp_path``: a FIFO, a symbolic link loop, a folder, a link to /dev/zero,
    a sparse 50 GiB .npy with a valid 32 x 32 header, a sparse 8 GiB text file, a malformed .npy header."""
    path = tmp_path / (name or f"hostile_{kind}")
    if kind == "fifo":
        os.mkfifo(path)
    elif kind == "loop":
        os.symlink(tmp_path / "hostile_loop2", path)
        os.symlink(path, tmp_path / "hostile_loop2")  # path -> hostile_loop2 -> path
    elif kind == "folder":
        path.mkdir()
    elif kind == "zero":
        os.symlink("/dev/zero", path)
    elif kind == "huge_npy":
        with open(path, "wb") as fh:
            np.lib.format.write_array_header_1_0(fh, {"descr": "<f8", "fortran_order": False, "shape": (32, 32)})
            fh.truncate(50 << 30)  # sparse
    elif kind == "huge_text":
        with open(path, "wb") as fh:
            fh.truncate(8 << 30)  # sparse
    else:
        path.write_bytes(MALFORMED_NPY)
    return path


HOSTILE = ["fifo", "loop", "folder", "zero", "huge_npy", "huge_text", "malformed"]
#: what the one line must say of each (never "no such file" for a file that exists)
SAYS = {"fifo": "FIFO", "loop": "loop of symbolic links", "folder": "folder", "zero": "character device",
        "huge_npy": "GiB", "huge_text": "GiB", "malformed": "malformed"}


def _cli_in_time(*args: str | Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "viscontact", *map(str, args)], capture_output=True, text=True,
                          timeout=60, check=False)


def _refused(proc: subprocess.CompletedProcess, key: str, says: str) -> None:
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 2 and len(lines) == 1, proc.stderr[-2000:]
    assert lines[0].startswith(f"viscontact: error: {key}") and says in lines[0], lines[0]


@pytest.mark.parametrize("shape", ["surface", "topography"])
@pytest.mark.parametrize("kind", HOSTILE)
def test_a_hostile_height_file_is_one_accurate_line(tmp_path, capsys, shape, kind):
    """Issue 34 items 1, 4, 9: a malformed .npy header ended in tokenize.TokenError; a 50 GiB .npy or
    8 GiB text map was read whole; /dev/zero, a FIFO, a loop or a folder was "no such file"."""
    path = _hostile_file(tmp_path, kind)
    case = _surface_case(tmp_path, path.name)
    if shape == "topography":
        case.write_text(case.read_text().replace('shape = "surface"', 'shape = "topography"\nunit = "m"\n'
                                                 'physical_size = [4e-3, 4e-3]'))
    code, err = _main(capsys, "run", case, "--out", tmp_path / "r.nc", "--dry-run")
    _one_line(code, err, "indenter.file")
    says = {("topography", "huge_npy"): "16 MiB", ("surface", "huge_text"): "not a .npy file"}.get((shape, kind),
                                                                                                SAYS[kind])
    assert says in err[0] and "no such file" not in err[0], err[0]


@pytest.mark.parametrize("kind", ["fifo", "loop", "folder"])
def test_a_hostile_case_or_prony_file_is_one_line_without_a_hang(tmp_path, kind):
    """Issue 34 item 3: a FIFO as the case file (run, steady, sweep) or as material.file hung."""
    path = _hostile_file(tmp_path, kind)
    for command in ("run", "steady", "sweep"):
        key = "sweep file" if command == "sweep" else "case file"
        _refused(_cli_in_time(command, path, "--out", tmp_path / "r.nc", "--dry-run" if command == "run" else "--quiet"),
                 key, SAYS[kind])
    prony = (ROOT / "cases" / "pmma_master_curve.toml").read_text().replace(
        'file = "materials/pmma_schapery1962.csv"', f'file = "{path}"')
    (tmp_path / "c.toml").write_text(prony)
    _refused(_cli_in_time("run", tmp_path / "c.toml", "--out", tmp_path / "r.nc", "--dry-run"), "material.file",
             SAYS[kind])


def test_a_case_from_a_pipe_with_a_writer_is_still_read(tmp_path):
    """``viscontact run <(cat case.toml)``: a pipe that has a writer is read, as before."""
    command = f'"{sys.executable}" -m viscontact run <(cat "{ROOT}/cases/creep_indentation.toml") --out "{tmp_path}/r.nc" '
    proc = subprocess.run(["bash", "-c", command + "--dry-run"], capture_output=True, text=True, timeout=120,
                          check=False)
    assert proc.returncode == 0, proc.stderr


@pytest.mark.parametrize("kind", ["fifo", "loop", "folder", "zero"])
@pytest.mark.parametrize("beside", [".checkpoint.npz", ".lock", ""])
def test_hostile_files_beside_a_result_are_one_line(tmp_path, kind, beside):
    """Issue 34 items 3, 9: a FIFO named OUT.nc.checkpoint.npz hung every run (zipfile.is_zipfile
    opened it); a FIFO lock said "file: Invalid argument"; a FIFO result hung ``plot``."""
    out = tmp_path / "r.nc"
    _hostile_file(tmp_path, kind, out.name + beside)
    if beside:
        proc = _cli_in_time("run", ROOT / "cases" / "creep_indentation.toml", "--out", out, *SMALL, "--quiet")
    else:
        proc = _cli_in_time("plot", out, "--out", tmp_path / "figs")
    assert proc.returncode == 2 and len(proc.stderr.strip().splitlines()) == 1, proc.stderr
    assert "Invalid argument" not in proc.stderr and "no such file" not in proc.stderr, proc.stderr
    if beside == ".lock" and kind in ("fifo", "zero"):
        assert "lock file" in proc.stderr and SAYS[kind] in proc.stderr, proc.stderr
    elif beside != ".lock":  # a folder or a loop as the lock: "Is a directory", "Too many levels of symbolic links"
        assert SAYS[kind] in proc.stderr, proc.stderr


def test_a_checkpoint_linked_to_dev_zero_is_not_called_pickled(stopped_run, capsys):
    """Issue 34 item 9: it said "contains pickled (object) data"."""
    case, out = stopped_run
    ckpt = Path(str(out) + ".checkpoint.npz")
    ckpt.unlink()
    os.symlink("/dev/zero", ckpt)
    code, err = _main(capsys, "run", case, "--out", out, "--resume", *SMALL)
    _one_line(code, err, "--resume")
    assert "character device" in err[0] and "pickled" not in err[0]


@pytest.mark.parametrize("kind", ["fifo", "loop", "folder"])
def test_open_result_refuses_what_is_not_a_file(tmp_path, kind):
    from viscontact.errors import ParameterError
    from viscontact.io.netcdf import open_result

    with pytest.raises(ParameterError, match=SAYS[kind]):
        open_result(_hostile_file(tmp_path, kind))


def test_an_empty_list_of_subsurface_times_is_refused_before_the_first_step(tmp_path, capsys):
    """Issue 34 item 2: ``output.subsurface_times = []`` passed --dry-run, computed every step, then
    failed in streaming.finish (need at least one array to stack), leaving only OUT.nc.partial."""
    from viscontact.problem.problem import OutputSettings

    case = ROOT / "cases" / "creep_subsurface_stress.toml"
    for dry in (["--dry-run"], []):
        code, err = _main(capsys, "run", case, "--out", tmp_path / "e.nc", "--set", "output.subsurface_times=[]", *dry)
        _one_line(code, err, "output.subsurface_times")
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(ParameterError, match="output.subsurface_times"):
        OutputSettings(subsurface_depths=(1e-4,), subsurface_times=())


# --- issue 34 items 1 and 7: extreme values refused before anything is derived from them ----------
PMMA = ROOT / "cases" / "pmma_master_curve.toml"


@pytest.mark.parametrize("case, change, key", [
    (PMMA, "grid.half_width=1e-300", "grid.half_width"),
    (CREEP_TEXT, "grid.half_width=1e-300", "grid.half_width"),
    (PMMA, "grid.half_width=1e300", "grid.half_width"),
    (PMMA, "indenter.radius=1e300", "grid.half_width"),
    (PMMA, "normal.value=1e300", "normal.value"),
    (CREEP_TEXT, "time.t_end=1e300", "time.dt"),
    (PMMA, "tangential.sliding_speed=1e300", "time.dt"),
])
def test_extreme_values_are_one_line_before_the_estimate(tmp_path, capsys, case, change, key):
    """An OverflowError (resources.window_cells -> window_side -> next_fast_len, or the guards'
    cells per radius) came before the guards; refusals printed 300-digit record counts."""
    if isinstance(case, str):
        (tmp_path / "c.toml").write_text(case)
        case = tmp_path / "c.toml"
    code, err = _main(capsys, "run", case, "--out", tmp_path / "x.nc", "--dry-run", "--set", change)
    _one_line(code, err, key)
    assert not any(len(word) > 20 and word.isdigit() for word in err[0].split()), err[0]


def test_a_run_that_would_end_at_t_0_is_refused(tmp_path, capsys):
    """Item 7: a sliding speed of 1e-6 m/s with t_end = 0.04 s made the default step 62.5 s: the run
    "ended at t = 0 s, 100 % short" with one record and exit 0 (here: 1e-9 m/s makes PMMA's step 48.8 s)."""
    code, err = _main(capsys, "run", PMMA, "--out", tmp_path / "x.nc", "--set", "tangential.sliding_speed=1e-9",
                      "--set", "time.t_end=0.04", "--quiet")
    _one_line(code, err, "time.dt")
    assert "100 % short" in err[0] and not (tmp_path / "x.nc").exists()


def test_force_does_not_accept_a_run_of_centuries(tmp_path, capsys):
    """Item 7: ``--force`` let ``--dry-run`` accept a run estimated at 1e296 days."""
    code, err = _main(capsys, "run", ROOT / "cases" / "creep_indentation.toml", "--out", tmp_path / "x.nc",
                      "--dry-run", "--force", "--set", "time.t_end=2e5", "--set", "grid.n=4096")
    _one_line(code, err, "time.t_end")
    assert "not even --force" in err[0]


def test_a_wake_bias_that_is_most_of_the_result_stops_the_run():
    """Item 7: partial slip at 10 m/s on a 2 mm domain warned of a bias "up to about 190 %" and
    returned the result; above WAKE_REFUSAL the run stops (the steps done kept by the caller)."""
    import dataclasses

    from viscontact.errors import NumericalGuardError
    from viscontact.problem.records import StepRecord
    from viscontact.running.observers import WAKE_REFUSAL, WakeWarning

    observer = WakeWarning()
    fields = {f.name: 0.0 for f in dataclasses.fields(StepRecord) if f.name not in ("t", "wake_loss")}
    with pytest.raises(NumericalGuardError, match="mostly that bias"):
        observer.on_step(None, StepRecord(**{**fields, "t": 1.0, "wake_loss": WAKE_REFUSAL * 1.01}))


# --- issue 34 item 6: refusals in time -------------------------------------------------------------
def test_a_history_of_20000_alternating_points_is_refused_in_time():
    """``normal.history`` of 20,000 alternating points took 25.6 s to be refused (turning steps and
    the time-step estimate point by point); 1,000 points 7.9 s."""
    import time

    from viscontact.running.api import load_case, prepare

    case = load_case(ROOT / "cases" / "creep_indentation.toml").with_overrides({"grid.n": 32})
    points = [[i * 1e-4, 0.15 if i % 2 else 0.05] for i in range(20000)]
    started = time.perf_counter()
    with pytest.raises(ParameterError, match="misses the turning point of normal.history"):
        prepare(case.with_overrides({"normal.history": points}))
    assert time.perf_counter() - started < 5.0


def test_turning_steps_at_once_are_those_point_by_point():
    """The vectorised turning steps against the definition, step by step (plateaus, ties, ints)."""
    from viscontact.problem.problem import PiecewiseLinear

    rng = np.random.default_rng(3)
    for _ in range(300):
        times = tuple(np.cumsum(rng.choice([0.1, 0.25, 1.0], int(rng.integers(1, 10)))).tolist())
        history = PiecewiseLinear(times, tuple(rng.choice([0, 1, 2, -1], len(times)).tolist()))
        for dt, last in ((0.1, 1000), (0.3, 4), (1.0, 1000), (0.07, 2)):
            expected = []
            for first, held_until, _, direction in history.turning_points():
                k = int(np.ceil(first / dt - 1e-9))
                if k > last:
                    break
                if k * dt <= held_until + 1e-9 * dt:
                    expected.append((k, history(k * dt)))
                    continue
                value, k = max((direction * history(m * dt), m) for m in (k, k - 1))
                expected.append((k, direction * value))
            assert history.turning_steps(dt, last) == tuple(expected)


def test_a_million_subsurface_depths_are_refused_before_the_run(capsys, tmp_path):
    """1.2 million ``output.subsurface_depths`` were estimated at 1.5 s and the run killed at 120 s."""
    from viscontact.problem.problem import MAX_SUBSURFACE_POINTS, OutputSettings

    with pytest.raises(ParameterError, match="output.subsurface_depths"):
        OutputSettings(subsurface_depths=tuple(np.linspace(0, 1e-3, MAX_SUBSURFACE_POINTS + 1)))
    depths = "[" + ", ".join(["1e-4"] * (MAX_SUBSURFACE_POINTS + 1)) + "]"
    code, err = _main(capsys, "run", ROOT / "cases" / "creep_subsurface_stress.toml", "--out", tmp_path / "e.nc",
                      "--dry-run", "--set", f"output.subsurface_depths={depths}")
    _one_line(code, err, "output.subsurface_depths")


# --- issue 34 item 8: the API's misuse is a TypeError with a sentence -------------------------------
def test_api_misuse_is_a_sentence_not_an_attribute_error():
    import viscontact as vc
    from viscontact.io.case import Case

    case = vc.load_case(ROOT / "cases" / "creep_indentation.toml")
    problem = case.with_overrides({"grid.n": 16, "time.t_end": 5e-4}).to_problem()
    misuses = [lambda: vc.shipped_case(None), lambda: vc.write_netcdf(None, "p.nc"),
               lambda: vc.to_dataset([1, 2], problem), lambda: vc.to_dataset(None, problem),
               lambda: case.with_overrides(None), lambda: case.with_overrides([("grid.n", 16)]),
               lambda: case.with_overrides({1: 2}), lambda: Case.from_toml_text(None, ".")]
    for misuse in misuses:
        with pytest.raises(TypeError, match=r"must be .*, got "):
            misuse()


def test_a_numpy_array_override_is_taken_as_its_list():
    """``with_overrides({"normal.history": np.array(...)})`` said "must be an array, got ndarray"."""
    import viscontact as vc

    case = vc.load_case(ROOT / "cases" / "creep_indentation.toml")
    history = np.array([[0.0, 0.1], [1e-3, 0.15]])
    assert case.with_overrides({"normal.history": history}).normal.history == history.tolist()
