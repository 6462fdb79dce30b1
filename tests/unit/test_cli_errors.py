"""The command line on bad input: status 2, one line on stderr naming the key, no traceback, no file."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BASE = (ROOT / "cases" / "creep_indentation.toml").read_text()
SCRIPT = Path(sys.executable).with_name("viscontact")
COMMAND = [str(SCRIPT)] if SCRIPT.exists() else [sys.executable, "-m", "viscontact.cli"]
TINY = {"\nn = 128": "\nn = 16", "half_width = 2.0e-3": "half_width = 1.6e-3", "t_end = 0.04": "t_end = 5e-4"}


def viscontact(*args: str | Path, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([*COMMAND, *map(str, args)], cwd=cwd, capture_output=True, text=True, timeout=300, check=False)


def edited(text: str, changes: dict[str, str]) -> str:
    for old, new in changes.items():
        assert old in text, old
        text = text.replace(old, new, 1)
    return text


BAD = {
    "wrong_type": ({"\nn = 128": '\nn = "big"'}, "grid.n"),
    "unknown_key": ({"poisson_ratio = 0.3": "poison_ratio = 0.3"}, "material.poison_ratio"),
    "out_of_range": ({"poisson_ratio = 0.3": "poisson_ratio = 0.7"}, "material.poisson_ratio"),
    "not_toml": ({"[time]": "[time"}, "case file"),
    "value_and_history": ({"value = 0.15 ": "value = 0.15\nhistory = [[0.0, 0.15]] "}, "normal.value"),
    "bad_mode": ({'mode = "none"': 'mode = "spinning"'}, "tangential.mode"),
    # issue 12: bulk modulus, [layer], subsurface output
    "both_poisson_and_bulk": ({"poisson_ratio = 0.3": "poisson_ratio = 0.3\nbulk_modulus = 4e6"},
                              "material.poisson_ratio"),
    "bulk_too_small": ({"poisson_ratio = 0.3": "bulk_modulus = 1e5"}, "material.bulk_modulus"),
    "layer_thickness": ({"[time]": "[layer]\nthickness = 0.0\n\n[time]"}, "layer.thickness"),
    "layer_substrate": ({"[time]": '[layer]\nthickness = 1e-3\nsubstrate = "steel"\n\n[time]'}, "layer.substrate"),
    "layer_needs_substrate_modulus": ({"[time]": '[layer]\nthickness = 1e-3\nsubstrate = "elastic"\n\n[time]'},
                                      "layer.substrate_shear_modulus"),
    "layer_substrate_poisson_ratio": ({"[time]": '[layer]\nthickness = 1e-3\nsubstrate = "elastic"\n'
                                                 'substrate_shear_modulus = 1e9\nsubstrate_poisson_ratio = 0.6\n\n[time]'},
                                      "layer.substrate_poisson_ratio"),
    "subsurface_depth": ({"[time]": "[output]\nsubsurface_depths = [-1e-4]\n\n[time]"}, "output.subsurface_depths[0]"),
    "subsurface_with_bulk": ({"poisson_ratio = 0.3": "bulk_modulus = 4e6",
                              "[time]": "[output]\nsubsurface_depths = [1e-4]\n\n[time]"}, "output.subsurface_depths"),
    "subsurface_with_layer": ({"[time]": "[layer]\nthickness = 1e-3\n\n[output]\nsubsurface_depths = [1e-4]\n\n[time]"},
                              "output.subsurface_depths"),
}


def assert_one_line_error(proc: subprocess.CompletedProcess, key: str) -> None:
    assert proc.returncode == 2, proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith(f"viscontact: error: {key}: "), lines[0]
    assert "Traceback" not in proc.stderr + proc.stdout


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_case(tmp_path: Path, name: str) -> None:
    changes, key = BAD[name]
    (tmp_path / "case.toml").write_text(edited(BASE, changes))
    proc = viscontact("run", "case.toml", "--out", "out.nc", cwd=tmp_path)
    assert_one_line_error(proc, key)
    assert not (tmp_path / "out.nc").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["case.toml"]


def test_steady_takes_bulk_modulus(tmp_path: Path) -> None:
    """Issue 12: ``steady`` on a nu(t) case (it was refused in one line before its steady kernels)."""
    text = edited(BASE, {**TINY, "poisson_ratio = 0.3": "bulk_modulus = 4e6",
                         'mode = "none"': 'mode = "frictionless_sliding"\nsliding_speed = 0.01', "dt = 2.5e-4": ""})
    (tmp_path / "case.toml").write_text(text)
    proc = viscontact("steady", "case.toml", "--out", "out.nc", "--quiet", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["case.toml", "out.nc"]


def test_missing_case_file(tmp_path: Path) -> None:
    proc = viscontact("run", "nope.toml", "--out", "out.nc", cwd=tmp_path)
    assert_one_line_error(proc, "case file")
    assert list(tmp_path.iterdir()) == []


def test_bad_override(tmp_path: Path) -> None:
    (tmp_path / "case.toml").write_text(BASE)
    proc = viscontact("run", "case.toml", "--out", "out.nc", "--set", "grid.n=2", cwd=tmp_path)
    assert_one_line_error(proc, "grid.n")
    assert not (tmp_path / "out.nc").exists()


def test_existing_result_is_kept(tmp_path: Path) -> None:
    (tmp_path / "case.toml").write_text(BASE)
    (tmp_path / "out.nc").write_text("precious")
    proc = viscontact("run", "case.toml", "--out", "out.nc", cwd=tmp_path)
    assert_one_line_error(proc, "out.nc")
    assert "--force" in proc.stderr
    assert (tmp_path / "out.nc").read_text() == "precious"


def test_plot_missing_result(tmp_path: Path) -> None:
    proc = viscontact("plot", "nope.nc", "--out", "figs", cwd=tmp_path)
    assert_one_line_error(proc, "nope.nc")
    assert not (tmp_path / "figs").exists()


def test_tiny_run_and_plot(tmp_path: Path) -> None:
    """End to end on a 16 x 16 grid, 3 steps: the contract commands succeed."""
    (tmp_path / "case.toml").write_text(edited(BASE, TINY))
    proc = viscontact("run", "case.toml", "--out", "out.nc", "--quiet", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == "" and "Traceback" not in proc.stderr
    proc = viscontact("plot", "out.nc", "--out", "figs", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "figs" / "pressure_profiles.png").exists()
    import xarray as xr

    with xr.open_dataset(tmp_path / "out.nc", engine="h5netcdf") as ds:
        assert ds.sizes["t"] == 3 and ds.attrs["complete"] == 1


def test_version() -> None:
    from viscontact import __version__

    proc = subprocess.run([*COMMAND, "--version"], capture_output=True, text=True, timeout=60, check=False)
    assert proc.returncode == 0 and __version__ in proc.stdout


def test_python_dash_m_is_the_command(tmp_path: Path) -> None:
    """``python -m viscontact`` (no console script on the PATH) runs the same command, errors included."""
    from viscontact import __version__

    proc = subprocess.run([sys.executable, "-m", "viscontact", "--version"], capture_output=True, text=True,
                          timeout=60, check=False)
    assert proc.returncode == 0 and __version__ in proc.stdout
    proc = subprocess.run([sys.executable, "-m", "viscontact", "run", "missing.toml", "--out", "r.nc"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=60, check=False)
    assert_one_line_error(proc, "case file")


@pytest.mark.parametrize("command", ["steady", "plot"])
@pytest.mark.parametrize(("values", "said"), [("0.01,0.02,1e-2", "0.01 {unit} is listed more than once"),
                                              ("", "must list at least one number in {unit}")])
def test_a_speed_or_time_listed_twice_or_none_is_refused(tmp_path: Path, command: str, values: str, said: str) -> None:
    """``steady --speeds 0.01,0.01`` wrote a result whose speed coordinate repeated a value;
    ``steady --speeds ""`` solved the one state at the case's speed as if no --speeds was given."""
    option, unit = ("--speeds", "m/s") if command == "steady" else ("--times", "s")
    proc = viscontact(command, "case.toml" if command == "steady" else "r.nc", "--out", "r.nc" if command == "steady"
                      else "figs", option, values, cwd=tmp_path)
    assert_one_line_error(proc, option)
    assert said.format(unit=unit) in proc.stderr


