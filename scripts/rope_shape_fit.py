#!/usr/bin/python3
"""How well smooth shapes hold a rope's computed shape (docs/accuracy-vs-time.md, "Attempts"):
reads a nodes CSV (`crane_sim run ... --nodes N.csv`: t, node, x, y, z), and for the output times
from FROM on (every STRIDE-th) fits each component of the upper part of the rope (its nodes from
the top down, the lowest FREE fraction left out) by least squares on cubics and SINES sines of
the node index over that part. Prints, per free fraction, the median and the largest over the
times of the fit's residual RMS over the fitted nodes [m]. A small residual with a part left free
says a rope reduced above and kept whole below could hold the run; a residual that stays with
the lower part free says the shapes missing run along the whole rope.

    scripts/rope_shape_fit.py N.csv FROM [--sines 6] [--stride 5] [--free 0,0.05,0.1,0.2,0.3,0.5]
"""
import argparse
import sys

import numpy as np


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("nodes", help="nodes CSV of crane_sim run --nodes")
    p.add_argument("start", type=float, help="first output time fitted [s]")
    p.add_argument("--sines", type=int, default=6, help="sines beside the cubics (default 6)")
    p.add_argument("--stride", type=int, default=5, help="fit every STRIDE-th output time")
    p.add_argument("--free", default="0,0.05,0.1,0.2,0.3,0.5",
                   help="fractions of the nodes left free at the rope's lower end")
    a = p.parse_args()
    try:
        free = [float(f) for f in a.free.split(",")]
    except ValueError:
        sys.exit("--free: comma-separated fractions in [0, 1), got '%s'" % a.free)
    if any(not 0.0 <= f < 1.0 for f in free) or a.sines < 0 or a.stride < 1:
        sys.exit("--free fractions in [0, 1), --sines >= 0 and --stride >= 1")
    try:
        d = np.loadtxt(a.nodes, delimiter=",", skiprows=1, ndmin=2)
    except (OSError, ValueError) as e:
        sys.exit("%s: not a nodes CSV (t,node,x,y,z): %s" % (a.nodes, e))
    if d.shape[1] != 5 or not np.isfinite(d).all():
        sys.exit("%s: not a nodes CSV (t,node,x,y,z)" % a.nodes)
    nodes = int(d[:, 1].max()) + 1
    if d.shape[0] % nodes:
        sys.exit("%s: a time with a node missing" % a.nodes)
    positions = d[:, 2:5].reshape(-1, nodes, 3)
    times = d[::nodes, 0]
    chosen = np.flatnonzero(times >= a.start)[::a.stride]
    if chosen.size == 0:
        sys.exit("%s: no output time from %g s" % (a.nodes, a.start))
    for f in free:
        k = int(round(nodes * (1.0 - f)))
        if k < 4 + a.sines:
            print("lower %.2f free: %d nodes left, too few for %d shapes" % (f, k, 4 + a.sines))
            continue
        s = np.linspace(0.0, 1.0, k)  # the fitted part's own coordinate, 0 at the top
        shapes = np.array([s**j for j in range(4)] +
                          [np.sin(np.pi * j * s) for j in range(1, a.sines + 1)]).T
        residual = []
        for i in chosen:
            part = positions[i, :k, :]
            c, *_ = np.linalg.lstsq(shapes, part, rcond=None)
            r = part - shapes @ c
            residual.append(np.sqrt((r**2).sum(axis=1).mean()))
        residual = np.array(residual)
        print("lower %.2f free (%d of %d nodes): residual RMS median %.3g m, largest %.3g m" %
              (f, nodes - k, nodes, np.median(residual), residual.max()))


if __name__ == "__main__":
    main()
