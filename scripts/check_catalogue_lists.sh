#!/bin/sh
# check_catalogue_lists.sh [SOURCE_DIR]: fails when the product code lists costs, methods or
# engines by hand, or decides a property of one by comparing its name, instead of asking the
# catalogue (model/include/stereo/catalogue.hpp, docs/architecture.md; issue 44). Looks at the
# code part of each line (comments are free to name rows) of app/, model/, sim/, hls/, io/,
# robot/, python/module.cpp and scripts/synth/synth.py. The experiments (experiments/) are left
# out on purpose: an evaluation names the rows it compares.
set -eu
root=${1:-$(dirname "$0")/..}
cd "$root"
cost='(ad|census|lcdm|zncc)'
method='(pipeline|edges|hierarchical|sparse|vertical|diagonal|asw)'
engine='(model|fast|naive|float|hls|rtl|full-search)'
q="[\"']"
# Two names of one kind side by side (a hand-written list), or a cost, method or engine variable
# compared with a name.
lists="$q$cost$q\s*,\s*$q$cost$q|$q$method$q\s*,\s*$q$method$q|$q$engine$q\s*,\s*$q$engine$q"
compares="(cost|method|engine)(\(\))?\s*(==|!=)\s*$q($cost|$method|$engine)$q"
found=$(find app model sim hls io robot python/module.cpp scripts/synth/synth.py \
            \( -name '*.cpp' -o -name '*.hpp' -o -name '*.py' \) \
            ! -name 'catalogue.hpp' ! -name 'catalogue.cpp' -print |
        sort | while read -r file; do
            # The code part of each line: C++ and Python comments removed.
            sed -e 's|//.*$||' -e 's|^\s*#.*$||' "$file" |
                grep -nE "$lists|$compares" | sed "s|^|$file:|" || true
        done)
if [ -n "$found" ]; then
    echo "costs, methods or engines named by hand outside the catalogue (ask stereo/catalogue.hpp):"
    echo "$found"
    exit 1
fi
echo "no hand-written lists of costs, methods or engines outside the catalogue"
