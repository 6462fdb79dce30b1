"""Never lose a finished run (issue 14 items 1, 2, 7): the output checked before computing, full
disks, signals during the final write, resource estimates beyond the machine.

Faults are real where the machine allows (a 1 MiB tmpfs filled during the write, a read-only mount,
``chattr +i``; these need root and are skipped otherwise) and injected otherwise (ENOSPC / EIO from
the writer). Signals are delivered to a real ``viscontact run`` subprocess while its final write is
under way (the write is slowed down by a wrapper so that the signal surely lands inside it).
"""
from __future__ import annotations

import errno
import os
import shutil
import signal
import stat
import subprocess
import sys
import textwrap
import time
import weakref
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from viscontact import cli
from viscontact.io import output_files
from viscontact.running import resources
from viscontact.io.netcdf import write_netcdf

ROOT = Path(__file__).resolve().parents[2]
CREEP = ROOT / "cases" / "creep_indentation.toml"
#: a 1-2 s run: creep indentation on 32^2 cells, 41 steps, dense displacement field recorded
SMALL = ("--set", "grid.n=32", "--set", "time.t_end=0.01", "--set", "output.fields=[\"pressure\", \"displacement_z\"]")


def _err_lines(capsys) -> list[str]:
    return [line for line in capsys.readouterr().err.splitlines() if line.strip()]


def _run(*args: str | Path) -> tuple[int, list[str]]:
    return cli.main(["run", *map(str, args)]), []


def _leftovers(folder: Path) -> list[str]:
    return [p.name for p in folder.iterdir() if ".tmp" in p.name or "probe" in p.name]


@pytest.fixture
def mount_point(tmp_path):
    """A folder under which tmpfs mounts can be made (root only); unmounted afterwards."""
    mounted: list[Path] = []

    def mount(name: str, options: str) -> Path:
        target = tmp_path / name
        target.mkdir()
        proc = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(target)], capture_output=True)
        if proc.returncode != 0:
            pytest.skip(f"cannot mount a tmpfs here: {proc.stderr.decode().strip()}")
        mounted.append(target)
        return target

    yield mount
    for target in reversed(mounted):
        subprocess.run(["umount", "-l", str(target)], capture_output=True)


# --- the output checked before computing (item 2) ------------------------------------------------
def test_path_under_a_regular_file_is_refused_before_the_run(tmp_path, capsys):
    (tmp_path / "file").write_text("x")
    for extra in ((), ("--dry-run",)):
        code = cli.main(["run", str(CREEP), "--out", str(tmp_path / "file" / "r.nc"), *extra])
        err = _err_lines(capsys)
        assert code == 2 and len(err) == 1 and "is a file, not a folder" in err[0]


def test_read_only_mount_is_refused_before_the_run(mount_point, capsys):
    folder = mount_point("ro", "size=1m,ro")
    for extra in ((), ("--dry-run",)):
        started = time.perf_counter()
        code = cli.main(["run", str(CREEP), "--out", str(folder / "r.nc"), "--quiet", *extra])
        err = _err_lines(capsys)
        assert code == 2 and len(err) == 1 and "Read-only file system" in err[0], err
        assert time.perf_counter() - started < 60  # refused up front, not after the 161-step run


def test_immutable_result_is_refused_before_the_run(tmp_path, capsys):
    out = tmp_path / "r.nc"
    xr.Dataset({"a": ("t", [1.0])}).to_netcdf(out, engine="h5netcdf")
    if subprocess.run(["chattr", "+i", str(out)], capture_output=True).returncode != 0:
        pytest.skip("chattr +i is not available here")
    try:
        code = cli.main(["run", str(CREEP), "--out", str(out), "--force", "--dry-run"])
        err = _err_lines(capsys)
        assert code == 2 and len(err) == 1 and "immutable" in err[0]
    finally:
        subprocess.run(["chattr", "-i", str(out)], capture_output=True)


def test_force_never_replaces_the_case_file(tmp_path, capsys):
    case = tmp_path / "case.toml"
    shutil.copy(CREEP, case)
    before = case.read_bytes()
    # a result must be named *.nc, so the case file is reached through a link of that name
    for out in (tmp_path / "link.nc", tmp_path / "deeper" / "link.nc"):
        out.parent.mkdir(exist_ok=True)
        out.symlink_to(case)
        code = cli.main(["run", str(case), "--out", str(out), "--force", "--quiet"])
        err = _err_lines(capsys)
        assert code == 2 and len(err) == 1 and "input file" in err[0]
        assert case.read_bytes() == before


