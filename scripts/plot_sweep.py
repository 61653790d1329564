#!/usr/bin/python3
"""Plot crane_sim sweep results: payload error against wall time, one panel per scene.

Usage: scripts/plot_sweep.py OUT.png SWEEP.csv [SWEEP.csv ...]
Full-order runs (time steps), reduced runs (modes, delta, time step; the chord's frame and the
paper's fixed frame apart) and the pendulum rope are drawn with their Pareto fronts (no other setting of the same model is both faster and more
accurate); rungs on a rigid structure are crosses; the paper's setting (half the rope DOF) is
starred. Needs Debian's python3-matplotlib.
"""
import csv
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def pareto(points):
    """Points (wall, err) not dominated by a faster and at least as accurate one."""
    front, best = [], float("inf")
    for w, e in sorted(points):
        if e < best:
            front.append((w, e))
            best = e
    return front


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    scenes = {}
    for path in sys.argv[2:]:
        with open(path) as f:
            for r in csv.DictReader(f):
                scenes.setdefault(r["scene"], []).append(r)
    n = len(scenes)
    cols = 2 if n > 1 else 1
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(6.5 * cols, 4.8 * rows), squeeze=False)
    floor = 1e-9
    for ax, (scene, rs) in zip(axes.flat, sorted(scenes.items())):
        ref = [r for r in rs if r["model"] == "reference"]
        rigid = [r for r in rs if r.get("structure_model") == "rigid"]
        if rigid:
            ax.scatter([float(r["wall_s"]) for r in rigid],
                       [max(float(r["payload_error_max"]), floor) for r in rigid], c="k",
                       marker="x", s=30, label="rigid structure (any rope)")
        for model, frame, colour, marker in (
                ("full", None, "tab:blue", "o"), ("reduced", "corotational", "tab:orange", "s"),
                ("reduced", "fixed", "tab:purple", "D"), ("pendulum", None, "tab:green", "^")):
            pts = [(float(r["wall_s"]), max(float(r["payload_error_max"]), floor), r)
                   for r in rs if r["model"] == model and r.get("structure_model") != "rigid"
                   and (frame is None or r.get("subdomain_frame", "fixed") == frame)]
            if not pts:
                continue
            label = "pendulum rope" if model == "pendulum" else f"{model} order"
            if model == "reduced":
                label = ("reduced, chord's frame" if frame == "corotational"
                         else "reduced, fixed frame (paper)")
                model_label = label
            else:
                model_label = model
            ax.scatter([p[0] for p in pts], [p[1] for p in pts], c=colour, marker=marker, s=22,
                       alpha=0.6, label=label)
            front = pareto([(p[0], p[1]) for p in pts])
            ax.plot([p[0] for p in front], [p[1] for p in front], c=colour, lw=1.5,
                    label=f"{model_label}: Pareto front")
            for w, e, r in pts:
                if model in ("full", "pendulum"):
                    ax.annotate(f"{float(r['time_step']) * 1e3:g} ms", (w, e), fontsize=7,
                                xytext=(3, 3), textcoords="offset points")
                elif int(r["rope_modes"]) > 100:
                    fixed = r.get("subdomain_frame", "fixed") == "fixed"
                    ax.scatter([w], [e], c="red", marker="*" if not fixed else "P", s=160, zorder=5,
                               label="paper: 50 % rope modes" + (", fixed frame" if fixed else
                                                                 ", chord's frame"))
        if ref:
            ax.axvline(float(ref[0]["wall_s"]), c="grey", ls=":", lw=1,
                       label=f"reference ({float(ref[0]['time_step']) * 1e3:g} ms)")
        duration = 20.0
        ax.axvline(duration, c="k", ls="--", lw=0.8, label="real time (20 s)")
        ax.axhline(0.15, c="tab:red", ls="--", lw=0.8, label="paper budget 0.15 m")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time of the 20 s run [s] (integration only, one core)")
        ax.set_ylabel("max payload error against the reference [m]")
        ax.set_title(scene)
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = axes.flat[0].get_legend_handles_labels()
    uniq = dict(zip(labels, handles))
    fig.legend(uniq.values(), uniq.keys(), loc="lower center", ncol=4, fontsize=8)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    fig.savefig(sys.argv[1], dpi=110)


if __name__ == "__main__":
    main()
