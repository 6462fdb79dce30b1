"""
Viscoelastic adhesion: a sticky sphere pulled off at three rates
=================================================================

The shipped case ``adhesive_pdms_retraction.toml``: a rigid sphere (R = 10 mm) touches a PDMS-like Zener
half-space (G(0) = 1.05 MPa, G(∞) = 0.35 MPa, retardation time τ = 0.1 s, ν = 0.5) whose surface
sticks to it by a Maugis–Dugdale law (work of adhesion w = 50 mJ/m², cohesive stress σ₀ = 19 kPa, so a
range h₀ = w/σ₀ = 2.6 µm and a Maugis parameter λ = 1.0 with G(∞), 0.48 with G(0)). The sphere jumps in
at the first touch, is pressed 4 µm in 0.1 s, held 0.5 s (five retardation times: the body relaxes
towards G(∞)) and pulled back to −8 µm, past the jump-off, at three rates (displacement control).

Slowly, the load follows the Maugis–Dugdale curve of the relaxed modulus G(∞) (Maugis 1992,
:func:`viscontact.physics.adhesion.maugis_dugdale`) and the pull-off force, the most tensile load, is
its own (−1.60 πwR). The faster the retraction, the more the material near the receding contact edge
answers with its glassy modulus, and the more work the pull-off takes: the loop between approach and
retraction widens and the pull-off force grows beyond that of either elastic body (the glassy one pulls
off at −1.73 πwR at its λ): viscoelastic dissipation at the edge of the contact, not the stiffer modulus
alone. The curves of both moduli are drawn for reference; 64² cells of 20 µm resolve the cohesive ring
with about five cells, so the slowest pull-off (−1.82 πwR) is 14 % more tensile than the relaxed
elastic one (the cell-by-cell law converges at first order in the cell size: Numerics, section 10);
the error is much the same at every rate, the rate effect (a factor of 2.2 over the five rates) is not.
"""

import matplotlib.pyplot as plt
import numpy as np

import viscontact as vc
from viscontact.physics.adhesion import maugis_dugdale, maugis_dugdale_pull_off

G0, G_INF, TAU, NU = 1.05e6, 0.35e6, 0.1, 0.5  # Pa, Pa, s, -
R, W, SIGMA = 0.01, 0.05, 1.9e4  # m, J/m^2, Pa
HOLD_END, PRESSED, PULLED = 0.6, 4e-6, -8e-6  # s, m, m


def retraction_case(duration: float) -> vc.Case:
    """The shipped history with the pull back from 4 um to -8 um over ``duration`` [s]; steps of 20 ms,
    or 1/40 of the retraction when that is shorter."""
    dt = min(0.02, duration / 40)
    return vc.Case.from_dict({
        "material": {"type": "zener", "shear_modulus_instantaneous": G0, "shear_modulus_long_term": G_INF,
                     "retardation_time": TAU, "poisson_ratio": NU},
        "indenter": {"shape": "sphere", "radius": R},
        "grid": {"n": 64, "half_width": 0.64e-3},
        "normal": {"control": "displacement",
                   "history": [[0.0, 0.0], [0.1, PRESSED], [HOLD_END, PRESSED], [HOLD_END + duration, PULLED]]},
        "adhesion": {"work_of_adhesion": W, "law": "maugis_dugdale", "cohesive_stress": SIGMA},
        "time": {"t_end": HOLD_END + duration, "dt": dt},
    })


# %%
# Five retractions, from 80 τ to 0.2 τ (1.5 µm/s to 600 µm/s); the first, third and fifth are drawn.
durations = np.array([8.0, 2.0, 0.8, 0.2, 0.02])
runs = {d: vc.run(retraction_case(d)) for d in durations}
scale = np.pi * W * R
for d, ds in runs.items():
    print(f"retraction over {d:5.2f} s ({abs(PULLED - PRESSED) / d * 1e6:6.1f} um/s): pull-off force "
          f"{ds.attrs['pull_off_force'] * 1e3:.2f} mN = {ds.attrs['pull_off_force'] / scale:.2f} pi w R")

# %%
# Load against approach: each run jumps in at the first touch, is pressed (the load rises above the
# glassy curve's: the approach is fast against τ), relaxes at 4 µm towards the relaxed curve, and on the
# way back follows a curve the further below the relaxed one the faster it is pulled, to the jump-off.
curves = {}
for name, g in (("G(∞)", G_INF), ("G(0)", G0)):
    e_star = 2 * g / (1 - NU)
    curves[name] = maugis_dugdale(1 + np.geomspace(1e-6, 30.0, 800), R, e_star, W, SIGMA)
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
for (name, curve), style in zip(curves.items(), ("k--", "k:")):
    keep = curve.approach <= PRESSED * 1.05
    ax1.plot(curve.approach[keep] * 1e6, curve.load[keep] / scale, style, lw=1, label=f"Maugis–Dugdale, {name}")
for d, color in zip(durations[::2], ("C0", "C1", "C2")):
    ds = runs[d]
    ax1.plot(ds["delta_z"] * 1e6, ds["load"] / scale, color, lw=1.2, label=f"pulled back over {d:g} s")
ax1.set(xlabel="approach δ [µm]", ylabel="load W / (π w R)", xlim=(PULLED * 1e6 * 0.8, PRESSED * 1e6 * 1.1))
ax1.legend(fontsize="small")

# %%
# The pull-off force against the retraction rate, with the elastic pull-offs of both moduli.
rates = abs(PULLED - PRESSED) / durations
pull_offs = np.array([runs[d].attrs["pull_off_force"] for d in durations])
ax2.semilogx(rates * 1e6, -pull_offs / scale, "o-", label="viscoelastic (64² cells)")
for (name, g), style in zip((("G(∞)", G_INF), ("G(0)", G0)), ("k--", "k:")):
    elastic = float(maugis_dugdale_pull_off(R, 2 * g / (1 - NU), W, SIGMA).load)
    ax2.axhline(-elastic / scale, ls=style[1:], color="k", lw=1, label=f"elastic Maugis–Dugdale, {name}")
ax2.set(xlabel="retraction rate [µm/s]", ylabel="pull-off force −P / (π w R)")
ax2.legend(fontsize="small")
fig.suptitle("Adhesive approach, dwell and retraction of a sphere on a Zener half-space")
fig.tight_layout()
plt.show()