@pytest.mark.parametrize("plots", ["the case file", "the result file"])
def test_plots_target_is_checked_before_the_run(tmp_path, capsys, plots):
    """Red team item 9: an existing file (or the result itself) as --plots failed only after the run."""
    case = tmp_path / "case.toml"
    shutil.copy(CREEP, case)
    out = tmp_path / "r.nc"
    target = case if plots == "the case file" else out
    code = cli.main(["run", str(case), "--out", str(out), "--plots", str(target), "--quiet", *SMALL])
    err = _err_lines(capsys)
    assert code == 2 and len(err) == 1 and err[0].startswith(f"viscontact: error: {target}: ") and "(--plots)" in err[0]
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == ["case.toml"]


def test_force_never_replaces_a_device_or_a_foreign_file(tmp_path, capsys):
    device = tmp_path / "null.nc"
    try:
        os.mknod(device, stat.S_IFCHR | 0o666, os.makedev(1, 3))
    except OSError:
        pytest.skip("cannot create a device node here")
    code = cli.main(["run", str(CREEP), "--out", str(device), "--force", "--quiet", *SMALL])
    assert code == 2 and "not a regular file" in _err_lines(capsys)[0]
    assert stat.S_ISCHR(os.stat(device).st_mode)
    notes = tmp_path / "notes.nc"
    notes.write_text("my notes")
    code = cli.main(["run", str(CREEP), "--out", str(notes), "--force", "--quiet", *SMALL])
    assert code == 2 and "not a netCDF result file" in _err_lines(capsys)[0]
    assert notes.read_text() == "my notes"


def test_force_through_a_symlink_replaces_its_target(tmp_path, capsys):
    target = tmp_path / "data" / "r.nc"
    target.parent.mkdir()
    xr.Dataset({"a": ("t", [1.0])}).to_netcdf(target, engine="h5netcdf")
    link = tmp_path / "r.nc"
    link.symlink_to(target)
    assert cli.main(["run", str(CREEP), "--out", str(link), "--force", "--quiet", *SMALL]) == 0
    assert link.is_symlink() and "pressure" in xr.open_dataset(target).data_vars
    assert _leftovers(tmp_path) == [] and _leftovers(target.parent) == []


# --- full disks (item 1) ---------------------------------------------------------------------------
def test_disk_filling_while_the_result_is_created_is_one_line_and_leaves_nothing(mount_point, tmp_path):
    """A real 2 MiB filesystem that passes the pre-run estimate and fills up (another program writing
    there) while the streamed result file is being created, before its space is claimed. It used to
    crash inside h5py (exit 139, a .tmp left)."""
    folder = mount_point("tiny", "size=2m")
    out = folder / "r.nc"
    proc, flag = _slow_writer(tmp_path, CREEP, "--out", out, "--quiet", *SMALL)
    _wait_for(flag, proc)
    free = shutil.disk_usage(folder).free
    (folder / "filler").write_bytes(b"\0" * (free - 16 * 1024))
    _, err = proc.communicate(timeout=120)
    errors = [line for line in err.splitlines() if line.startswith("viscontact: error")]
    assert proc.returncode == 2 and len(errors) == 1 and "Traceback" not in err, err
    assert "no space left" in errors[0] and "r.nc" in errors[0] and "needs about" in errors[0]
    assert sorted(p.name for p in folder.iterdir()) == ["filler"]


def test_disk_filling_during_a_streamed_run_cannot_take_its_claimed_space(mount_point, tmp_path):
    """Another program fills the disk while the run streams its records: the space of every record was
    claimed before the first step (viscontact.io.output_files.SpaceClaim), so the run completes."""
    folder = mount_point("claimed", "size=2m")
    out = folder / "r.nc"
    proc, flag = _slow_writer(tmp_path, CREEP, "--out", out, "--quiet", *SMALL, slow=APPEND)
    _wait_for(flag, proc)
    filler = folder / "filler"
    with open(filler, "wb", buffering=0) as fh:  # everything that is free
        try:
            while True:
                fh.write(b"\0" * 4096)
                fh.flush()
        except OSError:
            pass
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 0 and not err.strip(), err
    with xr.open_dataset(out) as ds:
        assert ds.attrs["complete"] == 1 and ds.sizes["t"] == 41
    assert sorted(p.name for p in folder.iterdir()) == ["filler", "r.nc"]


