"""
Seed Fig. 9: from partial slip to gross sliding
===============================================

The seed's Table 3: frictional sliding (μ_f = 0.3) under a held approach. Cases 1 and 2 slide from
t = 0 (without and with friction); in cases 3 and 4 the tangential displacement first grows at
0.17 and 0.017 a0/τ: the contact splits into a stick and a slip zone, and gross sliding begins when
the stick zone vanishes (at about 0.1τ and 0.6τ). The figure shows the shear traction of cases 3
and 4 against μ_f p with their stick zones, and the pressure of all four, at 0, 0.1, 0.5, 1 and 1.5τ.

Here on a 64² grid (``--n 64``) instead of the seed's 256².
"""

import tempfile
from pathlib import Path

import matplotlib.image as mpimg
import matplotlib.pyplot as plt
import xarray as xr

from viscontact.reproduce import reproduce

out = Path(tempfile.mkdtemp())
files = reproduce("fig9", out, n=64)

# %%
# When gross sliding began in each case (``t_gross_sliding`` in the result files).
for path in sorted(p for p in files if p.suffix == ".nc"):
    with xr.open_dataset(path) as ds:
        tau = float(ds["retardation_time"])
        print(f"{path.stem}: gross sliding from t = {float(ds['t_gross_sliding']) / tau:.3f} τ")

# %%
# The figure as ``viscontact reproduce fig9 --n 64`` writes it.
for png in sorted(p for p in files if p.suffix == ".png"):
    image = mpimg.imread(png)
    fig = plt.figure(figsize=(image.shape[1] / 150, image.shape[0] / 150), dpi=150)
    fig.figimage(image)
