#!/usr/bin/python3
"""Plot a campaign's damage per hour against load and radius (docs/fatigue.md "Campaigns").

Usage: scripts/plot_campaign.py RESULTS.csv OUT.png
RESULTS.csv from scripts/campaign.sh over runs that set payload.mass and trolley.radius (a
grid or samples). One column per hot spot: its Miner damage per simulated hour of each run
against the payload (top, coloured by radius) and against the radius (bottom, coloured by
payload), on a log scale. Runs that failed or made no lift are left out (counted on stderr).
Needs Debian's python3-matplotlib.
"""
import csv
import re
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def value(overrides, key):
    m = re.search(r"(?:^| )" + re.escape(key) + r"=([-+0-9.eE]+)", overrides)
    return float(m.group(1)) if m else None


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    runs, skipped = [], 0
    with open(sys.argv[1], newline="") as f:
        for r in csv.DictReader(f):
            mass, radius = value(r["overrides"], "payload.mass"), value(r["overrides"], "trolley.radius")
            if r["exit_status"] != "0" or r["lifts"] in ("", "0") or mass is None or radius is None:
                skipped += 1
                continue
            hours = float(r["sim_s"]) / 3600.0
            rate = {k: float(v) / hours for k, v in (p.split("=") for p in r["damage"].split())}
            runs.append((mass, radius, rate))
    if not runs:
        sys.exit(f"plot_campaign: no run of {sys.argv[1]} sets payload.mass and trolley.radius "
                 "and made a lift")
    spots = list(runs[0][2])
    fig, axes = plt.subplots(2, len(spots), figsize=(3.6 * len(spots), 6.4), squeeze=False,
                             sharey=True)
    mass = [r[0] / 1000.0 for r in runs]
    radius = [r[1] for r in runs]
    for j, name in enumerate(spots):
        rate = [r[2][name] for r in runs]
        top = axes[0][j].scatter(mass, rate, c=radius, s=10, cmap="viridis")
        bottom = axes[1][j].scatter(radius, rate, c=mass, s=10, cmap="plasma")
        axes[0][j].set_title(name)
        axes[0][j].set_xlabel("payload [t]")
        axes[1][j].set_xlabel("pick radius [m]")
        for ax in (axes[0][j], axes[1][j]):
            ax.set_yscale("log")
            ax.grid(True, which="both", alpha=0.3)
    axes[0][0].set_ylabel("damage per hour of the cycle")
    axes[1][0].set_ylabel("damage per hour of the cycle")
    fig.colorbar(top, ax=axes[0].tolist(), label="pick radius [m]")
    fig.colorbar(bottom, ax=axes[1].tolist(), label="payload [t]")
    fig.suptitle(f"{len(runs)} pick-and-place cycles: Miner damage per hour (S-N slope 3)")
    fig.savefig(sys.argv[2], dpi=110)
    print(f"plot_campaign: {len(runs)} runs plotted, {skipped} left out", file=sys.stderr)


if __name__ == "__main__":
    main()
