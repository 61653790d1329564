#!/usr/bin/python3
"""Markdown tables from crane_sim sweep CSVs (docs/accuracy-vs-time.md).

Usage: scripts/sweep_report.py [--headline | --ladder] SWEEP.csv [SWEEP.csv ...]
--headline prints one table row per scene (docs/accuracy-vs-time.md's headline table).
--ladder prints the fidelity ladder: each rung's cost and error, cheapest first, and
the cheapest rung within 1 mm and within the paper's 0.15 m.
Per scene: every setting, then the headline ratios: the paper's point (half the rope DOF at the
scene's step and delta) against full order at the same step; reduced against full at the same
step (1 ms); and at equal accuracy, the fastest setting of each model whose max payload error is
at most 1 mm, plus the fastest reduced setting within 0.02 m.
"""
import csv
import sys


def flexible(rows, model):
    """Rows of one rope model on the scene's own structure (the ladder's rigid rungs apart)."""
    return [r for r in rows if r["model"] == model and r.get("structure_model", "modal") != "rigid"]


def rung(r):
    s = r.get("structure_model", "modal")
    st = "rigid structure" if s == "rigid" else f"{s} structure ({r['structure_modes']} modes)"
    rope = {"pendulum": "pendulum rope", "full": "full ANCF rope"}.get(r["model"])
    if rope is None:
        rope = f"reduced rope ({r['rope_modes']} modes, delta {float(r['delta']):g} m{frame(r)})"
    return f"{rope}, {st}"


def frame(r):
    """', fixed frame' for the paper's frame where a sweep has both (the chord's frame unmarked)."""
    return ", fixed frame" if r.get("subdomain_frame") == "fixed" else ""


def ladder(paths):
    for path in paths:
        with open(path) as f:
            rows = list(csv.DictReader(f))
        ref = [r for r in rows if r["model"] == "reference"][0]
        print(f"### {rows[0]['scene']}\n")
        print(f"Reference: full order at {float(ref['time_step']) * 1e3:g} ms, {float(ref['wall_s']):.3g} s.\n")
        print("| rung | step [ms] | wall [s] | rtf | payload error [m] | rope RMS error [m] | jib tip error [m] |")
        print("| --- | --- | --- | --- | --- | --- | --- |")
        pend = [r for r in rows if r["model"] == "pendulum" or r.get("structure_model") == "rigid"]
        best = {}
        for m in ("full", "reduced"):  # the fastest flexible setting of each model per accuracy
            for lim in (1e-3, 0.15):
                f = fastest(flexible(rows, m), lim)
                if f:
                    best[id(f)] = f
        shown = pend + list(best.values())
        for r in sorted(shown, key=lambda r: float(r["wall_s"])):
            print(f"| {rung(r)} | {float(r['time_step']) * 1e3:g} | {float(r['wall_s']):.3g} | "
                  f"{float(r['rtf']):.3g} | {float(r['payload_error_max']):.2e} | "
                  f"{float(r['rope_rms_max']):.2e} | {float(r['jib_tip_error_max']):.2e} |")
        cand = [r for r in rows if r["model"] != "reference"]
        for lim, what in ((1e-3, "1 mm"), (0.15, "0.15 m")):
            f = fastest(cand, lim)
            if f:
                print(f"\nCheapest within {what} payload error: {rung(f)} at "
                      f"{float(f['time_step']) * 1e3:g} ms, {float(f['wall_s']):.3g} s "
                      f"({float(ref['wall_s']) / float(f['wall_s']):.0f}x under the reference).")
        print()


def fastest(rows, limit):
    ok = [r for r in rows if float(r["payload_error_max"]) <= limit]
    return min(ok, key=lambda r: float(r["wall_s"])) if ok else None


def describe(r):
    if r["model"] == "full":
        return f"full, {float(r['time_step']) * 1e3:g} ms"
    return (f"reduced, {r['rope_modes']} modes, delta {float(r['delta']):g} m, "
            f"{float(r['time_step']) * 1e3:g} ms, {r['structure_modes']} structure modes{frame(r)}")


