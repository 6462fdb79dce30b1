"""Direct sums against a product: where the constrained CG's bound corrections stop paying by direct sums.

    .venv/bin/python benchmarks/sparse_products.py [--n 256 --n 512] [--repeats 30]

The constrained CG adds the product of its bound corrections (a few points) by direct sums of
kernel blocks (``apply_sparse``: two passes over the grid a point) while they cost less than a
product (``apply``: transforms). Each operator says up to how many points that holds
(``ElasticOperator.sparse_limit``, from its convolver: 48 for the padded DC-FFT, 6 for the unpadded
periodic convolution). Printed per operator (the shipped seed Table 1 case on the full grid and on a
window of about half its side, and the shipped rough periodic case): the time of a double and a
single-precision product, of the preconditioner, and of the direct sums of 1 to 48 random points
[ms, mean of ``--repeats``], and the largest count of points whose direct sums cost less than the
double product and than the float32 one (the break-even: a mixed-precision solve compares them with
the float32 product, up to ``min(sparse_limit, SPARSE_LIMIT_MIXED = 24)`` points).
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from viscontact.bodies.compliance import compliance_of
from viscontact.io.case import load_case

CASES = Path(__file__).resolve().parents[1] / "src" / "viscontact" / "cases"
POINTS = (1, 2, 4, 8, 16, 24, 48)


def _mean_ms(action, repeats: int) -> float:
    action()
    start = time.perf_counter()
    for _ in range(repeats):
        action()
    return (time.perf_counter() - start) / repeats * 1e3


def row(label: str, op, n: int, repeats: int) -> str:
    rng = np.random.default_rng(0)
    field = rng.random((n, n))
    double = _mean_ms(lambda: op.apply(field), repeats)
    single = _mean_ms(lambda: op.apply_increment(field), repeats) if op.apply_increment else float("nan")
    precond = _mean_ms(lambda: op.preconditioner(field), repeats)
    sums = []
    for k in POINTS:
        sparse = np.zeros((n, n))
        sparse.flat[rng.choice(n * n, k, replace=False)] = 1.0
        sums.append(_mean_ms(lambda: op.apply_sparse(sparse), repeats))
    even = max((k for k, t in zip(POINTS, sums) if t < double), default=0)
    even_single = max((k for k, t in zip(POINTS, sums) if t < single), default=0)
    cells = " | ".join(f"{t:.2f}" for t in sums)
    return (f"| {label} | {double:.2f} | {single:.2f} | {precond:.2f} | {cells} | {even} / {even_single} | "
            f"{op.sparse_limit} |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, action="append", help="cells per side (repeatable; default 256 and 512)")
    ap.add_argument("--repeats", type=int, default=30)
    args = ap.parse_args()
    sizes = args.n or [256, 512]
    print("| operator | product [ms] | float32 product | preconditioner | "
          + " | ".join(f"{k} pt" for k in POINTS) + " | break-even [points]: double / float32 | sparse_limit |")
    print("|---" * (6 + len(POINTS)) + "|")
    for n in sizes:
        rough = load_case(CASES / "rough_periodic_sliding.toml").with_overrides({"grid.n": n}).to_problem()
        print(row(f"periodic {n}²", compliance_of(rough).elastic_operator("z", False), n, args.repeats))
        table1 = load_case(CASES / "seed_table1_v0.8.toml").with_overrides({"grid.n": n}).to_problem()
        op = compliance_of(table1).elastic_operator("z", False)
        print(row(f"DC-FFT {n}²", op, n, args.repeats))
        m = n // 2 + 10
        print(row(f"DC-FFT window {m}² of {n}²", op.window(m), m, args.repeats))


if __name__ == "__main__":
    main()