def test_forced_run_on_a_disk_too_small_stops_between_two_records(mount_point, tmp_path):
    """--force runs a result larger than the disk (refused without it): the run stops cleanly when the
    next record would not fit, one error line naming the file, what it needs and what is free, exit 2;
    the steps done stay in r.nc, readable, complete = 0 (never an HDF5 crash inside a write)."""
    folder = mount_point("small", "size=1m")
    out = folder / "r.nc"
    big = ("--set", "grid.n=64", "--set", "time.t_end=0.02",
           "--set", "output.fields=[\"pressure\", \"displacement_z\"]")
    code = subprocess.run([sys.executable, "-m", "viscontact.cli", "run", str(CREEP), "--out", str(out), *big],
                          capture_output=True, text=True)
    assert code.returncode == 2 and "result needs about" in code.stderr and "--force" in code.stderr
    proc = subprocess.run([sys.executable, "-m", "viscontact.cli", "run", str(CREEP), "--out", str(out), "--quiet",
                           "--force", *big], capture_output=True, text=True, timeout=300)
    errors = [line for line in proc.stderr.splitlines() if line.startswith("viscontact: error")]
    assert proc.returncode == 2 and len(errors) == 1 and "Traceback" not in proc.stderr, proc.stderr
    assert "no space left" in errors[0] and "r.nc" in errors[0] and "needs about" in errors[0]
    assert "free in" in errors[0] and "records done are in" in errors[0]
    with xr.open_dataset(out) as ds:
        assert ds.attrs["complete"] == 0 and ds.attrs["stopped_by"] == "ENOSPC" and 0 < ds.sizes["t"] < 81
        assert np.array_equal(ds["step"].values, np.arange(ds.sizes["t"]))
        assert np.all(np.isfinite(ds["displacement_z"].values)) and ds["load"].values[-1] > 0
    assert sorted(p.name for p in folder.iterdir()) == ["r.nc"]


def test_injected_enospc_and_eio_keep_the_previous_result(tmp_path, monkeypatch):
    out = tmp_path / "r.nc"
    old = xr.Dataset({"a": ("t", [1.0])})
    write_netcdf(old, out)
    new = xr.Dataset({"a": ("t", np.arange(1000.0))})

    def no_space(fd, offset, length):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(output_files.os, "posix_fallocate", no_space)
    with pytest.raises(OSError, match="needs about") as exc:
        write_netcdf(new, out, force=True)
    assert exc.value.errno == errno.ENOSPC and exc.value.filename == str(out)
    monkeypatch.undo()

    def io_error(fd):
        raise OSError(errno.EIO, "Input/output error")

    monkeypatch.setattr(output_files.os, "fsync", io_error)
    with pytest.raises(OSError, match="Input/output error") as exc:
        write_netcdf(new, out, force=True)
    assert exc.value.filename == str(out)
    assert xr.open_dataset(out)["a"].size == 1 and _leftovers(tmp_path) == []


def test_full_disk_at_a_checkpoint_names_the_file_the_size_and_the_remedy(tmp_path, capsys, monkeypatch):
    real = output_files.os.posix_fallocate

    def no_space_for_checkpoints(fd, offset, length):
        if ".checkpoint.npz" in os.readlink(f"/proc/self/fd/{fd}"):
            raise OSError(errno.ENOSPC, "No space left on device")
        return real(fd, offset, length)

    monkeypatch.setattr(output_files.os, "posix_fallocate", no_space_for_checkpoints)
    code = cli.main(["run", str(CREEP), "--out", str(tmp_path / "r.nc"), "--quiet", "--checkpoint-every", "5", *SMALL])
    err = _err_lines(capsys)
    assert code == 2 and len(err) == 1, err
    assert "r.nc.checkpoint.npz" in err[0] and "needs about" in err[0] and "--checkpoint-every" in err[0]
    assert _leftovers(tmp_path) == []