def test_plot_refuses_a_file_that_is_not_a_result(tmp_path: Path) -> None:
    (tmp_path / "notes.nc").write_text("not a netCDF file")
    proc = viscontact("plot", "notes.nc", "--out", "figs", cwd=tmp_path)
    assert_one_line_error(proc, "notes.nc")
    assert "not a viscontact result file" in proc.stderr and "HDF5" not in proc.stderr
    assert not (tmp_path / "figs").exists()


@pytest.mark.parametrize("out", ["out.txt", "out", "out.nc.bak"])
def test_out_must_be_a_netcdf_file(tmp_path: Path, out: str) -> None:
    (tmp_path / "case.toml").write_text(edited(BASE, TINY))
    for command, source in (("run", "case.toml"), ("steady", "case.toml"), ("sweep", "sweep.toml")):
        proc = viscontact(command, source, "--out", out, cwd=tmp_path)
        assert_one_line_error(proc, "--out")
        assert ".nc" in proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["case.toml"]


# --- messages: --quiet silences warnings, --log-level chooses what else is shown ---------------------------
# the seed's constant scheme at dt = 1 ms misses the creep by about 19 %: a ViscontactWarning from the
# time-step guard (warned, not refused: the refusal starts at 20 %)
COARSE = {**TINY, "t_end = 5e-4": "t_end = 4e-3", "dt = 2.5e-4": 'dt = 1e-3\nscheme = "constant"'}


