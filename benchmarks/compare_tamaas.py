"""Creep indentation in viscontact and in a Tamaas-based stepper: wall, CPU and memory, alternated.

    .venv/bin/python benchmarks/compare_tamaas.py --tamaas-python /work/tamaas-venv/bin/python
    .venv/bin/python benchmarks/compare_tamaas.py --n 128 --steps 51 --repeats 1      # quick look

The case (the seed's creep test): Zener half-space G(0) = 1.93 MPa, G(inf) = 0.193 MPa, retardation
time 10 ms, nu = 0.3; rigid sphere R = 10 mm pressed with W = 0.15 N from t = 0 and held; square
domain +-1.5 mm with n x n cells (default 256); 201 steps of 0.2 ms (piecewise-constant tractions,
the seed's scheme). Lee & Radok (1960): with the load held, a(t)^3 = 3 W R (1 - nu) J(t) / 8 and
delta(t)^(3/2) = a(t)^3 / R^(3/2), both proportional to the creep compliance J(t).

Contestants, each in its own subprocess (so that its peak memory is its own):

``viscontact``
    ``viscontact.run_to_file`` (what ``viscontact run`` does) on a :class:`viscontact.Problem` built
    with the public API, default output (pressure, shear and stick fields of every step) streamed to
    a result file in a temporary folder: its memory does not depend on the number of steps. The
    series and the last pressure are read back from that file with h5py after the run.
``tamaas``
    Tamaas's elastic Polonsky-Keer solver (``PolonskyKeerRey``) with its non-periodic DC-FFT
    operator (``ModelFactory.registerNonPeriodic``), driven by the exact hereditary recursion of a
    Prony creep compliance J(t) = J_inf - sum_m J_m exp(-t/lambda_m): each step is an elastic
    contact with the instantaneous compliance J_inst and the known displacement of the history
    traction r_k = sum_m J_m (p_{k-1} - A_m S_m,k-1) (S_m,k = A_m S_m,k-1 + p_k - p_{k-1},
    A_m = exp(-dt/lambda_m)) subtracted from the indenter surface.
``maxwell``
    Tamaas's own viscoelastic solver ``MaxwellViscoelastic`` (generalised Maxwell model, backward
    Euler), with the Zener material as a long-term modulus E(inf) plus one Maxwell branch of shear
    modulus G(0) - G(inf) and relaxation time lambda G(inf)/G(0). Shown against Lee-Radok, not timed
    against the others (it does not solve the same problem: its contact area does not creep).

The contestants alternate (viscontact, tamaas, viscontact, tamaas, ...) so that a change in the load
of a shared machine hits both; the table gives the median of each. Wall time is the subprocess's
(imports included) and the solve's alone; CPU time (user + sys) comes from ``os.wait4`` (the kernel's
rusage of that child), peak resident memory from the child's own VmHWM (its ``ru_maxrss`` would
include the parent's size, which Linux carries over through fork and exec).

The Tamaas environment
----------------------
Tamaas (AGPL-3.0, a compiled wheel with its own FFTW) runs in a virtual environment of its own,
never in viscontact's: its half of this script imports only numpy and tamaas. Create it once with

    python3 -m venv /work/tamaas-venv && /work/tamaas-venv/bin/pip install tamaas numpy scipy

and pass its interpreter with ``--tamaas-python`` or the environment variable
``VISCONTACT_TAMAAS_PYTHON``.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

# -- the case -------------------------------------------------------------------------------------
SHEAR_MODULUS_INSTANTANEOUS = 1.93e6  # Pa, G(0)
SHEAR_MODULUS_LONG_TERM = 0.193e6     # Pa, G(inf)
RETARDATION_TIME = 0.01               # s
POISSON_RATIO = 0.3
RADIUS = 0.01                         # m
LOAD = 0.15                           # N
HALF_WIDTH = 1.5e-3                   # m
DT = 2e-4                             # s
TAMAAS_ENV = "VISCONTACT_TAMAAS_PYTHON"
VISCONTACT_TOLERANCE = 1e-8  # relative change of the pressure per CG iteration (viscontact's default)
TAMAAS_TOLERANCE = 1e-10     # Tamaas's own error measure; see BENCHMARKS.md for the choice
#: times [s] of the Lee-Radok table (must be multiples of DT within the run)
TABLE_TIMES = (0.0, 0.002, 0.005, 0.01, 0.02, 0.04)


def creep_compliance(t: np.ndarray | float) -> np.ndarray:
    """Zener creep compliance J(t) [1/Pa] in shear (Lee-Radok's J)."""
    j0, jinf = 1.0 / SHEAR_MODULUS_INSTANTANEOUS, 1.0 / SHEAR_MODULUS_LONG_TERM
    return jinf - (jinf - j0) * np.exp(-np.asarray(t, dtype=float) / RETARDATION_TIME)


def cell_centres(n: int) -> tuple[np.ndarray, np.ndarray]:
    """(X, Y) [m] of the n x n cell centres on [-HALF_WIDTH, HALF_WIDTH]^2, indexed [y, x]."""
    dx = 2 * HALF_WIDTH / n
    x = -HALF_WIDTH + (np.arange(n) + 0.5) * dx
    return np.meshgrid(x, x, indexing="xy")


def peak_rss_mib() -> float:
    """This process's own peak resident memory [MiB]: VmHWM of /proc/self/status (Linux), which
    belongs to the process image; ``ru_maxrss`` is not used because Linux carries it over from the
    parent through fork and exec (a child would report at least its parent's size)."""
    try:
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    import resource
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def _cpu() -> float:
    t = os.times()
    return t.user + t.system


# -- the halves (each runs in its own process) -----------------------------------------------------
def half_viscontact(n: int, steps: int, tolerance: float) -> dict:
    """viscontact through its public API; returns the scalar series and the final pressure."""
    import warnings

    import viscontact as vc

    grid = vc.Grid(n, HALF_WIDTH)
    x, y = grid.mesh()
    problem = vc.Problem(
        material=vc.Material.zener(SHEAR_MODULUS_INSTANTANEOUS, SHEAR_MODULUS_LONG_TERM, RETARDATION_TIME,
                                   POISSON_RATIO),
        grid=grid, gap=(x**2 + y**2) / (2 * RADIUS),
        normal=vc.NormalLoading("load", vc.PiecewiseLinear.constant(LOAD)),
        tangential=vc.TangentialLoading(), time=vc.TimeStepping((steps - 1) * DT, DT, scheme="constant"),
        output=vc.OutputSettings(), solver=vc.SolverSettings(tolerance=tolerance), radius=RADIUS)
    with tempfile.TemporaryDirectory() as folder:
        wall, cpu = time.perf_counter(), _cpu()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            written = vc.run_to_file(problem, Path(folder) / "creep.nc")
        wall, cpu = time.perf_counter() - wall, _cpu() - cpu
        import h5py  # loaded by the run already; xarray is not

        with h5py.File(written.path, "r") as result:
            series = {key: result[name][:].tolist() for key, name in
                      (("t", "t"), ("delta", "delta_z"), ("area", "contact_area"), ("iterations", "iterations"))}
            pressure = result["pressure"][-1]
    return {"solve_wall": wall, "solve_cpu": cpu, **series, "pressure": pressure}


def _tamaas_model(n: int, shear_modulus: float):
    """A Tamaas basic_2d model of the domain with the non-periodic (DC-FFT) operator registered.
    Tamaas logs at level info: its solvers print their first and last iteration (read back by
    :func:`_tamaas_iterations`)."""
    import tamaas as tm

    tm.set_log_level(tm.LogLevel.info)
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [2 * HALF_WIDTH] * 2, [n, n])
    model.E = 2 * (1 + POISSON_RATIO) * shear_modulus
    model.nu = POISSON_RATIO
    tm.ModelFactory.registerNonPeriodic(model, "dcfft")
    return tm, model


