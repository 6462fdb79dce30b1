"""
Real-material master curve
==========================

The shipped case ``pmma_master_curve``: a rigid sphere (R = 10 mm) slides without friction on a
half-space of poly(methyl methacrylate) whose tensile relaxation modulus is a published Prony
series of 11 terms one decade apart (τ_i = 0.02 s … 2·10⁸ s, E(0) = 2239.47 MPa,
E(∞) = 2.24 MPa): Schapery's 1962 data as fitted by Park & Schapery (Int. J. Solids Struct. 36,
1653, 1999) and reproduced by Shanbhag (J. Rheol. 67, 965, 2023). The term file,
``cases/materials/pmma_schapery1962.csv``, is in pyvisco's layout; its companion ``.md`` gives the
sources and the licence. PMMA is a glassy polymer, not an elastomer: the series runs through the
glass transition to an entanglement plateau that the sources take as E(∞). ν = 0.5 is an
assumption of the case (the sources give none), so G = E/3.

The approach is held at δ = 1 µm, so the Hertz radius a = √(Rδ) = 100 µm is the same in the slow
(G(∞)) and the fast (G(0)) limit although the moduli differ a thousandfold; 20 steady states one
decade of speed apart, on the case's 64² grid.
"""

import matplotlib.pyplot as plt
import numpy as np

import viscontact as vc
from viscontact.plotting.result import speed_curve_figure
from viscontact.reference import hertz_from_approach
from viscontact.results import material_dataset

case = vc.load_case(vc.shipped_case("pmma_master_curve"))
material = case.to_problem().material
mat = material_dataset(material)

# %%
# The material: relaxation modulus G(t) with the 11 relaxation times, and the loss factor
# tan δ(ω). The decade-spaced discrete spectrum leaves a ripple on tan δ.
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.5))
ax1.loglog(mat["t"], mat["relaxation_modulus"] / 1e6)
for tau in material.tau:
    ax1.axvline(tau, color="0.8", lw=0.6, zorder=0)
ratio = material.shear_modulus_instantaneous / material.shear_modulus_long_term
ax1.set(xlabel="t [s]", ylabel="G(t) [MPa]", title=f"relaxation modulus, G(0)/G(∞) = {ratio:.0f}")
ax2.semilogx(mat["omega"], mat["tan_delta"])
ax2.set(xlabel="ω [rad/s]", ylabel="tan δ [-]", title="loss factor")
fig.tight_layout()

# %%
# The steady speed curve: μ_app (and peak pressure, contact area and shift) against the Deborah
# number v τ/a0 (τ: the shortest retardation time, 0.022 s; a0 = 100 µm), speed in m/s on the top
# axis. μ_app rises from zero, has one broad maximum near 10⁻⁸ m/s and falls back to zero.
speeds = np.logspace(-17, 2, 20)
ds = vc.run_steady(case, speeds)
speed_curve_figure(ds)

peak = int(np.argmax(ds["mu_app"].values))
print(f"mu_app maximum {float(ds['mu_app'][peak]):.4f} at v = {speeds[peak]:.0e} m/s")

# %%
# The limits: the load needed to hold δ = 1 µm climbs a thousandfold from Hertz with G(∞) (slow
# sliding, the material fully relaxed) to Hertz with G(0) (fast sliding, no time to relax).
radius, approach = case.indenter.radius, case.normal.value
limits = [hertz_from_approach(approach, radius, g, material.poisson_ratio).load
          for g in (material.shear_modulus_long_term, material.shear_modulus_instantaneous)]
fig, ax = plt.subplots(figsize=(5.5, 3.5))
ax.loglog(speeds, ds["load"], "o-", ms=4, label="viscontact, steady, 64²")
for load, name in zip(limits, ("Hertz, G(∞)", "Hertz, G(0)")):
    ax.axhline(load, color="k", ls="--", lw=0.8)
    ax.annotate(name, (speeds[0], load), textcoords="offset points", xytext=(2, 4), fontsize=8)
ax.set(xlabel="sliding speed v [m/s]", ylabel="load W [N]", title="held approach δ = 1 µm")
ax.legend(loc="center right")
fig.tight_layout()
print(f"slow limit: W / W_Hertz(G(inf)) = {float(ds['load'][0]) / limits[0]:.4f}; "
      f"fast limit: W / W_Hertz(G(0)) = {float(ds['load'][-1]) / limits[1]:.4f}")
