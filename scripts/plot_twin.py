#!/usr/bin/python3
"""Plot the twin's paths (docs/twin.md) from the CSV twin.test writes with record_csv:=FILE:
top view of the real payload, the twin's estimate and forecasts made every 10 s, and the
estimate's and 10 s forecasts' errors against time. Prints the figures the docs quote.

Usage: plot_twin.py RUN.csv OUT.png
"""
import bisect
import csv
import math
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    truth, est, fc = [], [], {}
    with open(sys.argv[1]) as f:
        for r in csv.DictReader(f):
            p = (float(r["t"]), float(r["x"]), float(r["y"]), float(r["z"]))
            if r["kind"] == "truth":
                truth.append(p)
            elif r["kind"] == "estimate":
                est.append(p)
            elif r["kind"] == "forecast":
                fc.setdefault(float(r["made_at"]), []).append(p)
    if not truth or not est:
        sys.exit("plot_twin: no truth or estimate rows in " + sys.argv[1])
    truth.sort()
    est.sort()
    ts = [p[0] for p in truth]

    def at(t):
        i = bisect.bisect_left(ts, t)
        if i == 0 or i >= len(ts):
            return None
        a, b = truth[i - 1], truth[i]
        w = (t - a[0]) / (b[0] - a[0]) if b[0] > a[0] else 0.0
        return [a[k] + w * (b[k] - a[k]) for k in (1, 2, 3)]

    est_err = [(e[0], math.dist(e[1:], at(e[0]))) for e in est if at(e[0])]
    # Converged: the time after which the estimate stays within 0.2 m.
    converged = 0.0
    for t, e in est_err:
        if e >= 0.2:
            converged = t
    late = sorted(e for t, e in est_err if t >= 30.0)
    fc_err = {10.0: [], 30.0: []}
    for t0, poses in fc.items():
        if t0 < 30.0:
            continue
        for ahead, store in fc_err.items():
            p = min(poses, key=lambda p: abs(p[0] - (t0 + ahead)))
            tr = at(p[0])
            if tr and abs(p[0] - t0 - ahead) < 0.3:
                store.append((t0, math.dist(p[1:], tr)))
    print("estimate within 0.2 m of the real payload from t = %.1f s on" % converged)
    if late:
        print("estimate after 30 s: median %.3f m, max %.3f m" % (late[len(late) // 2], late[-1]))
    for ahead, errs in fc_err.items():
        if errs:
            e = sorted(x for _, x in errs)
            print("forecasts made after 30 s, %g s ahead: median %.3f m, max %.3f m (%d)" %
                  (ahead, e[len(e) // 2], e[-1], len(e)))

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 5.5))
    ax1.plot([p[1] for p in truth], [p[2] for p in truth], "k-", lw=2.5, label="real crane (full order)")
    ax1.plot([p[1] for p in est], [p[2] for p in est], "-", color="tab:blue", lw=1,
             label="twin's estimate (reduced)")
    shown = 0
    for t0 in sorted(fc):
        if t0 >= 10.0 * shown - 0.5 and shown < 6:
            poses = fc[t0]
            ax1.plot([p[1] for p in poses], [p[2] for p in poses], "--", color="tab:orange",
                     lw=1.2, label="30 s forecasts (every 10 s)" if shown == 0 else None)
            ax1.plot(poses[0][1], poses[0][2], "o", color="tab:orange", ms=4)
            shown += 1
    ax1.set_xlabel("x [m]")
    ax1.set_ylabel("y [m]")
    ax1.set_aspect("equal", adjustable="datalim")
    ax1.set_title("Payload seen from above (slewing, trolley in)")
    ax1.legend(loc="best", fontsize=8)
    ax2.semilogy([t for t, _ in est_err], [max(e, 1e-3) for _, e in est_err], color="tab:blue",
                 lw=1, label="estimate error")
    for ahead, marker in ((10.0, "o"), (30.0, "s")):
        errs = fc_err[ahead]
        if errs:
            ax2.semilogy([t + ahead for t, _ in errs], [e for _, e in errs], marker, ms=4,
                         label="forecast error %g s ahead (at its time)" % ahead)
    ax2.axhline(0.2, color="gray", ls=":", lw=1)
    ax2.axhline(0.3, color="gray", ls="--", lw=1)
    ax2.set_xlabel("t [s] since the twin's start")
    ax2.set_ylabel("distance to the real payload [m]")
    ax2.set_title("Errors (5 Hz payload measurements, 5 cm noise)")
    ax2.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