def test_pre_run_disk_check_counts_the_checkpoints(tmp_path, capsys, monkeypatch):
    est = resources.estimate(resources_problem := __import__("viscontact.running.api", fromlist=["prepare"]).prepare(
        __import__("viscontact.io.case", fromlist=["load_case"]).load_case(CREEP))[0])
    # the checkpoint holds the solver state only (the records are streamed to the result)
    assert 0 < est.checkpoint_bytes < est.result_bytes and resources_problem.grid.n == 128
    free = est.result_bytes + est.checkpoint_bytes  # enough for the result, not for two checkpoints beside it
    monkeypatch.setattr(shutil, "disk_usage", lambda path: shutil._ntuple_diskusage(10**12, 10**12 - free, free))
    out = str(tmp_path / "r.nc")
    assert cli.main(["run", str(CREEP), "--out", out, "--dry-run"]) == 0
    capsys.readouterr()
    code = cli.main(["run", str(CREEP), "--out", out, "--dry-run", "--checkpoint-every", "10"])
    err = _err_lines(capsys)
    assert code == 2 and len(err) == 1 and "checkpoints" in err[0] and "--force" in err[0]


def test_pre_run_disk_check_of_a_resume_counts_only_what_is_still_to_write(tmp_path, capsys, monkeypatch):
    """A run stopped by a full disk, resumed after some space was freed: the streamed file already
    holds its first records, so the check asks only for the rest (it asked for the whole result)."""
    from viscontact.io.streaming import partial_path

    problem = __import__("viscontact.running.api", fromlist=["prepare"]).prepare(
        __import__("viscontact.io.case", fromlist=["load_case"]).load_case(CREEP))[0]
    need = resources.estimate(problem).result_bytes
    free = need // 3  # a third of the result free; two thirds already streamed
    monkeypatch.setattr(shutil, "disk_usage", lambda path: shutil._ntuple_diskusage(10**12, 10**12 - free, free))
    out = tmp_path / "r.nc"
    assert cli.main(["run", str(CREEP), "--out", str(out), "--dry-run"]) == 2  # a new run does not fit
    assert "needs about" in _err_lines(capsys)[0]
    partial_path(out).write_bytes(b"\0" * (need - free + 1))
    assert cli.main(["run", str(CREEP), "--out", str(out), "--dry-run", "--resume"]) == 0


# --- resources beyond the machine (item 7) ----------------------------------------------------------
def test_memory_and_run_time_beyond_the_machine_are_refused_unless_forced(tmp_path, capsys, monkeypatch):
    out = str(tmp_path / "r.nc")
    monkeypatch.setattr(resources, "available_memory", lambda: 2**20)
    assert cli.main(["run", str(CREEP), "--out", out, "--dry-run"]) == 2
    err = _err_lines(capsys)
    assert len(err) == 1 and "memory" in err[0] and "--force" in err[0]
    assert cli.main(["run", str(CREEP), "--out", out, "--dry-run", "--force"]) == 0
    err = _err_lines(capsys)
    assert len(err) == 1 and err[0].startswith("viscontact: warning:") and "memory" in err[0]
    monkeypatch.undo()
    monkeypatch.setattr(resources, "MAX_RUN_SECONDS", 1e-3)
    assert cli.main(["run", str(CREEP), "--out", out, "--dry-run"]) == 2
    err = _err_lines(capsys)
    assert len(err) == 1 and err[0].startswith("viscontact: error: time.t_end:")


# --- signals (item 1) ------------------------------------------------------------------------------
SLOW_WRITE = textwrap.dedent("""
    import importlib, os, sys, time
    flag, where = sys.argv[1:3]
    module, owner, name = where.split(":")
    owner = getattr(importlib.import_module(module), owner)
    original = getattr(owner, name)
    def slow(self, *args, **kwargs):
        if not os.path.exists(flag):
            open(flag, "a").close()
            time.sleep(2.0)
        return original(self, *args, **kwargs)
    setattr(owner, name, slow)
    from viscontact.cli import main
    sys.exit(main(sys.argv[3:]))
""")
#: what the slow writer slows down: the creation of the streamed result file (before its layout is
#: written), its first record, or its finishing (the final write of a streamed run)
CREATE, APPEND, FINISH = ("viscontact.io.streaming:ResultStream:create", "viscontact.io.streaming:ResultStream:append",
                          "viscontact.io.streaming:ResultStream:finish")


