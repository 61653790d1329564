#!/usr/bin/env bash
# Run a campaign of crane_sim runs (docs/campaigns.md) with GNU parallel: the scenes of
# CAMPAIGN.yaml times the product of its grid, one CSV row per run appended to RESULTS.csv as it
# finishes. Resumable: runs already in RESULTS.csv are skipped, so a second call runs only what
# is missing (an interrupted campaign keeps every finished row).
# Usage: scripts/campaign.sh CAMPAIGN.yaml RESULTS.csv [--jobs N] [--sshloginfile FILE]
#   --jobs N             parallel runs per host (default: one per core)
#   --sshloginfile FILE  GNU parallel's list of hosts (":" is this machine); the repository
#                        and its build must be at the same path on every host
set -euo pipefail
export PYENV_VERSION=system   # the system python (python3-yaml)
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
usage() { echo "usage: scripts/campaign.sh CAMPAIGN.yaml RESULTS.csv [--jobs N] [--sshloginfile FILE]" >&2; exit 2; }
[ $# -ge 2 ] || usage
CAMPAIGN="$1" RESULTS="$2"
shift 2
PAR=()
while [ $# -gt 0 ]; do
  case "$1" in
    --jobs)
      [ $# -ge 2 ] && [[ "$2" =~ ^[1-9][0-9]*$ ]] || { echo "campaign: --jobs needs a positive integer" >&2; exit 2; }
      PAR+=(--jobs "$2"); shift 2 ;;
    --sshloginfile)
      [ $# -ge 2 ] && [ -r "$2" ] || { echo "campaign: --sshloginfile needs a readable file" >&2; exit 2; }
      PAR+=(--sshloginfile "$2"); shift 2 ;;
    *) echo "campaign: unknown option '$1'" >&2; usage ;;
  esac
done
command -v parallel >/dev/null || { echo "campaign: GNU parallel is missing (scripts/install_deps.sh)" >&2; exit 2; }
PY=/usr/bin/python3
LINES="$(mktemp)"
trap 'rm -f "$LINES"' EXIT
"$PY" "$ROOT/scripts/campaign.py" expand "$CAMPAIGN" "$RESULTS" >"$LINES"
[ -s "$RESULTS" ] || "$PY" "$ROOT/scripts/campaign.py" header >"$RESULTS"
TODO=$(wc -l <"$LINES")
echo "campaign: $TODO runs to do ($(($(wc -l <"$RESULTS") - 1)) already in $RESULTS)" >&2
if [ "$TODO" -gt 0 ]; then
  # Each run prints its row when it ends; parallel hands the rows back (also from ssh hosts) one
  # whole row at a time. A run that fails still gives its row (exit_status, message).
  parallel "${PAR[@]}" --halt never --line-buffer --arg-file "$LINES" --delimiter '\n' \
    "$PY" "$ROOT/scripts/campaign.py" run {} >>"$RESULTS"
fi
# The rows, those with a non-zero exit status, and the usage over the finished runs.
"$PY" "$ROOT/scripts/campaign.py" summary "$RESULTS" >&2
