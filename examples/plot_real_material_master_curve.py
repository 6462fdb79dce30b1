"""
Real-material master curves
===========================

Two shipped cases slide a rigid sphere (R = 10 mm) without friction on a half-space described by a
published Prony series, each term file in pyvisco's layout under ``cases/materials/`` with a
companion ``.md`` giving the sources, the conversion and the licence:

* ``pu_elastomer_master_curve``: a **polyurethane elastomer**, 10 shear terms one decade apart
  (τ_i = 10⁻⁷ s … 10² s, G(0) = 108.5 MPa, G(∞) = 2.44 MPa): Tables 1 and 3 of Pei, Du, Miao &
  Suo, Polymer Testing 133, 108375 (2024), as typed in the sfem code (the weights scaled to sum to
  1 − g∞; ν = 0.5, the paper's model being incompressible). Held approach δ = 4 µm, 128² grid.
* ``pmma_master_curve``: poly(methyl methacrylate), a glassy polymer, 11 tensile terms
  (τ_i = 0.02 s … 2·10⁸ s, E(0) = 2239.47 MPa, E(∞) = 2.24 MPa): Schapery's 1962 data as fitted
  by Park & Schapery (Int. J. Solids Struct. 36, 1653, 1999) and reproduced by Shanbhag
  (J. Rheol. 67, 965, 2023); ν = 0.5 is the case's assumption. Held approach δ = 1 µm, 64² grid.

Under a held approach the Hertz radius a = √(Rδ) is the same in the slow (G(∞)) and the fast
(G(0)) limit, so one grid resolves both although the moduli differ 44-fold (PU) or 1000-fold
(PMMA). One steady state per decade of speed.
"""

import matplotlib.pyplot as plt
import numpy as np

import viscontact as vc
from viscontact.plotting.result import speed_curve_figure
from viscontact.physics.reference import hertz_from_approach
from viscontact.io.results import material_dataset

CURVES = {"pu_elastomer_master_curve": ("PU elastomer", np.logspace(-10, 8, 19)),
          "pmma_master_curve": ("PMMA", np.logspace(-17, 2, 20))}
cases = {name: vc.load_case(vc.shipped_case(name)) for name in CURVES}
materials = {name: case.to_problem().material for name, case in cases.items()}

# %%
# The materials: relaxation modulus G(t) normalised by G(0), and the loss factor tan δ(ω). The
# elastomer relaxes over 10⁻⁷ … 10² s to 2.25 % of its glassy modulus (tan δ up to 0.52 near
# 7·10² rad/s); PMMA over 0.02 … 2·10⁸ s to 0.1 %. One term per decade leaves a ripple on tan δ.
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.5))
for name, material in materials.items():
    mat = material_dataset(material)
    ratio = material.shear_modulus_instantaneous / material.shear_modulus_long_term
    label = f"{CURVES[name][0]}, G(0)/G(∞) = {ratio:.0f}"
    ax1.loglog(mat["t"], mat["relaxation_modulus"] / material.shear_modulus_instantaneous, label=label)
    ax2.semilogx(mat["omega"], mat["tan_delta"], label=CURVES[name][0])
ax1.set(xlabel="t [s]", ylabel="G(t) / G(0) [-]", title="relaxation modulus")
ax1.legend(fontsize=8)
ax2.set(xlabel="ω [rad/s]", ylabel="tan δ [-]", title="loss factor")
fig.tight_layout()

# %%
# The steady speed curves: μ_app (and peak pressure, contact area and shift) against the Deborah
# number v τ/a0 (τ: the shortest retardation time; a0 = √(Rδ)), speed in m/s on the top axis.
# Each μ_app rises from zero, has one broad maximum (the elastomer's near 0.1 m/s, PMMA's near
# 10⁻⁸ m/s) and falls back to zero.
results = {}
for name, (label, speeds) in CURVES.items():
    results[name] = ds = vc.run_steady(cases[name], speeds)
    speed_curve_figure(ds)
    peak = int(np.argmax(ds["mu_app"].values))
    print(f"{label}: mu_app maximum {float(ds['mu_app'][peak]):.4f} at v = {speeds[peak]:.0e} m/s")

# %%
# The limits: the load needed to hold the approach climbs from Hertz with G(∞) (slow sliding, the
# material fully relaxed) to Hertz with G(0) (fast sliding, no time to relax).
fig, axes = plt.subplots(1, 2, figsize=(10, 3.5))
for ax, (name, (label, speeds)) in zip(axes, CURVES.items()):
    case, material, ds = cases[name], materials[name], results[name]
    problem = case.to_problem()
    approach = problem.normal.history(problem.time.t_end)  # what the steady states hold
    limits = [hertz_from_approach(approach, case.indenter.radius, g, material.poisson_ratio).load
              for g in (material.shear_modulus_long_term, material.shear_modulus_instantaneous)]
    ax.loglog(speeds, ds["load"], "o-", ms=4, label=f"viscontact, steady, {case.grid.n}²")
    for load, limit in zip(limits, ("Hertz, G(∞)", "Hertz, G(0)")):
        ax.axhline(load, color="k", ls="--", lw=0.8)
        ax.annotate(limit, (speeds[0], load), textcoords="offset points", xytext=(2, 4), fontsize=8)
    ax.set(xlabel="sliding speed v [m/s]", ylabel="load W [N]",
           title=f"{label}, held approach δ = {approach * 1e6:g} µm")
    ax.legend(loc="center right", fontsize=8)
    print(f"{label}: slow limit W / W_Hertz(G(inf)) = {float(ds['load'][0]) / limits[0]:.4f}; "
          f"fast limit W / W_Hertz(G(0)) = {float(ds['load'][-1]) / limits[1]:.4f}")
fig.tight_layout()