def _slow_writer(tmp_path: Path, *args: str | Path, slow: str = CREATE) -> tuple[subprocess.Popen, Path]:
    """``viscontact run *args`` in a subprocess whose first call of ``slow`` creates the file
    ``tmp_path / "writing"`` and then sleeps 2 s."""
    flag = tmp_path / "writing"
    proc = subprocess.Popen([sys.executable, "-c", SLOW_WRITE, str(flag), slow, "run", *map(str, args)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    return proc, flag


def _wait_for(path: Path, proc: subprocess.Popen, timeout: float = 120) -> None:
    deadline = time.time() + timeout
    while not path.exists():
        if proc.poll() is not None or time.time() > deadline:
            proc.kill()
            pytest.fail(f"{path.name} never appeared: {proc.communicate()}")
        time.sleep(0.01)


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_signal_during_the_final_write_keeps_the_finished_run(tmp_path, sig, code):
    out = tmp_path / "r.nc"
    proc, flag = _slow_writer(tmp_path, CREEP, "--out", out, "--quiet", *SMALL, slow=FINISH)
    _wait_for(flag, proc)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=120)
    lines = [line for line in err.splitlines() if line.strip()]
    assert proc.returncode == code and len(lines) == 1 and "Traceback" not in err, err
    assert signal.Signals(sig).name in lines[0] and "complete" in lines[0]
    ds = xr.open_dataset(out)
    assert ds.attrs["complete"] == 1 and ds.sizes["t"] == 41
    assert _leftovers(tmp_path) == []


def test_double_sigint_still_writes_what_is_done(tmp_path):
    out = tmp_path / "r.nc"
    proc, flag = _slow_writer(tmp_path, CREEP, "--out", out, "--quiet", "--checkpoint-every", "2", "--set", "grid.n=64",
                              slow=FINISH)
    _wait_for(Path(str(out) + ".checkpoint.npz"), proc)
    proc.send_signal(signal.SIGINT)  # stop after this step: the partial result is written (slowly)
    _wait_for(flag, proc)
    proc.send_signal(signal.SIGINT)  # a second one during that write
    _, err = proc.communicate(timeout=120)
    lines = [line for line in err.splitlines() if line.strip()]
    assert proc.returncode == 130 and len(lines) == 1 and "Traceback" not in err, err
    ds = xr.open_dataset(out)
    assert ds.attrs["complete"] == 0 and 0 < ds.sizes["t"] < 161
    assert _leftovers(tmp_path) == []


SCRIPT = Path(sys.executable).with_name("viscontact")


@pytest.mark.skipif(not SCRIPT.exists(), reason="the viscontact console script is not installed")
@pytest.mark.parametrize("module", ["viscontact.plotting.base", "viscontact.io.netcdf"])
def test_sigint_at_start_up_is_one_line(tmp_path, module):
    """SIGINT while the command is still importing (the parser's figure options, then the solvers and
    xarray: about half a second): one line, status 130. The moment is the import of ``module``,
    read from ``python -X importtime`` as it happens: a fixed delay (0.3 s, 0.6 s) landed in the run
    itself on a fast machine, where the imports take under 0.6 s. (Before the interpreter runs the
    script's first line nothing of viscontact can act.)"""
    # as from a terminal: a suite started in the background (``&``, nohup) passes SIGINT on ignored,
    # and a command started with SIGINT ignored rightly ignores it
    proc = subprocess.Popen([sys.executable, "-X", "importtime", str(SCRIPT), "run", str(CREEP),
                             "--out", str(tmp_path / "r.nc")],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    for line in proc.stderr:  # one line a module, as each import completes
        if line.rstrip().endswith(f"| {module}"):
            break
    else:
        pytest.fail(f"{module} was never imported: {proc.communicate()}")
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    lines = [line for line in err.splitlines() if line.strip() and not line.startswith("import time:")]
    assert proc.returncode == 130 and len(lines) == 1 and "Traceback" not in err, err
    assert lines[0].startswith("viscontact: error:") and "interrupted" in lines[0]
    assert not (tmp_path / "r.nc").exists()


def test_an_interrupt_python_drops_is_delivered_again(tmp_path, capsys, monkeypatch):
    """SIGINT landing in a weakref callback (an import's module lock: seen in CI, the command then ran
    to the end with status 0) raises KeyboardInterrupt where Python can only print and drop it. The
    command still stops: one line, status 130, no result."""
    prepare = cli._prepare

    def interrupted_in_a_callback(args):
        class Lock:
            pass

        def callback(ref):
            raise KeyboardInterrupt

        lock = Lock()
        ref = weakref.ref(lock, callback)  # noqa: F841 (kept alive: its callback runs when lock goes)
        del lock  # the callback raises; Python drops the exception
        time.sleep(5)  # the command went on: the SIGINT sent again lands here
        return prepare(args)

    monkeypatch.setattr(cli, "_prepare", interrupted_in_a_callback)
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)  # as in the command
    try:
        started = time.perf_counter()
        code = cli.main(["run", str(CREEP), "--out", str(tmp_path / "r.nc"), "--dry-run"])
        waited = time.perf_counter() - started
    finally:
        signal.signal(signal.SIGINT, previous)
    lines = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert code == 130 and len(lines) == 1 and "interrupted" in lines[0], lines
    assert waited < 4 and not (tmp_path / "r.nc").exists()


def _interrupted_import(interrupt: BaseException) -> ImportError:
    """What an extension module's initialisation raises when SIGINT lands in it (pybind11's: scipy's
    HiGHS, seen here): ImportError('initialization failed') from the interrupt."""
    try:
        try:
            raise interrupt
        except BaseException as cause:
            raise ImportError("initialization failed") from cause
    except ImportError as exc:
        return exc


def test_sigint_inside_an_extension_modules_start_up_is_one_line(monkeypatch, capsys):
    """A sub-command's late import interrupted inside an extension module: one line and 130, as for
    any SIGINT; an ImportError of another cause is not taken for one."""
    from viscontact import cli

    def interrupted():
        raise _interrupted_import(KeyboardInterrupt())

    monkeypatch.setattr(cli, "_parser", interrupted)
    assert cli.main(["run", "case.toml"]) == 130
    assert capsys.readouterr().err == "viscontact: error: interrupted (no result file written)\n"

    def missing():
        raise ImportError("No module named 'somewhere'")

    monkeypatch.setattr(cli, "_parser", missing)
    with pytest.raises(ImportError, match="somewhere"):
        cli.main(["run", "case.toml"])


def test_sigint_inside_the_commands_own_imports_exits_130(monkeypatch):
    """The console script's start-up handler (SystemExit 130, its line already written) raised inside
    an extension module's initialisation: exit 130, not the ImportError's traceback."""
    import types

    from viscontact import _entry
    from viscontact.errors import raised_by_interrupt

    class Interrupted(types.ModuleType):
        def __getattr__(self, name):
            raise _interrupted_import(SystemExit(130))

    handler = signal.getsignal(signal.SIGINT)
    monkeypatch.setitem(sys.modules, "viscontact.cli", Interrupted("viscontact.cli"))
    try:
        with pytest.raises(SystemExit) as stop:
            _entry.main()
    finally:
        signal.signal(signal.SIGINT, handler)
    assert stop.value.code == 130
    assert not raised_by_interrupt(_interrupted_import(SystemExit(2)))
    assert not raised_by_interrupt(ImportError("initialization failed"))


def test_resume_removes_what_a_killed_write_left(tmp_path):
    """kill -9 cannot be deferred: a write killed half way leaves NAME.tmpXXXX; resuming (no other
    writer then) removes it."""
    out = tmp_path / "r.nc"
    stale = [tmp_path / "r.nc.tmpab12cd", tmp_path / "r.nc.checkpoint.npz.tmpef34gh"]
    for path in stale:
        path.write_bytes(b"half")
    other = tmp_path / "x.nc.tmp123"
    other.write_bytes(b"someone else's")
    removed = output_files.remove_temporaries(out) + output_files.remove_temporaries(str(out) + ".checkpoint.npz")
    assert sorted(removed) == sorted(stale) and other.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.nc.tmp123"]


# --- one writer per output (red team item 3), names that fit (item 12) ---------------------------
HOLD_LOCK = """
import sys, time
from viscontact.io.output_files import output_lock
with output_lock(sys.argv[1]):
    print("locked", flush=True)
    time.sleep(120)
"""


@pytest.fixture
def locked_by_another_process(tmp_path):
    """A process holding the output lock of ``tmp_path / "r.nc"``, as a run writing it does."""
    proc = subprocess.Popen([sys.executable, "-c", HOLD_LOCK, str(tmp_path / "r.nc")], stdout=subprocess.PIPE,
                            text=True, env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)})
    assert proc.stdout.readline().strip() == "locked"
    yield proc
    proc.kill()
    proc.wait()


