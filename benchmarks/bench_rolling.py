"""Steady rolling benchmark: one rolling state and a traction-creepage curve of 20 creepages on the
shipped case ``rolling_polymer_roller`` (a Zener rubber, V = a0/tau), against one steady sliding
state of the same contact; then the same in line contact on the shipped ``polymer_roller_line_contact``
(a Zener polymer, 2000 N/m, rolling at its sliding speed 0.5 m/s, v tau / a0 = 0.89). Prints two tables.

    .venv/bin/python benchmarks/bench_rolling.py                 # n = 128 and 256; line: 1024 and 4096
    .venv/bin/python benchmarks/bench_rolling.py --n 64 128 --line-n 1024

The curve: ``viscontact.run_steady(case, creepages=...)`` (what ``viscontact steady --creepages``
does, without writing the file), 20 braking creepages log-spaced from 1e-4 to 0.05, each started from
the previous one's stick set.
"""
from __future__ import annotations

import argparse
import time
import warnings

import numpy as np

import viscontact as vc


def measure(n: int) -> dict[str, float]:
    case = vc.load_case(vc.shipped_case("rolling_polymer_roller")).with_overrides({"grid.n": n})
    sliding = case.with_overrides({"tangential.mode": "frictionless_sliding", "tangential.sliding_speed": 0.0526,
                                   "tangential.rolling_speed": 0.0, "tangential.creepage": None})
    return _timed(case, sliding)


def measure_line(n: int) -> dict[str, float]:
    """One steady rolling state (creepage -5e-3) and the 20-point curve of the line contact on n cells
    (the first call of each size builds the steady kernels)."""
    case = vc.load_case(vc.shipped_case("polymer_roller_line_contact")).with_overrides({
        "grid.n": n, "tangential.mode": "rolling", "tangential.rolling_speed": 0.5, "tangential.creepage": -5e-3,
        "tangential.displacement_rate": None, "tangential.slip": None, "tangential.sliding_speed": None})
    return _timed(case)


def _timed(case, sliding=None) -> dict[str, float]:
    """Wall times [s] of one steady rolling state of ``case``, its 20-point curve (braking creepages
    1e-4 ... 0.05) and, given, the steady ``sliding`` state; with the curve's last F/(mu_f W)."""
    creepages = list(-np.logspace(-4, np.log10(0.05), 20))
    calls = [("state", lambda: vc.run_steady(case)), ("curve", lambda: vc.run_steady(case, creepages=creepages))]
    if sliding is not None:
        calls.append(("sliding", lambda: vc.run_steady(sliding)))
    out: dict[str, float] = {}
    for name, call in calls:
        start = time.perf_counter()
        result = call()
        out[name] = time.perf_counter() - start
        if name == "curve":
            out["saturation"] = float(result["traction_ratio"][-1])
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, nargs="+", default=[128, 256])
    parser.add_argument("--line-n", type=int, nargs="*", default=[1024, 4096])
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    print(f"{'n':>5} {'one state [s]':>14} {'20-point curve [s]':>19} {'one sliding state [s]':>22} "
          f"{'F/(mu W) at 0.05':>17}")
    for n in args.n:
        m = measure(n)
        print(f"{n:>5} {m['state']:>14.1f} {m['curve']:>19.1f} {m['sliding']:>22.1f} {m['saturation']:>17.3f}")
    if args.line_n:
        print(f"\nline contact\n{'n':>5} {'one state [s]':>14} {'20-point curve [s]':>19} {'F/(mu W) at 0.05':>17}")
    for n in args.line_n:
        m = measure_line(n)
        print(f"{n:>5} {m['state']:>14.2f} {m['curve']:>19.2f} {m['saturation']:>17.3f}")


if __name__ == "__main__":
    main()