def _run_in_process(tmp_path: Path, capsys, *options: str) -> tuple[str, str]:
    from viscontact import cli

    case = tmp_path / "case.toml"
    case.write_text(edited(BASE, COARSE))
    out = tmp_path / "out.nc"
    assert cli.main(["run", str(case), "--out", str(out), "--force", *options]) == 0
    captured = capsys.readouterr()
    return captured.out, captured.err


def test_warning_shown_by_default_and_silenced_by_quiet(tmp_path: Path, capsys) -> None:
    _, err = _run_in_process(tmp_path, capsys)
    assert "viscontact: warning: time.dt = 0.001 s" in err
    out, err = _run_in_process(tmp_path, capsys, "--quiet")
    assert out == "" and err == ""
    _, err = _run_in_process(tmp_path, capsys, "--log-level", "error")
    assert "warning" not in err


def test_log_level_debug_shows_more(tmp_path: Path, capsys) -> None:
    _, err = _run_in_process(tmp_path, capsys, "--log-level", "DEBUG")
    lines = err.splitlines()
    assert any(line.startswith("viscontact: debug: viscontact ") and " run " in line for line in lines), err
    assert any(line.startswith("viscontact: warning: time.dt") for line in lines), err


def test_history_names_the_command(tmp_path: Path, capsys) -> None:
    import xarray as xr

    _run_in_process(tmp_path, capsys, "--quiet")
    with xr.open_dataset(tmp_path / "out.nc", engine="h5netcdf") as ds:
        assert "created by viscontact" in ds.attrs["history"]
        assert ds.attrs["history"].endswith(f"by the command: viscontact run {tmp_path / 'case.toml'} --out "
                                            f"{tmp_path / 'out.nc'} --force --quiet")


PERIODIC_SLIP = """
[material]
type = "elastic"
shear_modulus = 1e6
poisson_ratio = 0.5
[indenter]
shape = "surface"
file = "gap.npy"
[grid]
n = 16
half_width = 0.5e-3
periodic = true
[normal]
control = "load"
history = [[0.0, 0.005], [0.003125, 0.005], [0.0046875, 0.04]]  # N; full contact from about 0.0126 N
[tangential]
mode = "partial_slip"
friction_coefficient = 0.3
displacement_rate = 1e-6
sliding_speed = 1e-2
steps_per_cell = 4
[time]
t_end = 0.0125
"""