@pytest.mark.parametrize("command", [("run",), ("run", "--force"), ("run", "--resume"), ("run", "--dry-run"),
                                     ("steady", "--force")])
def test_a_second_command_on_an_output_being_written_is_refused(tmp_path, capsys, locked_by_another_process,
                                                                command):
    """Whatever the options: one line naming the file and the process writing it, exit 2, and
    nothing of what that process writes touched (not the "interrupted run" message either: the
    run is not interrupted)."""
    out = tmp_path / "r.nc"
    out.write_bytes(b"")  # what the other process has written so far
    (tmp_path / "r.nc.partial").write_bytes(b"steps being written")
    code = cli.main([command[0], str(CREEP), "--out", str(out), *command[1:], *SMALL[:4], "--quiet"])
    err = _err_lines(capsys)
    assert code == 2 and len(err) == 1, err
    assert err[0] == (f"viscontact: error: {out}: is being written by another viscontact process "
                      f"(pid {locked_by_another_process.pid}); wait for it to end or choose another --out")
    assert out.read_bytes() == b"" and (tmp_path / "r.nc.partial").read_bytes() == b"steps being written"


def test_the_lock_is_released_and_its_file_removed_at_the_end(tmp_path, capsys):
    """A lock file left by a killed run (no process holds it) does not stop the next run; each
    run removes its lock file, and a folder it created only for it."""
    out = tmp_path / "r.nc"
    (tmp_path / "r.nc.lock").write_text("4194305\n")  # left by a run killed with -9
    assert cli.main(["run", str(CREEP), "--out", str(out), *SMALL, "--quiet"]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.nc"]
    code = cli.main(["run", str(tmp_path / "missing.toml"), "--out", str(tmp_path / "new" / "r.nc"), "--quiet"])
    assert code == 2 and not (tmp_path / "new").exists()


#: the slow writer slowing down the final rename of a streamed run (after its file is finished)
PUBLISH = "viscontact.io.streaming:ResultStream:publish"


@pytest.mark.parametrize("slow", [FINISH, PUBLISH])
def test_a_run_whose_partial_file_was_replaced_renames_nothing_and_keeps_its_own(tmp_path, slow):
    """Red team round 2, item 3: the lock file is removed under a run and another run (--force) puts
    its own r.nc.partial (and r.nc.lock) in place. The first run, at its end (before finishing its
    file, or before renaming it), renames nothing: one line, exit 1; the other run's files are left
    as they are; its own finished result is kept, as r.nc.orphan-PID.nc."""
    out = tmp_path / "r.nc"
    proc, flag = _slow_writer(tmp_path, CREEP, "--out", out, "--quiet", *SMALL, slow=slow)
    _wait_for(flag, proc)
    foreign, lock = b"\x89HDF\r\n\x1a\n: the other run's steps", b"4194305\n"
    (tmp_path / "r.nc.lock").unlink()
    (tmp_path / "r.nc.lock").write_bytes(lock)  # the other run's lock
    (tmp_path / "other").write_bytes(foreign)
    os.replace(tmp_path / "other", tmp_path / "r.nc.partial")  # as ResultStream.create does
    _, err = proc.communicate(timeout=120)
    lines = [line for line in err.splitlines() if line.strip()]
    assert proc.returncode == 1 and len(lines) == 1 and "Traceback" not in err, err
    kept = tmp_path / f"r.nc.orphan-{proc.pid}.nc"
    assert lines[0] == (f"viscontact: error: {tmp_path / 'r.nc.partial'}: another process replaced this file while "
                        "this run was writing it (its lock file was removed); nothing was renamed, this run's result "
                        f"is kept in {kept}")
    assert (tmp_path / "r.nc.partial").read_bytes() == foreign and (tmp_path / "r.nc.lock").read_bytes() == lock
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["r.nc.partial", "r.nc.lock", kept.name, "writing"])
    with xr.open_dataset(kept) as ds:
        assert ds.attrs["complete"] == 1 and ds.sizes["t"] == 41 and "problem_fingerprint" not in ds.attrs
        assert np.all(np.isfinite(ds["displacement_z"].values))


