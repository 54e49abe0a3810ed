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
missing=$(grep -vxFf "$here/match_digests.txt" "$actual" || true)
if [ -n "$missing" ]; then
  echo "stereo match output differs from the recorded digests:"
  echo "$missing"
  exit 1
fi
echo "$(wc -l <"$actual") runs match the recorded digests"