def headline(paths):
    for path in paths:
        with open(path) as f:
            rows = list(csv.DictReader(f))
        sc = rows[0]["scene"]
        full, red = flexible(rows, "full"), flexible(rows, "reduced")
        f1 = min(full, key=lambda r: float(r["time_step"]))
        w1 = float(f1["wall_s"])
        paper = [r for r in red if int(r["rope_modes"]) > 100]
        p = paper[0]
        pf = [r for r in paper if r.get("subdomain_frame") == "fixed"]
        s = [r for r in red if r["time_step"] == f1["time_step"] and r["rope_modes"] == "10"
             and abs(float(r["delta"]) - 0.05) < 1e-9 and r.get("subdomain_frame") != "fixed"][0]
        ff, fr, f2 = fastest(full, 1e-3), fastest(red, 1e-3), fastest(red, 0.02)

        def d(r):
            if r["model"] == "full":
                return f"{float(r['time_step']) * 1e3:g} ms"
            return (f"{r['rope_modes']} modes, delta {float(r['delta']):g} m, "
                    f"{float(r['time_step']) * 1e3:g} ms{frame(r)}")

        fixed = (f"{float(pf[0]['wall_s']):.3g} s, error {float(pf[0]['payload_error_max']):.1e} m: "
                 f"**{w1 / float(pf[0]['wall_s']):.2f}x**" if pf and pf[0] is not p else "-")
        print(f"| {sc} | error {float(p['payload_error_max']):.1e} m (rope RMS "
              f"{float(p['rope_rms_max']):.1e} m); {float(p['wall_s']):.3g} s against {w1:.3g} s: "
              f"**{w1 / float(p['wall_s']):.2f}x** | {fixed} | {float(s['wall_s']):.3g} s, error "
              f"{float(s['payload_error_max']):.1e} m: **{w1 / float(s['wall_s']):.3g}x** | full "
              f"{d(ff)}: {float(ff['wall_s']):.3g} s ({float(ff['payload_error_max']):.1e} m); reduced "
              f"{d(fr)}: {float(fr['wall_s']):.3g} s ({float(fr['payload_error_max']):.1e} m): "
              f"**{float(ff['wall_s']) / float(fr['wall_s']):.2f}x** | {d(f2)}: rtf "
              f"**{float(f2['rtf']):.0f}**, error {float(f2['payload_error_max']):.1e} m |")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    if sys.argv[1] == "--headline":
        headline(sys.argv[2:])
        return
    if sys.argv[1] == "--ladder":
        ladder(sys.argv[2:])
        return
    for path in sys.argv[1:]:
        with open(path) as f:
            rows = list(csv.DictReader(f))
        scene = rows[0]["scene"]
        print(f"### {scene}\n")
        print("| model | frame | step [ms] | rope modes | delta [m] | structure | wall [s] | rtf | "
              "subdomains | mode updates [s] | payload error [m] | rope RMS error [m] |")
        print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
        for r in rows:
            st = r.get("structure_model", "modal")
            st = "rigid" if st == "rigid" else f"{st} {r['structure_modes']}"
            print(f"| {r['model']} | {r.get('subdomain_frame', '-')} | {float(r['time_step']) * 1e3:g} | {r['rope_modes']} | "
                  f"{float(r['delta']):g} | {st} | {float(r['wall_s']):.3g} | "
                  f"{float(r['rtf']):.3g} | {r['subdomains']} | {float(r['mode_updates_s']):.3g} | "
                  f"{float(r['payload_error_max']):.2e} | {float(r['rope_rms_max']):.2e} |")
        full, red = flexible(rows, "full"), flexible(rows, "reduced")
        step = min(float(r["time_step"]) for r in full)
        full1 = [r for r in full if float(r["time_step"]) == step][0]
        w1 = float(full1["wall_s"])
        print()
        paper = [r for r in red if int(r["rope_modes"]) > 100]
        for p in paper:
            print(f"- Paper's point ({describe(p)}): payload error {float(p['payload_error_max']):.2e} m, "
                  f"rope RMS {float(p['rope_rms_max']):.2e} m; {float(p['wall_s']):.3g} s against "
                  f"{w1:.3g} s at full order and the same step: {w1 / float(p['wall_s']):.2g}x.")
        same = [r for r in red if float(r["time_step"]) == step and int(r["rope_modes"]) == 10
                and abs(float(r["delta"]) - 0.05) < 1e-12]
        if same:
            s = same[0]
            print(f"- Same step, 10 modes, delta 0.05 m: {float(s['wall_s']):.3g} s, payload error "
                  f"{float(s['payload_error_max']):.2e} m: {w1 / float(s['wall_s']):.3g}x faster than full.")
        ff, fr = fastest(full, 1e-3), fastest(red, 1e-3)
        if ff and fr:
            print(f"- Equal accuracy (payload error <= 1 mm): fastest full is {describe(ff)} "
                  f"({float(ff['wall_s']):.3g} s, {float(ff['payload_error_max']):.1e} m); fastest reduced is "
                  f"{describe(fr)} ({float(fr['wall_s']):.3g} s, {float(fr['payload_error_max']):.1e} m): "
                  f"{float(ff['wall_s']) / float(fr['wall_s']):.3g}x.")
        f2 = fastest(red, 0.02)
        if f2:
            print(f"- Fastest reduced within 0.02 m: {describe(f2)}, rtf {float(f2['rtf']):.3g} "
                  f"(payload error {float(f2['payload_error_max']):.2e} m).")
        print()


if __name__ == "__main__":
    main()
