#!/usr/bin/python3
"""Table of the hard-case runs of scripts/hard_cases.sh (docs/stability.md).

Usage: stability_report.py DIR   (DIR holds <case>.csv and <case>.log from crane_sim run)

Per case: exit status, simulated end time, energy drift (last - first) and largest rise over
the start (J), max constraint error (m), max tension over breaking force (the run summary's
peak_tension_ratio, over every step; the rows' largest tension_ratio for a log without it), subdomains,
energy-consistent steps (slack/taut switches of the tension-only rope), halved steps, wall seconds
of the integration.
"""
import csv
import glob
import os
import re
import sys


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    print("| case | exit | t_end s | energy drift J | max energy rise J | max constraint m | "
          "max tension / breaking | subdomains | energy-consistent steps | halved steps | wall s |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for log in sorted(glob.glob(os.path.join(sys.argv[1], "*.log"))):
        name = os.path.splitext(os.path.basename(log))[0]
        text = open(log).read()
        status = re.search(r"exit_status=(\d+)", text)
        summary = re.search(r"wall_s=(\S+) .*subdomains=(\d+)", text)
        halved = re.search(r"halved_steps=(\d+)", text)
        consistent = re.search(r"energy_consistent_steps=(\d+)", text)
        peak = re.search(r"peak_tension_ratio=(\S+)", text)
        rows = []
        path = os.path.join(sys.argv[1], name + ".csv")
        if os.path.exists(path):
            with open(path) as f:
                rows = list(csv.DictReader(f))
        if not rows:
            print("| %s | %s | - | - | - | - | - | - | - | - | - |" % (name, status.group(1) if status else "?"))
            continue
        e = [float(r["energy"]) for r in rows]
        print("| %s | %s | %.2f | %.4g | %.4g | %.2g | %.3f | %s | %s | %s | %s |" % (
            name, status.group(1) if status else "?", float(rows[-1]["t"]), e[-1] - e[0],
            max(e) - e[0], max(float(r["constraint_error"]) for r in rows),
            float(peak.group(1)) if peak else max(float(r["tension_ratio"]) for r in rows),
            summary.group(2) if summary else "-", consistent.group(1) if consistent else "0",
            halved.group(1) if halved else "0",
            summary.group(1) if summary else "-"))
        if status and status.group(1) != "0":
            reason = [l for l in text.splitlines() if "failure" in l or "error" in l]
            if reason:
                print("|   | %s | | | | | | | | | |" % reason[0].replace("|", "/"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