def half_tamaas(n: int, steps: int, tolerance: float) -> dict:
    """Tamaas's elastic Polonsky-Keer solver driven by the exact hereditary recursion (see module doc)."""
    j0, jinf = 1.0 / SHEAR_MODULUS_INSTANTANEOUS, 1.0 / SHEAR_MODULUS_LONG_TERM
    amplitudes, times = np.array([jinf - j0]), np.array([RETARDATION_TIME])
    decay = np.exp(-DT / times)
    j_inst = jinf - amplitudes.sum()  # piecewise-constant tractions: every increment acts as a step
    tm, model = _tamaas_model(n, 1.0 / j_inst)
    operator = model.operators["dcfft"]
    x, y = cell_centres(n)
    sphere = -(x**2 + y**2) / (2 * RADIUS)  # Tamaas: surface height, u positive into the solid
    surface = sphere.copy()                  # the solver keeps a view: updated in place each step
    solver = tm.PolonskyKeerRey(model, surface, tolerance)
    solver.setIntegralOperator("dcfft")
    solver.max_iter = 10000
    solver.dump_freq = 10**9  # log only the first and the last iteration of each solve
    dA = (2 * HALF_WIDTH / n) ** 2
    mean_pressure = LOAD / (2 * HALF_WIDTH) ** 2
    internal = np.zeros((amplitudes.size, n, n))  # S_m: exponentially weighted sums of increments
    previous = np.zeros((n, n))
    u_history, u_elastic = np.zeros((n, n)), np.zeros((n, n))
    out: dict = {"t": [], "delta": [], "area": []}
    diagnostics = 0.0
    wall, cpu = time.perf_counter(), _cpu()
    for k in range(steps):
        # r_k = sum_m J_m (p_{k-1} - A_m S_m,k-1); its displacement IC * r_k is J_inst^-1 (K r_k)
        history_traction = amplitudes.sum() * previous - np.tensordot(amplitudes * decay, internal, axes=1)
        operator(history_traction, u_history)
        u_history /= j_inst
        np.subtract(sphere, u_history, out=surface)
        solver.solve(mean_pressure)
        p = np.array(model.traction, copy=True)
        internal *= decay[:, None, None]
        internal += p - previous
        previous = p
        # diagnostics (not timed): approach = total displacement minus the sphere over the contact
        t0 = time.perf_counter()
        contact = p > 0
        operator(p, u_elastic)
        out["t"].append(k * DT)
        out["area"].append(float(contact.sum() * dA))
        out["delta"].append(float(np.mean((u_elastic + u_history - sphere)[contact])))
        diagnostics += time.perf_counter() - t0
    wall, cpu = time.perf_counter() - wall - diagnostics, _cpu() - cpu - diagnostics
    out.update(solve_wall=wall, solve_cpu=cpu, pressure=previous)
    return out


