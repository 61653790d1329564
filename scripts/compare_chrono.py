#!/usr/bin/python3
"""Compare a crane_sim time series of the Project Chrono rope case with Chrono's solution.

Usage: scripts/compare_chrono.py SERIES.csv [CHRONO.csv]
SERIES.csv from `crane_sim run config/scenes/rope_pendulum_chrono.yaml --out SERIES.csv`;
CHRONO.csv defaults to test/data/chrono_rope_pendulum/caseA_dt1e-3.csv (its README says how it
was made).
Prints the number of common output times and the max |tip x| and |tip z| differences [m].
"""
import csv
import os
import sys


def rows(path, tkey):
    with open(path) as f:
        return {round(float(r[tkey]), 6): r for r in csv.DictReader(f)}


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    chrono = sys.argv[2] if len(sys.argv) == 3 else os.path.join(
        root, "test", "data", "chrono_rope_pendulum", "caseA_dt1e-3.csv")
    c, m = rows(chrono, "t"), rows(sys.argv[1], "t")
    ts = sorted(set(c) & set(m))
    if not ts:
        sys.exit("no common output times")
    dx = max(abs(float(c[t]["tip_x"]) - float(m[t]["payload_x"])) for t in ts)
    dz = max(abs(float(c[t]["tip_z"]) - float(m[t]["payload_z"])) for t in ts)
    print(f"common_times,{len(ts)}\nmax_tip_x_difference,{dx:.6g}\nmax_tip_z_difference,{dz:.6g}")


if __name__ == "__main__":
    main()
