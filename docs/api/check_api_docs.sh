#!/bin/sh
# docs.api_reference (label docs): build the API reference (target api_docs) and fail on any
# Doxygen warning, or when a page that the installed headers must produce is missing or says
# nothing (the filter of comment_filter.py stopped working).
# usage: check_api_docs.sh BUILD_DIR API_DOCS_DIR
set -eu
build=$1 out=$2
cmake --build "$build" --target api_docs
if [ -s "$out/warnings.txt" ]; then
  echo "docs.api_reference: $(wc -l < "$out/warnings.txt") Doxygen warning line(s):"
  head -40 "$out/warnings.txt"
  exit 1
fi
for page in index.html structstereo_1_1MatchConfig.html classstereo_1_1MatcherRegistry.html \
            matcher_8hpp.html; do
  [ -f "$out/html/$page" ] || { echo "docs.api_reference: html/$page missing"; exit 1; }
done
# The prose comments reached the pages: the file's description and a member's.
grep -q "One interface for every matcher" "$out/html/matcher_8hpp.html" \
  || { echo "docs.api_reference: matcher.hpp's description is not on its page"; exit 1; }
grep -q "ndisp, window, sigma" "$out/html/structstereo_1_1MatchConfig.html" \
  || { echo "docs.api_reference: MatchConfig's member documentation is missing"; exit 1; }
echo "docs.api_reference: $(ls "$out/html" | wc -l) files in $out/html, no Doxygen warning"
