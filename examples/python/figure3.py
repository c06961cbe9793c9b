"""The paper's figure 3 from the FBM theory: F, E_e and the energy rate of a uniform bundle, each over
its maximum, with x_p < x_c < x_m marked.  python3 figure3.py [OUT.png]"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

import rupture

dist = "uniform"
curves = rupture.fbm.curves(dist, points=1001)
maxima = rupture.fbm.theory(dist)
fig, ax = plt.subplots(figsize=(6, 4))
for column, label in [("force", "F / F_max"), ("elastic_energy", "E_e / E_e,max"), ("energy_rate", "ℰ / ℰ_max")]:
    ax.plot(curves["strain"], curves[column] / curves[column].max(), label=label)
for key in ("x_p", "x_c", "x_m"):
    ax.axvline(maxima[key], color="grey", linestyle=":")
    ax.annotate(key, (maxima[key], 1.03), ha="center")
ax.set_xlabel("strain x [1] (per N κ = 1)")
ax.set_ylabel("normalised value [1]")
ax.set_ylim(0, 1.1)
ax.legend(loc="lower center")
out = sys.argv[1] if len(sys.argv) > 1 else "figure3.png"
fig.savefig(out, dpi=120)
print(f"x_p = {maxima['x_p']:.4f}, x_c = {maxima['x_c']:.4f}, x_m = {maxima['x_m']:.4f} -> {out}")
