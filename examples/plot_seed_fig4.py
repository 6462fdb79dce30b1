"""
Seed Fig. 4: frictionless sliding at three speeds
=================================================

The seed's Table 1 cases: a sphere slides without friction over the Zener half-space under a held
load of 0.148 N at v = 0.4, 0.8 and 1.2 a0/τ for 4τ. ``viscontact reproduce fig4`` runs the three
shipped cases and draws the paper's figure: the pressure along y = 0 at 0, 0.5, 1 and 2 τ (the peak
moves to the leading edge and the contact shifts forward with time and speed) and the apparent
friction μ_app(t), which rises with speed and is steady after about 3τ.

Here on a 64² grid (``--n 64``) instead of the seed's 256²: a quick preview.
"""

import tempfile
import warnings
from pathlib import Path

import matplotlib.image as mpimg
import matplotlib.pyplot as plt

from viscontact.reproduce import reproduce

out = Path(tempfile.mkdtemp())
with warnings.catch_warnings(record=True) as caught:  # shown below as the command line shows them
    warnings.simplefilter("always")
    files = reproduce("fig4", out, n=64)
for warning in caught:
    print(f"viscontact: warning: {warning.message}")
print("\n".join(p.name for p in files))

# %%
# The figure as ``viscontact reproduce fig4 --n 64`` writes it.
png = next(p for p in files if p.suffix == ".png")
image = mpimg.imread(png)
fig = plt.figure(figsize=(image.shape[1] / 150, image.shape[0] / 150), dpi=150)
_ = fig.figimage(image)
