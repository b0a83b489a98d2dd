# Bar chart of the damage histogram of a rift run (share of particles per damage interval of 0.1,
# like Table 5.2 / Figure 5.11 of the hydraulic-fracture thesis). Called by `rift run` as:
#   python3 - DAMAGE_HISTOGRAM_CSV OUTPUT_PNG TITLE   (this script on standard input)
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

with open(sys.argv[1]) as f:
    rows = list(csv.DictReader(f))
labels = [f"{float(r['damage_from']):.1f}-{float(r['damage_to']):.1f}" for r in rows]
percent = [float(r["percent"]) for r in rows]
fig, ax = plt.subplots(figsize=(7, 4))
ax.bar(range(len(rows)), percent, color="#b5523b")
ax.set_xticks(range(len(rows)))
ax.set_xticklabels(labels, rotation=45, ha="right")
ax.set_xlabel("damage")
ax.set_ylabel("particles (%)")
ax.set_title(sys.argv[3] if len(sys.argv) > 3 else "damage histogram")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=150)