def test_output_names_too_long_for_the_files_beside_it_are_refused_before_the_run(tmp_path, capsys):
    """The checkpoint's temporary file is the longest name a run writes beside --out: a name that
    leaves no room for it is refused before any step, not at the first checkpoint."""
    limit = os.pathconf(tmp_path, "PC_NAME_MAX")
    out = tmp_path / ("e" * (limit - len(".nc.checkpoint.npz.tmpXXXXXXXX") + 1) + ".nc")
    code = cli.main(["run", str(CREEP), "--out", str(out), *SMALL, "--checkpoint-every", "5", "--quiet"])
    err = _err_lines(capsys)
    assert code == 2 and len(err) == 1 and "is too long" in err[0] and "shorter --out" in err[0], err
    assert list(tmp_path.iterdir()) == []
    fits = tmp_path / ("e" * (limit - len(".nc.checkpoint.npz.tmpXXXXXXXX")) + ".nc")
    assert cli.main(["run", str(CREEP), "--out", str(fits), *SMALL, "--checkpoint-every", "5", "--quiet"]) == 0


def test_a_long_symbolic_link_name_checkpoints_beside_its_target(tmp_path, capsys):
    """The names written beside the result are checked against its target's name, but the checkpoint
    went beside the link, under the link's name: a 235-byte link to t.nc passed the check and the run
    died at its first checkpoint (File name too long), after computing. It now goes beside the target,
    as OUT.partial and the lock do."""
    target = tmp_path / "t.nc"
    assert cli.main(["run", str(CREEP), "--out", str(target), *SMALL, "--quiet"]) == 0
    link = tmp_path / ("L" * 232 + ".nc")
    link.symlink_to(target.name)
    code = cli.main(["run", str(CREEP), "--out", str(link), *SMALL, "--checkpoint-every", "5", "--force", "--quiet"])
    assert code == 0, capsys.readouterr().err
    assert link.is_symlink() and sorted(p.name for p in tmp_path.iterdir()) == sorted([target.name, link.name])
    with xr.open_dataset(target) as ds:
        assert ds.attrs["complete"] == 1


