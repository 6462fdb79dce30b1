"""Steady rolling benchmark: one rolling state and a traction-creepage curve of 20 creepages on the
shipped case ``rolling_polymer_roller`` (a Zener rubber, V = a0/tau), against one steady sliding
state of the same contact. Prints a table.

    .venv/bin/python benchmarks/bench_rolling.py                 # n = 128 and 256
    .venv/bin/python benchmarks/bench_rolling.py --n 64 128

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
    creepages = list(-np.logspace(-4, np.log10(0.05), 20))
    out: dict[str, float] = {}
    for name, call in (("state", lambda: vc.run_steady(case)),
                       ("curve", lambda: vc.run_steady(case, creepages=creepages)),
                       ("sliding", lambda: vc.run_steady(sliding))):
        start = time.perf_counter()
        result = call()
        out[name] = time.perf_counter() - start
        if name == "curve":
            out["saturation"] = float(result["traction_ratio"][-1])
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, nargs="+", default=[128, 256])
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    print(f"{'n':>5} {'one state [s]':>14} {'20-point curve [s]':>19} {'one sliding state [s]':>22} "
          f"{'F/(mu W) at 0.05':>17}")
    for n in args.n:
        m = measure(n)
        print(f"{n:>5} {m['state']:>14.1f} {m['curve']:>19.1f} {m['sliding']:>22.1f} {m['saturation']:>17.3f}")


if __name__ == "__main__":
    main()