def half_maxwell(n: int, steps: int, tolerance: float) -> dict:
    """Tamaas's ``MaxwellViscoelastic`` on the same case: the Zener material as a generalised Maxwell
    model (long-term modulus plus one branch of shear modulus G(0) - G(inf) relaxing in
    lambda G(inf)/G(0), the relaxation time of the same standard linear solid)."""
    g0, ginf = SHEAR_MODULUS_INSTANTANEOUS, SHEAR_MODULUS_LONG_TERM
    tm, model = _tamaas_model(n, ginf)
    x, y = cell_centres(n)
    surface = -(x**2 + y**2) / (2 * RADIUS)
    solver = tm.MaxwellViscoelastic(model, surface, tolerance, DT, [g0 - ginf], [RETARDATION_TIME * ginf / g0])
    solver.setIntegralOperator("dcfft")
    solver.max_iter = 10000
    solver.dump_freq = 10**9
    dA = (2 * HALF_WIDTH / n) ** 2
    out: dict = {"t": [], "delta": [], "area": []}
    wall, cpu = time.perf_counter(), _cpu()
    for k in range(steps):
        solver.solve(LOAD / (2 * HALF_WIDTH) ** 2)  # updates the branch states (solve_should_update)
        p = np.asarray(model.traction)
        out["t"].append(k * DT)
        out["area"].append(float((p > 0).sum() * dA))
        out["delta"].append(float(np.asarray(model.displacement).max()))  # its displacement at the centre
    out.update(solve_wall=time.perf_counter() - wall, solve_cpu=_cpu() - cpu, pressure=np.array(p, copy=True))
    return out


def _tamaas_iterations(log: str) -> list[int]:
    """Iterations of each solve from Tamaas's log: each solve prints a header line "Iter ..." then
    the lines "0 cost error" and "N cost error"; N is that solve's iteration count."""
    counts: list[int] = []
    for line in log.splitlines():
        parts = line.split()
        if parts and parts[0] == "Iter":
            counts.append(0)
        elif counts and len(parts) == 3 and parts[0].isdigit():
            counts[-1] = int(parts[0])
    return counts


HALVES = {"viscontact": half_viscontact, "tamaas": half_tamaas, "maxwell": half_maxwell}


