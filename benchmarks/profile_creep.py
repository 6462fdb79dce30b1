"""Where the creep run's time and memory go: a profile of ``transient.simulate`` for the seed's creep case.

    .venv/bin/python benchmarks/profile_creep.py --n 256 [--steps 201] [--line] [--pyinstrument]

Prints (all from one run unless said otherwise):

* wall, user and sys CPU time, minor page faults and peak RSS of the run;
* cProfile by category: FFTs (count, shapes, time), the rest of the constrained CG (numpy element
  work), the hereditary history, per-step bookkeeping, records; and the top functions by own time;
* CG iterations per step (first step, mean, max) and FFT pairs per step;
* with ``--line``: line_profiler of :func:`viscontact.numerics.constrained.constrained_cg` (needs the
  ``bench`` extra); with ``--pyinstrument``: pyinstrument's call tree (``bench`` extra);
* ``--memory``: peak RSS of the same run at two lengths (fresh subprocesses), i.e. its growth per
  step, and tracemalloc's peak within one step.

The case is the one of ``compare_tamaas.py`` (Zener seed material, W = 0.15 N held, +-1.5 mm).
"""
from __future__ import annotations

import argparse
import cProfile
import collections
import os
import pstats
import resource
import subprocess
import sys
import time
import warnings

import numpy as np
import scipy.fft

import viscontact as vc
from compare_tamaas import peak_rss_mib
from viscontact.solvers import transient
from viscontact.running import loop

HALF_WIDTH, RADIUS, LOAD, DT = 1.5e-3, 0.01, 0.15, 2e-4


def creep_problem(n: int, steps: int) -> vc.Problem:
    grid = vc.Grid(n, HALF_WIDTH)
    x, y = grid.mesh()
    return vc.Problem(material=vc.Material.zener(1.93e6, 0.193e6, 0.01, 0.3), grid=grid,
                      gap=(x**2 + y**2) / (2 * RADIUS),
                      normal=vc.NormalLoading("load", vc.PiecewiseLinear.constant(LOAD)),
                      tangential=vc.TangentialLoading(), time=vc.TimeStepping((steps - 1) * DT, DT, scheme="constant"),
                      radius=RADIUS)


def run(problem: vc.Problem) -> list:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return list(loop.simulate(problem))


class FFTCensus:
    """Wraps the scipy.fft functions the solver calls: count, input shape and time per call."""

    NAMES = ("rfft2", "irfft2", "rfft", "irfft", "fft", "ifft")

    def __init__(self) -> None:
        self.calls: collections.Counter = collections.Counter()
        self.seconds: collections.Counter = collections.Counter()
        self.saved = {name: getattr(scipy.fft, name) for name in self.NAMES}

    def __enter__(self) -> "FFTCensus":
        for name, fn in self.saved.items():
            setattr(scipy.fft, name, self._wrap(name, fn))
        return self

    def __exit__(self, *exc) -> None:
        for name, fn in self.saved.items():
            setattr(scipy.fft, name, fn)

    def _wrap(self, name, fn):
        def wrapped(x, *args, **kwargs):
            key = (name, tuple(np.shape(x)), str(kwargs.get("s", "")))
            start = time.perf_counter()
            out = fn(x, *args, **kwargs)
            self.seconds[key] += time.perf_counter() - start
            self.calls[key] += 1
            return out
        return wrapped


CATEGORIES = (  # (label, predicate on (file, function)); the first that matches takes the function
    ("FFT (scipy.fft / pocketfft)", lambda f, fn: "scipy/fft" in f or "pocketfft" in fn or "_pocketfft" in f),
    ("history (Prony recursion)", lambda f, fn: f.endswith("history.py")),
    ("constrained CG (element-wise numpy)", lambda f, fn: f.endswith("constrained.py")),
    ("convolution glue", lambda f, fn: f.endswith("convolution.py")),
    ("step bookkeeping (guard, records, gap)", lambda f, fn: f.endswith(("transient.py", "sliding.py", "records.py"))),
)


def categorise(stats: pstats.Stats) -> dict[str, float]:
    """Own time per category (a function's tottime counts for the category of its file; numpy
    built-ins are attributed to their caller's category through the callers table)."""
    out: collections.Counter = collections.Counter()
    for (file, _, fn), (_, _, tottime, _, callers) in stats.stats.items():
        for label, pred in CATEGORIES:
            if pred(file, fn):
                out[label] += tottime
                break
        else:
            if file == "~" and callers:  # a C function: split its time over its callers' categories
                total = sum(c[2] for c in callers.values()) or 1.0
                for (cfile, _, cfn), c in callers.items():
                    label = next((lab for lab, pred in CATEGORIES if pred(cfile, cfn)), "other")
                    out[label] += tottime * c[2] / total
            else:
                out["other"] += tottime
    return dict(out)