@pytest.mark.parametrize("options", [(), ("--force",), ("--resume",), ("--dry-run",)])
def test_a_folder_named_like_the_streamed_file_is_in_the_way(tmp_path, capsys, options):
    """A folder r.nc.partial is no interrupted run's steps (the message said "--resume continues it"):
    whatever the options, one line saying it is a folder in the way, exit 2, and nothing touched."""
    out = tmp_path / "r.nc"
    folder = tmp_path / "r.nc.partial"
    folder.mkdir()
    (folder / "kept.txt").write_text("mine")
    code = cli.main(["run", str(CREEP), "--out", str(out), *options, *SMALL, "--quiet"])
    err = _err_lines(capsys)
    assert code == 2 and len(err) == 1, err
    assert err[0] == (f"viscontact: error: {folder}: is a folder in the way: a run streams its steps into this "
                      "file beside r.nc; move it away or choose another --out")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.nc.partial"]
    assert [p.name for p in folder.iterdir()] == ["kept.txt"] and (folder / "kept.txt").read_text() == "mine"


def test_run_to_file_refuses_a_folder_named_like_the_streamed_file(tmp_path):
    import viscontact as vc

    folder = tmp_path / "r.nc.partial"
    folder.mkdir()
    case = vc.load_case(CREEP).with_overrides({"grid.n": 32, "time.t_end": 0.01})
    with pytest.raises(IsADirectoryError, match="is a folder in the way"):
        vc.run_to_file(case, tmp_path / "r.nc", force=True)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.nc.partial"] and not any(folder.iterdir())