# -- the driver ------------------------------------------------------------------------------------
def tamaas_python(given: str | None) -> str:
    """The interpreter of the Tamaas environment, or exit 2 with how to create it."""
    path = given or os.environ.get(TAMAAS_ENV)
    hint = ("create it with `python3 -m venv /work/tamaas-venv && /work/tamaas-venv/bin/pip install tamaas numpy "
            f"scipy` and pass --tamaas-python /work/tamaas-venv/bin/python (or set {TAMAAS_ENV})")
    if not path:
        _refuse(f"no Tamaas environment given; {hint}")
    try:
        usable = subprocess.run([path, "-c", "import tamaas, numpy"], capture_output=True).returncode == 0
    except OSError:
        usable = False
    if not usable:
        _refuse(f"{path} cannot import tamaas and numpy; {hint}")
    return path


def _refuse(message: str) -> None:
    """Bad input: one line, exit status 2."""
    print(f"compare_tamaas: {message}", file=sys.stderr)
    sys.exit(2)


def run_half(python: str, half: str, args: argparse.Namespace, workdir: Path) -> dict:
    """Run one half in a subprocess; its own timings plus the kernel's rusage of that child."""
    result = workdir / f"{half}.npz"
    cmd = [python, __file__, "--half", half, "--n", str(args.n), "--steps", str(args.steps),
           "--tamaas-tolerance", str(args.tamaas_tolerance), "--result", str(result)]
    out = run_child(cmd, result, f"compare_tamaas: the {half} half")
    out["rss_mib"] = float(out["own_rss_mib"])
    return out


