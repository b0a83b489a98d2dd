# Plots the final damage field of a 2D rift run. Called by `rift run` as:
#   python3 - FINAL_STATE_CSV OUTPUT_PNG TITLE   (this script on standard input)
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

data = np.loadtxt(sys.argv[1], delimiter=",", skiprows=1, ndmin=2)
x, y, damage = data[:, 0], data[:, 1], data[:, 2]
width = x.max() - x.min() if x.size > 1 else 1.0
height = y.max() - y.min() if y.size > 1 else 1.0
aspect = height / width if width > 0 else 1.0
fig, ax = plt.subplots(figsize=(8, max(2.5, 8 * aspect)))
n = max(len(x), 1)
size = max(0.2, 4.0e4 / n)
sc = ax.scatter(x * 1e3, y * 1e3, c=damage, s=size, cmap="inferno_r", vmin=0.0, vmax=1.0, marker="s", linewidths=0)
ax.set_aspect("equal")
ax.set_xlabel("x (mm)")
ax.set_ylabel("y (mm)")
ax.set_title(sys.argv[3] if len(sys.argv) > 3 else "damage")
fig.colorbar(sc, ax=ax, label="damage", shrink=0.8)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=150)
