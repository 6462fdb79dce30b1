"""Streamed results (issue 15 item 3): each record goes to the netCDF file as the run goes.

Checked against independent truth: the in-memory result of the same run (``viscontact.running``) for the
file's content, the uninterrupted run for a resumed one, and the memory an in-memory run takes for
the claim that a streamed one does not grow with the number of steps. The file after a kill -9 and
the resume from it: ``test_reliability.test_kill_9_then_resume_equals_uninterrupted``.
"""
from __future__ import annotations

import dataclasses
import tracemalloc
from pathlib import Path

import pytest
import xarray as xr

import viscontact as vc
from viscontact.running import api
from viscontact.solvers import transient
from viscontact.running import loop
from viscontact.errors import ParameterError, RunInterrupted
from viscontact.running.observers import StreamWriter
from viscontact.io import netcdf, results
from viscontact.io.results import netcdf_encoding, to_dataset
from viscontact.io.streaming import ResultStream, is_complete_result, layout_bytes, partial_path

from vc_testing import SEED_A0, SEED_RADIUS, seed_material, sphere_problem

pytestmark = pytest.mark.filterwarnings("ignore:history dropped")  # short runs, wake not the point


def _same(a: xr.Dataset, b: xr.Dataset) -> None:
    """Identical variables, coordinates and attributes but ``history`` (it holds the time of writing)."""
    xr.testing.assert_identical(a.assign_attrs(history=""), b.assign_attrs(history=""))


def _partial_slip(n: int = 16, t_end: float = 6e-3, every: int = 1):
    return sphere_problem(seed_material(), n, 1.5e-3, mode="partial_slip", friction=0.3, rate=5e-2,
                          speed=3e-3 / n / 5e-4, t_end=t_end, scheme="linear", every=every,
                          fields=("pressure", "shear_x", "stick", "displacement_z"), title="stream")


def test_streamed_file_is_the_in_memory_result(tmp_path):
    """Same variables, coordinates, values and attributes as ``to_dataset`` of the same run (the
    step count is not a multiple of ``every``: the last step is recorded too)."""
    problem = _partial_slip(every=3)
    expected = vc.run(problem)
    written = api.run_to_file(problem, tmp_path / "r.nc")
    assert written.records == expected.sizes["t"] == 5
    assert not partial_path(tmp_path / "r.nc").exists()
    with xr.open_dataset(written.path, engine="h5netcdf") as ds:
        _same(ds.load(), expected)
        assert ds.encoding["unlimited_dims"] == {"t"}
        assert ds["pressure"].encoding["chunksizes"] == (1, 16, 16) and ds["pressure"].encoding["zlib"]
        assert ds["pressure"].encoding["shuffle"] and ds["pressure"].encoding["complevel"] == 1
    assert expected.attrs["t_gross_sliding"] > 0  # the attribute computed at the end is a real one


@pytest.mark.parametrize("fields", [("pressure", "shear_x", "stick", "displacement_z"), ()])
def test_layout_is_what_xarray_writes_byte_for_byte(monkeypatch, fields):
    """The streamed file's layout, written with h5netcdf alone (a run never loads xarray), is the
    file xarray writes of ``to_dataset`` of no record with the streamed encoding: the same bytes
    (with the clock of the ``history`` attribute fixed). Booleans (``stick``), integers, scales,
    the unlimited ``t`` and the ``coordinates`` attribute are all in it."""
    class FixedClock(results.datetime):
        @classmethod
        def now(cls, tz=None):
            return cls(2026, 1, 2, 3, 4, 5, tzinfo=tz)

    monkeypatch.setattr(results, "datetime", FixedClock)
    problem = dataclasses.replace(_partial_slip(), output=vc.OutputSettings(fields=fields))
    skeleton = to_dataset([], problem, case_text="[grid]\nn = 16\n")
    skeleton.attrs["history"] += " by a test"
    by_xarray = skeleton.to_netcdf(engine="h5netcdf", unlimited_dims=("t",),
                                   encoding=netcdf_encoding(skeleton, streamed=True))
    assert layout_bytes(problem, case_text="[grid]\nn = 16\n", history="by a test") == by_xarray


def test_clean_stop_ends_the_file_with_complete_0(tmp_path):
    problem = _partial_slip()
    out = tmp_path / "r.nc"
    steps = []
    with pytest.raises(RunInterrupted) as info:
        api.run_to_file(problem, out, should_stop=lambda: "SIGTERM" if steps.append(1) or len(steps) == 4 else None)
    assert info.value.saved == (out, 4)
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert ds.sizes["t"] == 4 and ds.attrs["complete"] == 0 and ds.attrs["stopped_by"] == "SIGTERM"
        xr.testing.assert_identical(ds["pressure"].load(), vc.run(problem)["pressure"].isel(t=slice(0, 4)))


