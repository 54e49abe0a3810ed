#!/usr/bin/env bash
# ctest golden.match_digests: re-runs match_digests.sh and requires every line it prints to be a
# line of the recorded match_digests.txt (same scene, options and PNG digest). Exits 77 (skip)
# when none of the scenes is present.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
actual=$(mktemp)
trap 'rm -f "$actual"' EXIT
"$here/match_digests.sh" "$@" >"$actual"
if [ ! -s "$actual" ]; then
  echo "no scene found: skipped"
  exit 77
fi
"$here/lines_recorded.sh" "$actual" "$here/match_digests.txt" "stereo match's outputs"
