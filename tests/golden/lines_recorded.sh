#!/usr/bin/env bash
# lines_recorded.sh ACTUAL RECORD WHAT: exits 0 when every line of ACTUAL is a line of RECORD
# (the golden digests' check), else prints WHAT and the lines that differ and exits 1. Shared by
# check_match_digests.sh and default_digests.sh.
set -euo pipefail
missing=$(grep -vxFf "$2" "$1" || true)
if [ -n "$missing" ]; then
  echo "$3 differ from the recorded digests:"
  echo "$missing"
  exit 1
fi
echo "$(wc -l <"$1") runs match the recorded digests"
