#!/usr/bin/python3
"""Plot payload x, cab dx and jib-tip dz histories of crane_sim time series (docs/cli.md CSV).

Usage: scripts/plot_series.py [--columns=a,b,...] OUT.png SERIES.csv [SERIES.csv ...]
       (one line per file; --columns picks other CSV columns, one panel each)
"""
import csv
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    args = sys.argv[1:]
    panels = (("payload_x", "payload x [m]"), ("cab_dx", "cab dx [m]"),
              ("jib_tip_dz", "jib tip dz [m]"))
    if args and args[0].startswith("--columns="):
        panels = tuple((c, c) for c in args.pop(0).split("=", 1)[1].split(",") if c)
    if len(args) < 2:
        sys.exit(__doc__)
    fig, axes = plt.subplots(len(panels), 1, figsize=(8, 8), sharex=True, squeeze=False)
    axes = axes[:, 0]
    for path in args[1:]:
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
    fig.savefig(args[0], dpi=100)


if __name__ == "__main__":
    main()
