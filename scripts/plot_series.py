#!/usr/bin/python3
"""Plot payload x, cab dx and jib-tip dz histories of crane_sim time series (docs/cli.md CSV).

Usage: scripts/plot_series.py OUT.png SERIES.csv [SERIES.csv ...]   (one line per file)
"""
import csv
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    panels = (("payload_x", "payload x [m]"), ("cab_dx", "cab dx [m]"),
              ("jib_tip_dz", "jib tip dz [m]"))
    fig, axes = plt.subplots(len(panels), 1, figsize=(8, 8), sharex=True)
    for path in sys.argv[2:]:
        with open(path) as f:
            rows = list(csv.DictReader(f))
        t = [float(r["t"]) for r in rows]
        for ax, (key, label) in zip(axes, panels):
            ax.plot(t, [float(r[key]) for r in rows], lw=1.0,
                    label=os.path.splitext(os.path.basename(path))[0])
            ax.set_ylabel(label)
            ax.grid(True, alpha=0.3)
    axes[0].legend()
    axes[-1].set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(sys.argv[1], dpi=100)


if __name__ == "__main__":
    main()
