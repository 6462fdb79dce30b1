"""Time of a line contact (``grid.dimension = 1``, plane strain): a 4096-cell line x 1000 steps.

    .venv/bin/python benchmarks/line_contact.py [--n 4096] [--steps 1000] [--mode frictionless_sliding]

A rigid cylinder (R = 10 mm, W = 2000 N/m) on the Zener polymer of the shipped case
``polymer_roller_line_contact`` (G(0) = 20 MPa, G(inf) = 2 MPa, tau = 1 ms, nu = 0.5) on +-8 mm, sliding
frictionless at 0.5 m/s from t = 0 (one cell of sliding per step: the frame shifts every step), or
``--mode none`` (held indentation, creep) or ``--mode partial_slip`` (the shipped case's tangential
loading). The steps run through :func:`viscontact.solvers.transient.steps` (no records kept: the solver
alone). Each step is O(n log n): its transforms are 1-D real FFTs of 2n points. Prints the wall and
CPU time, the time per step and the last step's mu_app and contact half-width.
"""
from __future__ import annotations

import argparse
import time

from viscontact.io.case import load_case
from viscontact.io.shipped import shipped_case
from viscontact.solvers.transient import steps


def problem(n: int, count: int, mode: str):
    """The shipped roller case on n cells with ``count`` steps of one cell of sliding each."""
    case = load_case(shipped_case("polymer_roller_line_contact"))
    dx = 2 * case.grid.half_width / n
    speed = case.tangential.sliding_speed
    changes = {"grid.n": n, "time.t_end": count * dx / speed, "tangential.mode": mode}
    if mode == "none":
        changes["time.dt"] = dx / speed
    return case.with_overrides(changes).to_problem()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=4096, help="cells of the line (default 4096)")
    parser.add_argument("--steps", type=int, default=1000, help="time steps (default 1000)")
    parser.add_argument("--mode", default="frictionless_sliding",
                        choices=("frictionless_sliding", "none", "partial_slip"), help="tangential.mode")
    args = parser.parse_args()
    pb = problem(args.n, args.steps, args.mode)
    wall, cpu = time.perf_counter(), time.process_time()
    last = None
    for _, last in steps(pb):
        pass
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    print(f"line contact, {pb.grid.n} cells x {pb.time.n_steps} steps ({args.mode}): {wall:.2f} s wall, "
          f"{cpu:.2f} s CPU, {1e3 * wall / pb.time.n_steps:.2f} ms per step; last step: mu_app = {last.mu_app:.5g}, "
          f"half-width {last.contact_area / 2 * 1e3:.4g} mm")


if __name__ == "__main__":
    main()
