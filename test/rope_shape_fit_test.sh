#!/usr/bin/env bash
# scripts/rope_shape_fit.py against shapes whose fit is known, on a rope of 61 nodes: bent as a
# cubic plus sin(3 pi s) (in the span of cubics and three sines: residual at round-off; two sines
# leave it), and as a cubic with a 1 cm wave on its lowest 12 nodes only (fitted whole it leaves
# the wave; with the lower fifth free the upper part is a cubic again in its own coordinate);
# malformed input refused by name.
# Usage: rope_shape_fit_test.sh SOURCE_DIR
set -uo pipefail
ROOT="${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}"
export PYENV_VERSION=system
FIT="/usr/bin/python3 $ROOT/scripts/rope_shape_fit.py"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

/usr/bin/python3 - "$TMP" <<'EOF'
import math, sys
out = sys.argv[1]
n = 61
def write(name, sine, lower_wave):
    with open(out + "/" + name, "w") as f:
        f.write("t,node,x,y,z\n")
        for k in range(3):
            t = 0.5 * k
            for i in range(n):
                s = i / (n - 1)
                x = 0.2 * s**3 - 0.1 * s + (1 + k) * (0.05 * (1 - t) + 0.01) * s * s
                if sine:
                    x += 0.05 * (1 + k) * math.sin(3 * math.pi * s)
                if lower_wave and i > 48:  # the lowest 12 nodes: a wave the upper shapes lack
                    x += 0.01 * math.sin(7 * math.pi * s)
                f.write("%g,%d,%.15g,%.15g,%.15g\n" % (t, i, x, 0.3 * s * s, 60.0 * (1 - s)))
write("smooth.csv", True, False)
write("lower_wave.csv", False, True)
EOF

# largest residual [m] of the line for FRACTION free (the field before the closing unit)
largest() { awk -v f="$2" '$1 == "lower" && $2 + 0 == f + 0 {print $(NF - 1) + 0}' <<<"$1"; }
below() { awk -v a="$1" -v b="$2" 'BEGIN {exit !(a < b)}'; }

out=$($FIT "$TMP/smooth.csv" 0 --sines 3 --stride 1 --free 0) || fail "smooth fit exited $?"
r=$(largest "$out" 0)
below "${r:-1}" 1e-9 || fail "a cubic plus sin(3 pi s) with 3 sines left ${r:-nothing} m: $out"

out=$($FIT "$TMP/smooth.csv" 0 --sines 2 --stride 1 --free 0) || fail "two-sine fit exited $?"
r=$(largest "$out" 0)
below 1e-3 "${r:-0}" || fail "sin(3 pi s) of 15 cm fitted by 2 sines left only ${r:-nothing} m"

out=$($FIT "$TMP/lower_wave.csv" 0 --sines 3 --stride 1 --free 0,0.2) ||
  fail "lower-wave fit exited $?"
r0=$(largest "$out" 0)
r2=$(largest "$out" 0.2)
below 1e-4 "${r0:-0}" || fail "the lower wave fitted whole left only ${r0:-nothing} m: $out"
below "${r2:-1}" 1e-9 || fail "with the lower fifth free the upper part left ${r2:-nothing} m: $out"

printf 't,node,x\n0,0,1\n' > "$TMP/bad.csv"
if msg=$($FIT "$TMP/bad.csv" 0 2>&1); then
  fail "a CSV without y and z accepted: $msg"
else
  grep -q "bad.csv" <<<"$msg" || fail "the refusal does not name the file: $msg"
fi
if msg=$($FIT "$TMP/smooth.csv" 0 --free 1.5 2>&1); then
  fail "--free 1.5 accepted: $msg"
else
  grep -q -- "--free" <<<"$msg" || fail "the refusal does not name --free: $msg"
fi

echo "rope_shape_fit_test: $failures failed"
[ "$failures" -eq 0 ]