def test_stop_never_replaces_a_complete_result(tmp_path):
    """An OUT replaced under --force is kept until the new result is complete: a stopped run leaves
    its steps in OUT.partial."""
    problem = _partial_slip()
    out = tmp_path / "r.nc"
    api.run_to_file(problem, out)
    before = out.read_bytes()
    with pytest.raises(RunInterrupted) as info:
        api.run_to_file(problem, out, should_stop=lambda: "SIGINT", force=True)
    assert info.value.saved == (partial_path(out), 1)
    assert out.read_bytes() == before and is_complete_result(out)
    assert not is_complete_result(partial_path(out))


def test_reopen_drops_the_records_after_the_checkpoint_and_continues(tmp_path):
    """What --resume does with a streamed file that ran ahead of its checkpoint: truncate, append."""
    problem = _partial_slip()
    records = [rec for _, rec in transient.steps(problem)]
    path = tmp_path / "s.nc"
    stream = ResultStream.create(path, problem)
    writer = StreamWriter(problem, stream)
    for rec in records[:9]:
        writer.on_step(None, rec)
    stream.close()  # as a kill leaves it
    stream = ResultStream.reopen(path, problem, 5)
    writer = StreamWriter(problem, stream)
    for rec in records[5:]:
        writer.on_step(None, rec)
    stream.finish()
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        _same(ds.load(), to_dataset(records, problem))


def _peak_bytes(run) -> int:
    tracemalloc.start()
    try:
        run()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_memory_does_not_grow_with_the_number_of_steps(tmp_path):
    """Peak (traced) memory of a 100-step and a 20-step run: streamed, the difference is under 10 %
    of the 80 extra records; in memory (``viscontact.running``, which must hold them: 20 and 60 steps)
    it is over 80 % of its 40 extra records. The approach is held (Lee & Radok: the contact radius
    stays sqrt(R delta) while the pressure relaxes), so the solver's support windows are the same
    in both runs: under a held load the contact grows with the creep, and the cropped kernels of
    its larger windows (bounded: test_support_window) are up to 160 kB at 100 steps, what this
    limit allows for records."""
    n, dt = 32, 2.5e-4
    per_record = 3 * n * n * 8 + n * n  # pressure, shear_x, displacement_z (float64), stick (1 byte)

    def problem(steps):
        return sphere_problem(seed_material(), n, 2e-3, control="displacement", value=SEED_A0**2 / SEED_RADIUS,
                              t_end=(steps - 1) * dt, dt=dt, scheme="linear",
                              fields=("pressure", "shear_x", "stick", "displacement_z"))

    out = tmp_path / "r.nc"
    streamed = [_peak_bytes(lambda: api.run_to_file(problem(s), out.with_suffix(f".{s}.nc"))) for s in (20, 100)]
    to_dataset([], problem(20))  # what xarray loads on its first Dataset (the streamed runs never load it)
    in_memory = [_peak_bytes(lambda: vc.run(problem(s))) for s in (20, 60)]
    assert in_memory[1] - in_memory[0] > 0.8 * 40 * per_record, in_memory  # the measure sees records
    assert streamed[1] - streamed[0] < 0.1 * 80 * per_record, streamed


