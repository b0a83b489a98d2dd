# Plots K_I and K_II against time for every crack tip of an MPM run. Called by `rift run` as:
#   python3 - CRACK_TIPS_CSV OUTPUT_PNG TITLE   (this script on standard input)
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

series = {}
with open(sys.argv[1]) as f:
    for row in csv.DictReader(f):
        key = (int(row["crack"]), row["tip"])
        series.setdefault(key, []).append(row)
end = max((float(r["time"]) for rows in series.values() for r in rows), default=1.0)
scale, unit = (1e6, "µs") if end < 1e-3 else (1e3, "ms") if end < 1.0 else (1.0, "s")
fig, ax = plt.subplots(figsize=(7, 4.2))
for (crack, tip), rows in sorted(series.items()):
    t = [float(r["time"]) * scale for r in rows]
    ax.plot(t, [float(r["K_I"]) / 1e6 for r in rows], "-", label=f"crack {crack} {tip}: $K_I$")
    ax.plot(t, [float(r["K_II"]) / 1e6 for r in rows], "--", label=f"crack {crack} {tip}: $K_{{II}}$")
ax.axhline(0.0, color="0.6", lw=0.6)
ax.set_xlabel(f"time ({unit})")
ax.set_ylabel("stress intensity factor (MPa √m)")
ax.set_title(sys.argv[3] if len(sys.argv) > 3 else "crack tips")
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=150)
