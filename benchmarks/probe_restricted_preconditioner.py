"""How far a better preconditioner of the contact's restricted operator can cut the CG's iterations,
and at what cost (issue 35: at most 5 CG iterations a step). Dense linear algebra on a small window.

    .venv/bin/python benchmarks/probe_restricted_preconditioner.py            # m = 48, contact radius 16 cells
    .venv/bin/python benchmarks/probe_restricted_preconditioner.py --m 64 --radius 24

The constrained CG solves, on the free set F (the contact), K_FF p = r with K the DC-FFT (aperiodic)
influence matrix of the Boussinesq kernel (zz, nu = 0.3) on an m x m support window, preconditioned by
P_FF, P the Fourier preconditioner of :class:`viscontact.numerics.convolution.FourierPreconditioner`:
the exact inverse of the window's periodic operator K_per (P = K_per^-1). Each variant below is a
fixed symmetric operator M approximating K_FF^-1; printed: the extreme eigenvalues of M K_FF, its
condition number, the share of eigenvalues above 1.1, the CG iterations from a random right-hand
side to a residual of 1e-10, and the cost of one application of M in transform pairs of the
window's size (unpadded m^2 pairs; one padded (2m)^2 product of K d, which every iteration makes, is
about four of them), hence the estimated cost of the solve in unpadded pairs:

* ``P_FF``: what the solver uses (one pair);
* ``Chebyshev degree d``: d steps of the Chebyshev iteration for (P K_per)_FF y = P_FF r, the polynomial
  approximation of (K_per,FF)^-1 (2 d + 1 pairs);
* ``ring Schur, w cells``: P_FF - P_FO P_OO^-1 P_OF with O the outside cells within w of the contact
  (a dense solve on the ring: not an FFT operation, no pair count);
* ``Schur of P``: the same over all the outside, = (K_per,FF)^-1 exactly (an inner solve);
* ``exact``: K_FF^-1.

The numbers of 2026-11-28 are in BENCHMARKS.md (issue 35's diary section).
"""
from __future__ import annotations

import argparse

import numpy as np

from viscontact.numerics.convolution import FourierPreconditioner
from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import influence_coefficients

#: a padded (2m)^2 product (forward and inverse) in unpadded m^2 pairs: four times the points
PADDED_PAIR = 4.0


def dense_operators(m: int) -> tuple[np.ndarray, np.ndarray]:
    """(K, P): the aperiodic influence matrix of the m x m window and the dense Fourier preconditioner."""
    kernel = influence_coefficients(Grid(m, 1.0), 0.3, ("zz",))["zz"]
    rows, cols = np.divmod(np.arange(m * m), m)
    k = kernel[(rows[:, None] - rows[None, :]) % (2 * m), (cols[:, None] - cols[None, :]) % (2 * m)]
    pre = FourierPreconditioner.for_kernel(kernel)
    p = np.stack([pre(e.reshape(m, m)).ravel() for e in np.eye(m * m)], axis=1)
    return k, 0.5 * (p + p.T)


def cg_iterations(m_op: np.ndarray, a: np.ndarray, tolerance: float = 1e-10, cap: int = 500) -> int:
    """Preconditioned CG iterations for a x = b, b random, to |r| < tolerance |b|."""
    b = np.random.default_rng(0).standard_normal(a.shape[0])
    x, r = np.zeros_like(b), b.copy()
    z = m_op @ r
    d, rz = z.copy(), r @ z
    for it in range(1, cap + 1):
        ad = a @ d
        step = rz / (d @ ad)
        x += step * d
        r -= step * ad
        if np.linalg.norm(r) < tolerance * np.linalg.norm(b):
            return it
        z = m_op @ r
        rz, rz_old = r @ z, rz
        d = z + rz / rz_old * d
    return cap


def chebyshev_inverse(b: np.ndarray, lo: float, hi: float, degree: int) -> np.ndarray:
    """The matrix of ``degree`` + 1 Chebyshev steps for b y = c from y = 0 (Saad, Iterative Methods,
    Alg. 12.1), an approximation of b^-1 from the spectrum bounds [lo, hi] of b."""
    eye = np.eye(b.shape[0])
    theta, delta = (hi + lo) / 2, (hi - lo) / 2
    sigma = theta / delta
    rho = 1 / sigma
    y = d = eye / theta
    residual = eye - b @ y
    for _ in range(degree):
        rho_new = 1 / (2 * sigma - rho)
        d = rho_new * rho * d + 2 * rho_new / delta * residual
        y = y + d
        residual = eye - b @ y
        rho = rho_new
    return y


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--m", type=int, default=48, help="window cells per side (dense: (m^2)^2 doubles)")
    ap.add_argument("--radius", type=float, default=16.0, help="contact radius [cells]")
    args = ap.parse_args()
    m = args.m
    k, p = dense_operators(m)
    centre = m / 2 - 0.5
    rows, cols = np.divmod(np.arange(m * m), m)
    distance = np.hypot(rows - centre, cols - centre)
    free = distance < args.radius
    a = k[np.ix_(free, free)]
    p_ff, p_fo, p_oo = p[np.ix_(free, free)], p[np.ix_(free, ~free)], p[np.ix_(~free, ~free)]
    k_periodic_ff = np.linalg.inv(p)[np.ix_(free, free)]
    b = p_ff @ k_periodic_ff
    spectrum = np.linalg.eigvals(b).real
    lo, hi = spectrum.min(), spectrum.max()
    variants: list[tuple[str, np.ndarray, float | None]] = [("P_FF (the solver's)", p_ff, 1.0)]
    for degree in (1, 2, 3):
        approx = chebyshev_inverse(b, lo, hi, degree) @ p_ff
        variants.append((f"Chebyshev degree {degree}", 0.5 * (approx + approx.T), 2.0 * degree + 1))
    for width in (2, 5, 8):
        ring = (~free) & (distance < args.radius + width)
        p_fr = p[np.ix_(free, ring)]
        variants.append((f"ring Schur, w = {width} cells", p_ff - p_fr @ np.linalg.solve(p[np.ix_(ring, ring)], p_fr.T),
                         None))
    variants.append(("Schur of P (= K_per,FF^-1)", p_ff - p_fo @ np.linalg.solve(p_oo, p_fo.T), None))
    variants.append(("exact K_FF^-1", np.linalg.inv(a), None))
    print(f"# window {m}^2, contact radius {args.radius:g} cells ({int(free.sum())} free points); "
          f"spectrum of (P K_per)_FF [{lo:.3f}, {hi:.3f}]")
    print("| preconditioner | min eig | max eig | condition | eig > 1.1 | CG iterations | pairs an application "
          "| est. cost [pairs] |")
    print("|---|---|---|---|---|---|---|---|")
    for name, m_op, pairs in variants:
        eig = np.sort(np.linalg.eigvals(m_op @ a).real)
        its = cg_iterations(m_op, a)
        cost = "–" if pairs is None else f"{its * (PADDED_PAIR + pairs):.0f}"
        print(f"| {name} | {eig[0]:.3f} | {eig[-1]:.3f} | {eig[-1] / eig[0]:.2f} | {100 * np.mean(eig > 1.1):.1f} % "
              f"| {its} | {'–' if pairs is None else f'{pairs:g}'} | {cost} |")


if __name__ == "__main__":
    main()
