#!/usr/bin/env bash
# scripts/site_launch.py (docs/site.md): the launch file it writes for the shipped site, with
# crane_b on its own <machine>, parses in roslaunch and names one node per crane and
# the monitor; a crane name not in the site is refused.
# Run in the workspace's environment (ctest: devel/env.sh).
set -uo pipefail
export PYENV_VERSION=system
export PATH="/usr/bin:$PATH"
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
T="$(mktemp -d)"
trap 'rm -rf "$T"' EXIT
fail() { echo "site_launch_test: FAILED: $*"; exit 1; }
/usr/bin/python3 "$ROOT/scripts/site_launch.py" "$ROOT/config/sites/two_t8036.yaml" \
  --host crane_b=127.0.0.1 >"$T/site.launch" || fail "generator"
roslaunch --nodes "$T/site.launch" >"$T/nodes" 2>"$T/err" || fail "roslaunch: $(cat "$T/err")"
for n in /crane_a/crane_sim_node /crane_b/crane_sim_node /site_monitor /rviz; do
  grep -qx "$n" "$T/nodes" || fail "node $n missing: $(cat "$T/nodes")"
done
grep -q 'name="host" value="127.0.0.1"' "$T/site.launch" || fail "no host for crane_b"
if /usr/bin/python3 "$ROOT/scripts/site_launch.py" "$ROOT/config/sites/two_t8036.yaml" \
     --host crane_c=127.0.0.1 >/dev/null 2>"$T/err2"; then fail "unknown crane accepted"; fi
grep -q "crane_c" "$T/err2" || fail "the unknown crane is not named"
echo "site_launch_test: passed"