def test_partial_slip_reaching_full_periodic_contact_is_one_line(tmp_path: Path, capsys) -> None:
    """A uniform shear is in the null space of the periodic tangential operator: refused at the step
    whose contact covers the period, in one line naming the remedies, with the steps done kept."""
    import numpy as np
    import xarray as xr

    from viscontact import cli

    x = -0.5e-3 + (np.arange(16) + 0.5) * 1e-3 / 16
    np.save(tmp_path / "gap.npy", np.tile(1e-6 * (1 - np.cos(2 * np.pi / 1e-3 * x)), (16, 1)))
    (tmp_path / "case.toml").write_text(PERIODIC_SLIP)
    out = tmp_path / "out.nc"
    assert cli.main(["run", str(tmp_path / "case.toml"), "--out", str(out), "--quiet"]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1, lines
    assert lines[0].startswith("viscontact: error: tangential.mode: partial slip with the contact covering the "
                               "whole period (t = 0.0046875 s)"), lines[0]
    assert "gross_sliding" in lines[0] and "grid.periodic = false" in lines[0]
    assert lines[0].endswith(f"(the 3 records done are in {out}, complete = 0)"), lines[0]
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert ds.attrs["complete"] == 0 and ds.sizes["t"] == 3 and float(ds["contact_fraction"][-1]) < 1


def test_fretting_beyond_gross_slip_stops_in_one_line(tmp_path: Path, capsys) -> None:
    """A displacement history whose amplitude exceeds gross slip (the shipped fretting case at 32^2,
    delta_x to 40 um: gross slip at 12.5 um with G(0)) stops at the step whose stick zone vanished,
    in one line naming the key, the time and the remedy, status 2, the steps done kept (complete = 0);
    the indenter never slid."""
    import xarray as xr

    from viscontact import cli

    text = edited((ROOT / "cases" / "fretting_zener.toml").read_text(),
                  {"n = 64": "n = 32", "[0.0025, 8e-6]": "[0.0025, 40e-6]"})
    (tmp_path / "case.toml").write_text(text)
    out = tmp_path / "out.nc"
    assert cli.main(["run", str(tmp_path / "case.toml"), "--out", str(out), "--quiet"]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1, lines
    assert lines[0].startswith("viscontact: error: tangential.displacement_history: the stick zone vanished at t = "), \
        lines[0]
    assert "exceeds gross slip" in lines[0] and "tangential.displacement_rate" in lines[0]
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        done = ds.sizes["t"]
        assert ds.attrs["complete"] == 0 and 2 <= done < 11 and (ds["phase"].values == 1).all()
        assert lines[0].endswith(f"(the {done} records done are in {out}, complete = 0)"), lines[0]
        assert float(ds["delta_x"][-1]) < 40e-6 and float(ds["sliding_distance"][-1]) == 0


@pytest.mark.parametrize("speeds", [(), ("--speeds", "0.01,0.1")])
def test_steady_of_a_fretting_case_is_refused_in_one_line(tmp_path: Path, capsys, speeds) -> None:
    """A displacement history never slides, so a fretting case has no steady sliding state: steady
    (one speed given with --set, or --speeds) refuses it in one line keyed
    tangential.displacement_history, status 2, no file - before, it wrote the steady state of gross
    sliding at the speed given, which the case never reaches; a steady sweep of such runs is refused
    before any run (check_run)."""
    from viscontact import cli
    from viscontact.io.case import load_case
    from viscontact.errors import ParameterError
    from viscontact.sweep.spec import check_run

    (tmp_path / "case.toml").write_text(edited((ROOT / "cases" / "fretting_zener.toml").read_text(),
                                               {"n = 64": "n = 16"}))
    out = tmp_path / "out.nc"
    args = ["steady", str(tmp_path / "case.toml"), "--out", str(out), *speeds]
    assert cli.main([*args, *(() if speeds else ("--set", "tangential.sliding_speed=0.01"))]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("viscontact: error: tangential.displacement_history: a "
                                                   "displacement history (fretting) never slides"), lines
    assert not out.exists()
    with pytest.raises(ParameterError, match="^tangential.displacement_history: .*no steady sliding state"):
        check_run(load_case(tmp_path / "case.toml").with_overrides({"tangential.sliding_speed": 0.01}), "steady")


# --- argparse's own errors: one line naming the option, status 2 (argparse printed its usage block first) --
OPTION_ERRORS = {
    "missing_out": (["run", "case.toml"], "--out", "required"),
    "format": (["run", "case.toml", "--out", "out.nc", "--format", "jpg"], "--format", "'png'"),
    "figure": (["reproduce", "fig5", "--out", "figs"], "figure", "'fig4'"),
    "checkpoint_every": (["run", "case.toml", "--out", "out.nc", "--checkpoint-every", "x"], "--checkpoint-every",
                         "int"),
    "log_level": (["run", "case.toml", "--out", "out.nc", "--log-level", "verbose"], "--log-level", "'debug'"),
    "unknown_option": (["run", "case.toml", "--out", "out.nc", "--sets", "grid.n=64"], "unrecognized arguments",
                       "--sets grid.n=64"),
    "no_command": ([], "COMMAND", "required"),
}


@pytest.mark.parametrize("name", sorted(OPTION_ERRORS))
def test_option_errors_are_one_line(tmp_path: Path, name: str) -> None:
    args, key, allowed = OPTION_ERRORS[name]
    (tmp_path / "case.toml").write_text(BASE)
    proc = viscontact(*args, cwd=tmp_path)
    assert_one_line_error(proc, key)
    assert allowed in proc.stderr and "--help" in proc.stderr and "usage:" not in proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["case.toml"]


def test_option_errors_in_process_return_2(capsys) -> None:
    """``cli.main`` returns the status of an option error like any other (argparse raised SystemExit)."""
    from viscontact import cli

    assert cli.main(["plot", "r.nc", "--out", "figs", "--format", "gif"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("viscontact: error: --format: invalid choice: 'gif'"), err


@pytest.mark.parametrize("command", ["plot", "material"])
def test_a_figure_folder_that_is_a_file_is_refused_before_any_work(tmp_path: Path, command: str) -> None:
    """``plot R.nc --out FILE`` said only ``FILE: File exists``; ``material CASE --plots FILE`` printed
    the material and then that line. Both now say what is wanted, as ``run --plots FILE`` does, before
    anything is read or printed."""
    (tmp_path / "figs").write_text("a file in the way")
    case = Path(__file__).resolve().parents[2] / "cases" / "creep_indentation.toml"
    args = ("plot", "r.nc", "--out") if command == "plot" else ("material", case, "--plots")
    proc = viscontact(*args, "figs", cwd=tmp_path)
    assert_one_line_error(proc, "figs")
    option = "--out" if command == "plot" else "--plots"
    assert f"give a folder for the figures ({option})" in proc.stderr and not proc.stdout
    assert (tmp_path / "figs").read_text() == "a file in the way"