def run_child(cmd: list[str], result: Path, what: str, env: dict | None = None) -> dict:
    """Run ``cmd`` (which writes the npz ``result``) and return its arrays plus the child's wall,
    CPU (user + sys), sys time and minor page faults from ``os.wait4``; exit with ``what`` failed."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, env=env)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"{what} failed (exit {os.waitstatus_to_exitcode(status)})")
    with np.load(result) as data:
        out = {k: data[k] for k in data.files}
    out.update(wall=wall, cpu=usage.ru_utime + usage.ru_stime, sys=usage.ru_stime, faults=usage.ru_minflt)
    return out


def _row(name: str, runs: list[dict], steps: int) -> list[str]:
    med = {k: float(np.median([r[k] for r in runs])) for k in ("wall", "solve_wall", "cpu", "sys", "rss_mib")}
    its = np.asarray(runs[-1]["iterations"], dtype=float)
    return [name, f"{med['wall']:.1f}", f"{med['solve_wall']:.1f}", f"{1e3 * med['solve_wall'] / steps:.0f}",
            f"{med['cpu']:.1f}", f"{med['sys']:.1f}", f"{med['rss_mib']:.0f}",
            f"{its.mean():.1f} (first {its[0]:.0f}, max {its.max():.0f})" if its.size else "-"]


def lee_radok_table(results: dict[str, dict]) -> list[list[str]]:
    """a(t)^3 and delta(t)^(3/2) relative to Hertz with G(0), against J(t)/J(0) (Lee-Radok)."""
    e_star = 2 * SHEAR_MODULUS_INSTANTANEOUS / (1 - POISSON_RATIO)
    a0_cubed = 3 * LOAD * RADIUS / (4 * e_star)
    delta0 = a0_cubed ** (2 / 3) / RADIUS
    rows = []
    for t in TABLE_TIMES:
        row = [f"{t * 1e3:.0f}", f"{creep_compliance(t) * SHEAR_MODULUS_INSTANTANEOUS:.3f}"]
        for name, res in results.items():
            k = int(np.argmin(np.abs(res["t"] - t)))
            if abs(res["t"][k] - t) > 1e-9:
                row += ["-", "-"]
                continue
            a_cubed = (res["area"][k] / np.pi) ** 1.5
            ratio = res["delta"][k] / delta0
            row += [f"{a_cubed / a0_cubed:.3f}", f"{np.sign(ratio) * abs(ratio) ** 1.5:.3f}"]
        rows.append(row)
    return rows


def print_table(header: list[str], rows: list[list[str]]) -> None:
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for r in rows:
        print("| " + " | ".join(r) + " |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=256, help="cells per side (default 256)")
    ap.add_argument("--steps", type=int, default=201, help="time steps of 0.2 ms (default 201)")
    ap.add_argument("--repeats", type=int, default=2, help="alternated pairs (default 2)")
    ap.add_argument("--tamaas-python", help=f"interpreter of the Tamaas environment (or ${TAMAAS_ENV})")
    ap.add_argument("--tamaas-tolerance", type=float, default=TAMAAS_TOLERANCE,
                    help=f"tolerance of Tamaas's solvers (default {TAMAAS_TOLERANCE:g})")
    ap.add_argument("--no-maxwell", action="store_true", help="skip Tamaas's MaxwellViscoelastic")
    ap.add_argument("--half", choices=sorted(HALVES), help=argparse.SUPPRESS)
    ap.add_argument("--result", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.half:  # a child: solve, save, exit
        tolerance = VISCONTACT_TOLERANCE if args.half == "viscontact" else args.tamaas_tolerance
        if args.half == "viscontact":
            out = HALVES[args.half](args.n, args.steps, tolerance)
        else:  # Tamaas logs to the C++ streams: catch them in a file to count its iterations
            with tempfile.TemporaryFile("w+") as log:
                saved = os.dup(1), os.dup(2)
                sys.stdout.flush()
                os.dup2(log.fileno(), 1)
                os.dup2(log.fileno(), 2)
                try:
                    out = HALVES[args.half](args.n, args.steps, tolerance)
                finally:
                    os.dup2(saved[0], 1)
                    os.dup2(saved[1], 2)
                log.seek(0)
                out["iterations"] = _tamaas_iterations(log.read())
        out["own_rss_mib"] = peak_rss_mib()
        np.savez(args.result, **{k: np.asarray(v) for k, v in out.items()})
        return

    python = tamaas_python(args.tamaas_python)
    load = os.getloadavg()
    print(f"# creep indentation, {args.n}^2 x {args.steps} steps, {time.strftime('%Y-%m-%d %H:%M')}, "
          f"{os.cpu_count()} cores, load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} at the start")
    runs: dict[str, list[dict]] = {"viscontact": [], "tamaas": []}
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(args.repeats):
            for half, interpreter in (("viscontact", sys.executable), ("tamaas", python)):
                runs[half].append(run_half(interpreter, half, args, Path(tmp)))
                r = runs[half][-1]
                print(f"  {half:10s} wall {r['wall']:6.1f} s (solve {float(r['solve_wall']):6.1f} s), "
                      f"CPU {r['cpu']:6.1f} s (sys {r['sys']:.1f} s), peak RSS {r['rss_mib']:.0f} MiB", flush=True)
        maxwell = None if args.no_maxwell else run_half(python, "maxwell", args, Path(tmp))
    load = os.getloadavg()
    print(f"# load average at the end {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}\n")

    print_table(["code", "wall [s]", "solve wall [s]", "ms/step", "CPU [s]", "of which sys [s]", "peak RSS [MiB]",
                 "iterations/step"],
                [_row(h, runs[h], args.steps) for h in runs])
    v, t = runs["viscontact"], runs["tamaas"]
    ratio = {k: float(np.median([b[k] for b in t]) / np.median([a[k] for a in v]))
             for k in ("wall", "solve_wall", "cpu", "rss_mib")}
    p_v, p_t = v[-1]["pressure"], t[-1]["pressure"]
    print(f"\nTamaas stepper / viscontact: wall {ratio['wall']:.1f}x, solve wall {ratio['solve_wall']:.1f}x, "
          f"CPU {ratio['cpu']:.1f}x, peak memory {ratio['rss_mib']:.2f}x")
    print(f"final pressure: max |p_viscontact - p_tamaas| / max p = {np.abs(p_v - p_t).max() / p_v.max():.1e}, "
          f"contact cells {int((p_v > 0).sum())} vs {int((p_t > 0).sum())}\n")

    results = {"viscontact": v[-1], "tamaas stepper": t[-1]}
    if maxwell is not None:
        results["MaxwellViscoelastic"] = maxwell
        print(f"MaxwellViscoelastic: solve {float(maxwell['solve_wall']):.1f} s, peak RSS {maxwell['rss_mib']:.0f} MiB "
              f"(its 'delta' column is its displacement at the centre)")
    print("Lee-Radok under the held load: a(t)^3 / a_H^3 and (delta(t) / delta_H)^(3/2) must follow J(t)/J(0) "
          "(a_H, delta_H: Hertz with G(0))\n")
    header = ["t [ms]", "J(t)/J(0)"]
    for name in results:
        header += [f"{name} a^3", f"{name} delta^1.5"]
    print_table(header, lee_radok_table(results))


if __name__ == "__main__":
    main()
