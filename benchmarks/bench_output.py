"""What writing the result costs a run: ``viscontact.run_to_file`` (what ``viscontact run`` does) on the
creep and seed Table 1 problems of ``bench_core.py``, streamed to a file in a temporary folder.

    .venv/bin/python benchmarks/bench_output.py                 # 256^2, one run of each
    .venv/bin/python benchmarks/bench_output.py --repeats 3     # median (best) of three

Columns: the run's wall time; the time its own thread spends handing records to the stream
(``StreamWriter.keep``: writing the record queued before, queueing this one; the fields' compression
runs on the stream's thread meanwhile, :mod:`viscontact.io.streaming`), in total and per record; the
size of the file. To compare two trees, run the script with ``PYTHONPATH=<tree>/src``, alternately.
"""
from __future__ import annotations

import argparse
import platform
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

import viscontact as vc
from bench_core import A0, TAU, sphere
from viscontact.running import observers
from viscontact.problem.problem import TangentialLoading


def problems(n: int) -> dict[str, vc.Problem]:
    """The creep and table1 rows of ``bench_core.py``."""
    v, hw = 0.8 * A0 / TAU, 2.56 * A0
    return {"creep": sphere(n, 1.5e-3, "load", 0.15, TangentialLoading(), 0.04, 2e-4),
            "table1": sphere(n, hw, "load", 0.148, TangentialLoading("frictionless_sliding", 0.0, 0.0, v), 4 * TAU,
                             2 * hw / n / v)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=256, help="cells per side (default 256)")
    ap.add_argument("--repeats", type=int, default=1, help="runs of each problem: median and best")
    args = ap.parse_args()

    spent = [0.0]
    keep = observers.StreamWriter.keep

    def timed_keep(self, record):
        start = time.perf_counter()
        keep(self, record)
        spent[0] += time.perf_counter() - start

    observers.StreamWriter.keep = timed_keep
    print(f"# viscontact result streaming, n = {args.n}, {platform.processor() or platform.machine()}, "
          f"{platform.python_version()}, {time.strftime('%Y-%m-%d %H:%M')}")
    print("| problem | records | run_to_file wall [s] | writing on the run's thread [s] | per record [ms] | file [MiB] |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as folder, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name, problem in problems(args.n).items():
            walls, writing = [], []
            for i in range(args.repeats):
                spent[0] = 0.0
                start = time.perf_counter()
                written = vc.run_to_file(problem, Path(folder) / f"{name}{i}.nc")
                walls.append(time.perf_counter() - start)
                writing.append(spent[0])
            size = written.path.stat().st_size / 2**20
            wall = f"{np.median(walls):.2f} (best {min(walls):.2f})" if args.repeats > 1 else f"{walls[0]:.2f}"
            print(f"| {name} | {written.records} | {wall} | {np.median(writing):.2f} | "
                  f"{np.median(writing) / written.records * 1e3:.1f} | {size:.1f} |")


if __name__ == "__main__":
    main()
