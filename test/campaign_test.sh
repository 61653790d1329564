#!/usr/bin/env bash
# scripts/campaign.sh on local slots (docs/campaigns.md): a 2 x 2 grid of short runs, every row
# present once with exit status 0 and finite figures; a second call runs nothing; a removed row
# runs again; a campaign with an unknown key is refused naming it; seeded samples of a lift
# carry its usage figures and the summary adds them up. Usage: campaign_test.sh
# [CRANE_SIM] (default: the build's).
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[ $# -ge 1 ] && export CRANE_SIM="$1"
T="$(mktemp -d)"
trap 'rm -rf "$T"' EXIT
fail() { echo "campaign_test: FAILED: $*"; exit 1; }
cat >"$T/c.yaml" <<YAML
scenes: [$ROOT/config/scenes/rope_pendulum_chrono.yaml]
duration: 0.2
set: ["rope.elements=6", "initial.mode=equilibrium"]
grid:
  initial.swing_deg: [2, 10]
  rope.model: [full, pendulum]
YAML
"$ROOT/scripts/campaign.sh" "$T/c.yaml" "$T/r.csv" --jobs 2 2>"$T/log1" || fail "first call: $(cat "$T/log1")"
rows() { awk 'NR > 1' "$T/r.csv" | wc -l; }
[ "$(rows)" -eq 4 ] || fail "expected 4 rows, got $(rows): $(cat "$T/r.csv")"
[ "$(cut -d, -f1 "$T/r.csv" | sort | uniq -d | wc -l)" -eq 0 ] || fail "duplicate ids"
/usr/bin/python3 - "$T/r.csv" <<'PY' || fail "row contents"
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for r in rows:
    assert r["exit_status"] == "0", r
    assert abs(float(r["sim_s"]) - 0.2) < 1e-9, r
    swing = float(r["max_swing_deg"])
    assert math.isfinite(swing) and swing > 1.0, r
    assert math.isfinite(float(r["max_tension_ratio"])), r
# the swing's start shows in the figure: 10 deg runs swing about 10 deg, 2 deg about 2
for r in rows:
    want = 10.0 if "initial.swing_deg=10" in r["overrides"] else 2.0
    assert abs(float(r["max_swing_deg"]) - want) < 0.5, r
PY
"$ROOT/scripts/campaign.sh" "$T/c.yaml" "$T/r.csv" 2>"$T/log2" || fail "second call"
grep -q "0 runs to do" "$T/log2" || fail "second call ran again: $(cat "$T/log2")"
[ "$(rows)" -eq 4 ] || fail "second call changed the rows"
sed -i '3d' "$T/r.csv"   # forget one run: only it runs again
"$ROOT/scripts/campaign.sh" "$T/c.yaml" "$T/r.csv" 2>"$T/log3" || fail "third call"
grep -q "1 runs to do" "$T/log3" || fail "expected 1 run to do: $(cat "$T/log3")"
[ "$(rows)" -eq 4 ] || fail "after the resumed run: $(rows) rows"
printf 'scenes: [t8036_combination1]\ngird: {payload.mass: [1]}\n' >"$T/bad.yaml"
if "$ROOT/scripts/campaign.sh" "$T/bad.yaml" "$T/bad.csv" 2>"$T/log4"; then fail "bad campaign accepted"; fi
grep -q "gird" "$T/log4" || fail "the unknown key is not named: $(cat "$T/log4")"
# Seeded samples of a lift: each row's usage figures (one lift, k_Q of its mass, four hot
# spots' damage), drawn the same on a second expansion; the summary over the runs.
cat >"$T/s.yaml" <<YAML
scenes: [$ROOT/config/scenes/t8036_lift_off_slow.yaml]
duration: 8
set: ["rope.elements=10"]
samples: {count: 2, seed: 7, uniform: {payload.mass: [2000, 4000]}}
YAML
"$ROOT/scripts/campaign.sh" "$T/s.yaml" "$T/s.csv" --jobs 2 2>"$T/log5" || fail "samples: $(cat "$T/log5")"
/usr/bin/python3 "$ROOT/scripts/campaign.py" expand "$T/s.yaml" >"$T/e1"
/usr/bin/python3 "$ROOT/scripts/campaign.py" expand "$T/s.yaml" >"$T/e2"
cmp -s "$T/e1" "$T/e2" || fail "the samples differ between two expansions"
/usr/bin/python3 - "$T/s.csv" "$T/log5" <<'PY' || fail "usage columns: $(cat "$T/s.csv" "$T/log5")"
import csv, math, re, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2, rows
masses = []
for r in rows:
    assert r["exit_status"] == "0", r
    m = float(re.search(r"payload\.mass=([0-9.e+]+)", r["overrides"]).group(1))
    assert 2000 <= m <= 4000, r
    masses.append(m)
    assert r["lifts"] == "1", r
    kq = (m / 12500.0) ** 3
    assert abs(float(r["k_q"]) - kq) < 1e-5 * kq, (r, kq)
    assert float(r["max_phi_2"]) > 1.0, r
    damage = dict(p.split("=") for p in r["damage"].split())
    assert set(damage) == {"mast_foot", "mast_top", "jib_root", "counter_jib_root"}, r
    assert all(float(d) > 0 for d in damage.values()), r
assert masses[0] != masses[1], masses
log = open(sys.argv[2]).read()
assert "campaign usage: 2 runs" in log and "2 lifts" in log, log
kq = sum((m / 12500.0) ** 3 for m in masses) / 2
got = float(re.search(r"k_Q ([0-9.e+-]+)", log).group(1))
assert abs(got - kq) < 1e-3 * kq, (got, kq)
total = sum(float(dict(p.split("=") for p in r["damage"].split())["mast_foot"]) for r in rows)
got = float(re.search(r"mast_foot damage ([0-9.e+-]+), ([0-9.e+-]+) per hour", log).group(1))
assert abs(got - total) < 1e-3 * total, (got, total)
PY
printf 'scenes: [t8036_combination1]\nsamples: {count: 2, uniform: {payload.mass: [5, 1]}}\n' >"$T/bad2.yaml"
if "$ROOT/scripts/campaign.sh" "$T/bad2.yaml" "$T/bad2.csv" 2>"$T/log6"; then fail "bad samples accepted"; fi
grep -q "samples.uniform.payload.mass" "$T/log6" || fail "the bad samples key is not named: $(cat "$T/log6")"
echo "campaign_test: passed"