def memory_growth(n: int, steps: tuple[int, int]) -> None:
    """Peak RSS of the run at two lengths, each in a fresh interpreter."""
    code = ("import profile_creep as p, compare_tamaas as c; "
            f"p.run(p.creep_problem({n}, {{steps}})); print(c.peak_rss_mib())")
    here = os.path.dirname(os.path.abspath(__file__))
    rss = []
    for s in steps:
        out = subprocess.run([sys.executable, "-c", code.format(steps=s)], cwd=here, capture_output=True, text=True,
                             check=True)
        rss.append(float(out.stdout.split()[-1]))
    print(f"peak RSS: {rss[0]:.0f} MiB at {steps[0]} steps, {rss[1]:.0f} MiB at {steps[1]} steps "
          f"-> {(rss[1] - rss[0]) / (steps[1] - steps[0]) * 1024:.0f} KiB per step "
          f"(one (n, n) float64 field is {n * n * 8 / 1024:.0f} KiB)")


def allocation_census(n: int) -> None:
    """tracemalloc (numpy reports its buffers to it) over one mid-run step: the peak of memory
    allocated within the step above its start, and what is still live after it (the record)."""
    import tracemalloc

    problem = creep_problem(n, 20)
    ops = transient.operators(problem)
    state = transient.init(problem)
    for _ in range(10):
        state, _ = transient.step(problem, ops, state)
    tracemalloc.start(1)
    base = tracemalloc.get_traced_memory()[0]
    state, record = transient.step(problem, ops, state)
    current, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    print(f"one step ({record.iterations} CG iterations): peak {(peak - base) / 2**20:.1f} MiB allocated above "
          f"its start, {(current - base) / 2**20:.1f} MiB still live after it")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=256)
    ap.add_argument("--steps", type=int, default=201)
    ap.add_argument("--line", action="store_true", help="line_profiler of constrained_cg")
    ap.add_argument("--pyinstrument", action="store_true", help="pyinstrument call tree")
    ap.add_argument("--memory", action="store_true", help="RSS growth per step and an allocation census")
    ap.add_argument("--top", type=int, default=15)
    args = ap.parse_args()
    problem = creep_problem(args.n, args.steps)
    load = os.getloadavg()
    print(f"# profile of the creep run, {args.n}^2 x {args.steps} steps, {os.cpu_count()} cores, "
          f"load average {load[0]:.2f}, {time.strftime('%Y-%m-%d %H:%M')}")

    # 1. plain run: times, page faults
    r0, t0, w0 = resource.getrusage(resource.RUSAGE_SELF), os.times(), time.perf_counter()
    records = run(problem)
    w1, t1, r1 = time.perf_counter(), os.times(), resource.getrusage(resource.RUSAGE_SELF)
    its = np.array([r.iterations for r in records])
    print(f"plain run: wall {w1 - w0:.1f} s, user {t1.user - t0.user:.1f} s, sys {t1.system - t0.system:.1f} s, "
          f"minor page faults {r1.ru_minflt - r0.ru_minflt} ({(r1.ru_minflt - r0.ru_minflt) / len(records):.0f} per "
          f"step), peak RSS {peak_rss_mib():.0f} MiB")
    print(f"CG iterations per step: first {its[0]}, mean {its.mean():.1f}, median {np.median(its):.0f}, "
          f"max {its.max()}, total {its.sum()}")
    del records

    # 2. cProfile + FFT census
    prof = cProfile.Profile()
    with FFTCensus() as census:
        prof.enable()
        records = run(problem)
        prof.disable()
    stats = pstats.Stats(prof)
    total = stats.total_tt
    print(f"\ncProfile (total {total:.1f} s, with profiling overhead):")
    print("| category | own time [s] | share |")
    print("|---|---|---|")
    for label, sec in sorted(categorise(stats).items(), key=lambda kv: -kv[1]):
        print(f"| {label} | {sec:.2f} | {100 * sec / total:.0f}% |")
    print("\nFFT calls (function, input shape, s=):")
    print("| call | count | per step | ms per call | total [s] |")
    print("|---|---|---|---|---|")
    for key, count in census.calls.most_common():
        sec = census.seconds[key]
        print(f"| {key[0]} {key[1]} {key[2]} | {count} | {count / len(records):.1f} | {1e3 * sec / count:.2f} | {sec:.2f} |")
    print(f"\ntop {args.top} functions by own time:")
    stats.sort_stats("tottime").print_stats(args.top)
    del records

    if args.line:
        from line_profiler import LineProfiler

        from viscontact.numerics import constrained

        lp = LineProfiler(constrained.constrained_cg)
        lp.enable()
        run(creep_problem(args.n, min(args.steps, 51)))
        lp.disable()
        lp.print_stats(output_unit=1e-3, stripzeros=True)
    if args.pyinstrument:
        from pyinstrument import Profiler

        p = Profiler(interval=0.002)
        p.start()
        run(creep_problem(args.n, min(args.steps, 51)))
        p.stop()
        print(p.output_text(unicode=False, color=False, show_all=False))
    if args.memory:
        memory_growth(args.n, (max(args.steps // 4, 2), args.steps))
        allocation_census(args.n)


if __name__ == "__main__":
    main()