def test_the_steps_of_a_killed_run_are_not_overwritten_without_resume_or_force(tmp_path, capsys):
    from viscontact import cli

    case = tmp_path / "case.toml"
    case.write_text((Path(__file__).resolve().parents[2] / "cases" / "creep_indentation.toml").read_text()
                    .replace("\nn = 128", "\nn = 32").replace("t_end = 0.04", "t_end = 0.001"))
    out = tmp_path / "r.nc"
    partial_path(out).write_bytes(b"steps of a killed run")
    code = cli.main(["run", str(case), "--out", str(out), "--quiet"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "--resume" in err[0] and "r.nc.partial" in err[0]
    assert partial_path(out).read_bytes() == b"steps of a killed run" and not out.exists()
    assert cli.main(["run", str(case), "--out", str(out), "--quiet", "--force"]) == 0
    assert is_complete_result(out) and not partial_path(out).exists()


def test_streamed_subsurface_stresses_are_the_in_memory_ones(tmp_path):
    """[output] subsurface_depths: the stresses at the recorded steps nearest to subsurface_times are
    computed at the end from the fields read back from the streamed file (none held in memory)."""
    case = vc.load_case(vc.shipped_case("creep_subsurface_stress")).with_overrides(
        {"grid.n": 16, "time.t_end": 0.006, "output.subsurface_times": [0.0021, 0.006], "output.every": 2})
    expected = vc.run(case)
    written = api.run_to_file(case, tmp_path / "r.nc")
    with xr.open_dataset(written.path, engine="h5netcdf") as ds:
        _same(ds.load(), expected)
        assert ds["von_mises_stress"].dims == ("t_sub", "z", "x") and ds.sizes["t_sub"] == 2
        assert float(ds["von_mises_stress"].max()) > 0


def test_memory_estimate_counts_the_subsurface_transforms():
    """The shipped creep_subsurface_stress case at n = 64 (13 depths down to 1 mm: padding 5, padded
    transforms of 320^2): the stresses it computes at the end of the run need 22 MiB (traced peak),
    which the memory estimate adds to the run's (within 20 %; before, it added nothing: the peak
    RSS of the case at n = 128, 256, 512 was 1.7-1.8 times the estimate)."""
    from dataclasses import replace

    from viscontact.running.resources import estimate

    case = vc.load_case(vc.shipped_case("creep_subsurface_stress")).with_overrides(
        {"grid.n": 64, "time.t_end": 0.001, "output.subsurface_times": [0.0, 0.001]})
    problem, _ = api.prepare(case)
    records = list(loop.simulate(problem))
    measured = _peak_bytes(lambda: results.subsurface_variables(records, problem))
    without = replace(problem, output=replace(problem.output, subsurface_depths=()))
    added = estimate(problem).peak_memory_bytes - estimate(without).peak_memory_bytes
    assert 0.8 * measured < added < 1.2 * measured, (added, measured)


def test_the_claimed_space_bounds_what_the_file_takes(tmp_path):
    """The disk space a streamed run claims (viscontact.running.resources.stream_bytes) is an upper bound of
    what its records and its finishing really add to the file (blocks allocated on disk)."""
    from viscontact.running.resources import stream_bytes

    problem = _partial_slip(every=1)
    out = tmp_path / "r.nc"
    stream = ResultStream.create(out, problem)
    layout = out.stat().st_blocks * 512
    stream.close()
    written = api.run_to_file(problem, out, force=True)
    grown = written.path.stat().st_blocks * 512 - layout
    assert 0 < grown <= stream_bytes(problem, written.records)


def test_space_claim_holds_the_space_until_handed_back(tmp_path):
    """A real claim: the free space of the folder drops by its size, comes back piece by piece, and
    the claim leaves no file behind; a claim the disk cannot hold is one ENOSPC naming the file."""
    import errno
    import shutil

    from viscontact.io.output_files import SpaceClaim

    size = 64 * 2**20
    free = shutil.disk_usage(tmp_path).free
    claim = SpaceClaim(tmp_path / "r.nc", size, reserve=2**20)
    if claim.claimed == 0:
        pytest.skip("this filesystem makes no unnamed allocated files")
    assert free - shutil.disk_usage(tmp_path).free >= 0.9 * size
    claim.take(size)  # everything but the reserve
    assert claim.claimed == 2**20
    claim.close()
    assert abs(free - shutil.disk_usage(tmp_path).free) < 0.1 * size and list(tmp_path.iterdir()) == []
    with pytest.raises(OSError, match="needs about") as info:
        SpaceClaim(tmp_path / "r.nc", 2 * free + 2**30)
    assert info.value.errno == errno.ENOSPC and info.value.filename == str(tmp_path / "r.nc")


def test_the_partial_file_is_beside_the_target_of_a_linked_out(tmp_path):
    """--out through a symbolic link: the streamed file lies beside the file the final rename
    replaces (the link's target, maybe on another filesystem), not beside the link."""
    target = tmp_path / "data" / "r.nc"
    target.parent.mkdir()
    target.write_bytes(b"")
    link = tmp_path / "r.nc"
    link.symlink_to(target)
    assert partial_path(link) == target.with_name("r.nc.partial")
    assert partial_path(tmp_path / "new.nc") == tmp_path / "new.nc.partial"


def test_each_record_is_written_one_append_late_and_drain_writes_it(tmp_path):
    """The queued record (its fields compressing on the stream's thread) is in the file after the
    next append or drain, never before; what a checkpoint counts (drain) is what the file holds."""
    problem = _partial_slip()
    records = [rec for _, rec in transient.steps(problem)][:4]
    path = tmp_path / "s.nc"
    stream = ResultStream.create(path, problem)
    for k, rec in enumerate(records):
        stream.append(rec)
        assert stream.count == k and stream.queued is not None
        assert stream.file["t"].shape == (k,) and stream.file["pressure"].shape[0] == k
    assert stream.drain() == 4 and stream.queued is None and stream.drain() == 4
    stream.close()
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        expected = to_dataset(records, problem)
        for name in ("pressure", "shear_x", "stick", "displacement_z", "load", "step"):
            assert (ds[name].values == expected[name].values).all(), name


@pytest.mark.parametrize("shuffle", [True, False])
def test_direct_chunks_read_back_bit_for_bit_whatever_the_field(tmp_path, shuffle):
    """The chunk encoder (byte shuffle + zlib, written with HDF5's direct chunk write) against HDF5's
    own filters on the same data: smooth, all-zero, incompressible noise (stored unfiltered, the
    filters marked skipped) and int8 fields; with and without the shuffle (a file of the former
    layout, zlib alone, resumed)."""
    import h5py
    import numpy as np

    from viscontact.io.streaming import chunk_encoder

    rng = np.random.default_rng(1)
    x = np.linspace(-1, 1, 32)
    fields = [np.sqrt(np.maximum(0.5 - x[:, None] ** 2 - x ** 2, 0)) * 1e6, np.zeros((32, 32)),
              np.frombuffer(rng.bytes(32 * 32 * 8), dtype=np.uint64).reshape(32, 32),
              (rng.random((32, 32)) > 0.5).astype(np.int8)]
    with h5py.File(tmp_path / "c.h5", "w") as f:
        for i, field in enumerate(fields):
            options = dict(shape=(0, 32, 32), maxshape=(None, 32, 32), chunks=(1, 32, 32), dtype=field.dtype,
                           compression="gzip", compression_opts=1, shuffle=shuffle)
            direct, by_hdf5 = f.create_dataset(f"d{i}", **options), f.create_dataset(f"h{i}", **options)
            encode = chunk_encoder(direct)
            assert encode is not None
            direct.resize(1, axis=0), by_hdf5.resize(1, axis=0)
            mask, chunk = encode(field)
            direct.id.write_direct_chunk((0, 0, 0), chunk, mask)
            by_hdf5[0] = field
            assert (mask != 0) == (i == 2)  # only the noise does not shrink
    with h5py.File(tmp_path / "c.h5", "r") as f:
        for i, field in enumerate(fields):
            assert np.array_equal(f[f"d{i}"][0], field) and np.array_equal(f[f"d{i}"][0], f[f"h{i}"][0])


def test_no_encoder_for_chunks_or_filters_it_does_not_know(tmp_path):
    import h5py

    from viscontact.io.streaming import chunk_encoder

    with h5py.File(tmp_path / "c.h5", "w") as f:
        common = dict(shape=(0, 8, 8), maxshape=(None, 8, 8), dtype="f8")
        assert chunk_encoder(f.create_dataset("two_steps", chunks=(2, 8, 8), compression="gzip", **common)) is None
        assert chunk_encoder(f.create_dataset("lzf", chunks=(1, 8, 8), compression="lzf", **common)) is None
        assert chunk_encoder(f.create_dataset("checksum", chunks=(1, 8, 8), compression="gzip", fletcher32=True,
                                              **common)) is None
        assert chunk_encoder(f.create_dataset("plain", chunks=(1, 8, 8), **common)) is None


# --- resume: only the streamed file of the checkpointed case is continued (red team items 1, 5, 6) ---
def _small_case(tmp_path: Path, load: float = 0.15) -> Path:
    """The shipped creep case on 32^2 cells, 21 steps (under a second), at ``load`` [N]."""
    case = tmp_path / f"case_{load}.toml"
    text = (Path(__file__).resolve().parents[2] / "cases" / "creep_indentation.toml").read_text()
    case.write_text(text.replace("\nn = 128", "\nn = 32").replace("t_end = 0.04", "t_end = 0.005")
                    .replace("value = 0.15", f"value = {load}"))
    assert case.read_text() != text and f"value = {load}" in case.read_text()
    return case


def _stopped_at(case, out: Path, steps: int, *, checkpoint_every: int = 0, force: bool = False) -> None:
    """Run ``case`` into ``out`` (``force``: replacing it) and stop it cleanly (SIGINT) after ``steps`` steps."""
    done = []
    with pytest.raises(RunInterrupted):
        api.run_to_file(case, out, checkpoint_every=checkpoint_every, force=force,
                        should_stop=lambda: "SIGINT" if done.append(1) or len(done) == steps else None)


def test_resume_refuses_a_streamed_file_written_for_another_case(tmp_path):
    """Run A checkpoints and stops; run B (another load) starts over on the same out and stops: out
    is B's. A's checkpoint (put back: a fresh run removes it) must not continue B's records."""
    a, b, out = _small_case(tmp_path), _small_case(tmp_path, 0.16), tmp_path / "r.nc"
    ckpt = api.checkpoint_path(out)
    _stopped_at(a, out, 6, checkpoint_every=2)
    saved = ckpt.read_bytes()
    _stopped_at(b, out, 8, force=True)
    ckpt.write_bytes(saved)
    before = out.read_bytes()
    with pytest.raises(ParameterError, match="r.nc: was written for another case"):
        api.run_to_file(a, out, resume=True)
    assert out.read_bytes() == before and not partial_path(out).exists()  # refused, nothing touched


def test_a_fresh_run_removes_the_checkpoint_of_an_earlier_run(tmp_path):
    """--force starts over: once the new run has its own streamed file, the earlier run's checkpoint
    is gone, so a later --resume cannot pick it up."""
    case, out = _small_case(tmp_path), tmp_path / "r.nc"
    ckpt = api.checkpoint_path(out)
    _stopped_at(case, out, 6, checkpoint_every=2)
    assert ckpt.exists()
    seen = []
    _stopped_at(case, out, 3, force=True)  # no checkpointing: an earlier run's checkpoint would stay
    with pytest.raises(ParameterError, match="no checkpoint"):
        api.run_to_file(case, out, resume=True, progress=lambda k, n: seen.append(k))
    assert not ckpt.exists() and not seen


@pytest.mark.parametrize("content", ["empty", "truncated", "foreign netCDF", "complete result"])
def test_resume_from_a_bad_streamed_file_is_one_line_and_leaves_it(tmp_path, capsys, content):
    """What --resume finds in OUT.partial after a kill may be anything: one line naming it, exit 2,
    the file byte for byte as it was."""
    from viscontact import cli

    case, out = _small_case(tmp_path), tmp_path / "r.nc"
    _stopped_at(case, out, 6, checkpoint_every=2)
    partial = partial_path(out)
    if content == "empty":
        partial.write_bytes(b"")
    elif content == "truncated":
        partial.write_bytes(out.read_bytes()[:3000])
    elif content == "foreign netCDF":
        xr.Dataset({"a": ("x", [1.0, 2.0])}).to_netcdf(partial, engine="h5netcdf")
    else:
        api.run_to_file(case, tmp_path / "other.nc")
        (tmp_path / "other.nc").rename(partial)
    out.unlink()  # as a kill leaves it: the steps in OUT.partial
    before = partial.read_bytes()
    code = cli.main(["run", str(case), "--out", str(out), "--resume", "--quiet"])
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert code == 2 and len(err) == 1, err
    assert err[0].startswith(f"viscontact: error: --resume: {partial}: ") and "--force" in err[0]
    assert partial.read_bytes() == before and not out.exists()


def test_a_resumed_file_is_not_stopped_and_its_history_says_resumed(tmp_path):
    """stopped_by says why an incomplete file stopped: a resumed, complete one has none, and its
    history has one entry per command (created, resumed)."""
    case, out = _small_case(tmp_path), tmp_path / "r.nc"
    _stopped_at(case, out, 6, checkpoint_every=2)
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert ds.attrs["stopped_by"] == "SIGINT" and ds.attrs["problem_fingerprint"]
    api.run_to_file(case, out, resume=True, history="by a test resuming")
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert ds.attrs["complete"] == 1 and "stopped_by" not in ds.attrs
        assert "problem_fingerprint" not in ds.attrs  # the complete file's attributes: the in-memory result's
        assert " created by viscontact " in ds.attrs["history"]
        assert ds.attrs["history"].endswith("resumed by viscontact " + vc.__version__ + " by a test resuming")


def test_records_flushed_counts_the_whole_records_and_open_result_reads_only_those(tmp_path):
    """HDF5's flush is not atomic: a kill inside one left the raw file with the last record's extent
    but not all its values (its step read 0). records_flushed is set after each record's flush has
    returned; open_result reads the records up to it."""
    import h5py

    from viscontact.io.streaming import FLUSHED

    problem = _partial_slip()
    records = [rec for _, rec in transient.steps(problem)][:4]
    path = tmp_path / "s.nc"
    stream = ResultStream.create(path, problem)
    assert stream.file.attrs[FLUSHED] == 0
    for k, rec in enumerate(records):
        stream.append(rec)
        assert stream.file.attrs[FLUSHED] == k  # the one before is whole on disk
    stream.drain()
    assert stream.file.attrs[FLUSHED] == 4
    stream.close()
    assert netcdf.open_result(path).sizes["t"] == 4
    with h5py.File(path, "r+") as f:  # as a kill inside the fourth record's flush leaves it
        f.attrs[FLUSHED] = 3
        f["step"][3] = 0
    torn = netcdf.open_result(path)
    assert torn.sizes["t"] == 3 and list(torn["step"].values) == [0, 1, 2]


def test_run_to_file_never_replaces_a_result_without_force_nor_an_input_file(tmp_path):
    """Before, ``run_to_file`` left that check to its caller: run twice into the same file it replaced
    the finished result without a word, and given the case file's own path as ``out`` it wrote the
    result over the case file."""
    case = _small_case(tmp_path)
    out = tmp_path / "r.nc"
    api.run_to_file(case, out)
    before = out.read_bytes()
    with pytest.raises(FileExistsError, match="without --force"):
        api.run_to_file(case, out)
    assert out.read_bytes() == before and not partial_path(out).exists()
    api.run_to_file(case, out, force=True)  # replaced on request
    text = case.read_text()
    with pytest.raises(FileExistsError, match="input file"):
        api.run_to_file(case, case, force=True)
    assert case.read_text() == text


@pytest.mark.parametrize("kind", ["folder", "file"])
def test_a_checkpoint_name_taken_by_something_else_is_refused_before_the_run(tmp_path, kind):
    """OUT.checkpoint.npz as a folder failed after the streamed file was made (left behind as
    OUT.partial, 'Is a directory'); as a file that is no checkpoint it was deleted without a word
    (a fresh run removes an earlier run's checkpoint)."""
    case, out = _small_case(tmp_path), tmp_path / "r.nc"
    ckpt = api.checkpoint_path(out)
    if kind == "folder":
        ckpt.mkdir()
    else:
        ckpt.write_text("my notes")
    with pytest.raises(OSError, match="folder" if kind == "folder" else "not a viscontact checkpoint"):
        api.run_to_file(case, out, checkpoint_every=2)
    assert not out.exists() and not partial_path(out).exists()
    assert ckpt.is_dir() if kind == "folder" else ckpt.read_text() == "my notes"


def test_a_queued_record_keeps_its_claim_until_it_is_written(tmp_path):
    """Issue 34 item 5: take() gave the claim back when a record was queued, and the record was
    written only after the next step, so another program filling the disk took the space between.
    The claim is now kept until drain writes the record."""
    problem = _partial_slip()
    records = [rec for _, rec in transient.steps(problem)][:3]
    stream = ResultStream.create(tmp_path / "s.nc", problem)
    try:
        if stream.space.claimed == 0:
            pytest.skip("this filesystem makes no unnamed allocated files")
        for rec in records:
            before = stream.space.claimed
            stream.append(rec)  # the previous record written (its claim released), this one queued
            queued = stream.space.claimed
            stream.drain()
            assert stream.space.claimed < queued <= before, (before, queued, stream.space.claimed)
    finally:
        stream.close()


def test_the_free_space_in_a_full_disk_error_is_what_the_write_found(tmp_path, monkeypatch):
    """Issue 34 item 5: the "free" figure was measured after the claim was given back."""
    import shutil
    from collections import namedtuple

    from viscontact.io.output_files import SpaceClaim

    claim = SpaceClaim(tmp_path / "r.nc", 8 * 2**20, reserve=2**20)
    usage = namedtuple("usage", "total used free")
    monkeypatch.setattr(shutil, "disk_usage", lambda path: usage(10**9, 10**9, 4096))
    held = max(claim.claimed - claim.reserve, 0)
    with pytest.raises(OSError, match="4.0 KiB free|4 KiB free|4096 B") as info:
        claim.check(held + 2 * 2**20)
    assert claim.claimed == held + claim.reserve or claim.claimed == 0  # nothing given back
    assert "needs about" in str(info.value)
    claim.close()
