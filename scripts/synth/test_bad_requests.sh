#!/bin/sh
# test_bad_requests.sh SYNTH_PY PYTHON: bad input to estimate, the sweeps and merge is one error
# line on stderr, nothing on stdout and a non-zero exit, before any Yosys run (ctest label synth).
set -u
synth=$1 python=$2
folder=bad_requests_test
mkdir -p $folder && cd $folder || exit 1
echo '[{"width": 16, "height": 12, "ndisp": 2, "window": 3}]' > configs.json
echo '{"target": "ice40", "config": {}}' > not_a_point.json
echo '{"partial": true, "command": "estimate", "options": {}}' > partial.json
echo 'not json' > text.json
echo '{"points": []}' > sweep.json
status=0
while read -r request; do
    rm -f out.txt err.txt
    # shellcheck disable=SC2086
    if "$python" "$synth" $request > out.txt 2> err.txt; then
        echo "accepted: $request"; status=1; continue
    fi
    if [ "$(wc -l < err.txt)" -ne 1 ] || ! grep -q '^synth.py: error: ' err.txt || [ -s out.txt ]; then
        echo "not one error line: $request"; cat err.txt out.txt; status=1; continue
    fi
    echo "refused: $request: $(cat err.txt)"
done <<'REQUESTS'
estimate --target xilinx --top stereo_nosuch_top
estimate --target ice40 --top axil
estimate --target xilinx --top synth --constant-kernel
sweep --targets xilinx --configs configs.json --out s.json --jobs 0
sweep --targets xilinx --configs configs.json --out s.json --jobs -2
sweep --targets xilinx --configs configs.json --out s.json --jobs many
sweep --targets xilinx --configs configs.json --out s.json --top nosuch
lanes-sweep --width 16 --height 12 --window 3 --points 2:2 --out s.json --jobs 0
merge m.json not_a_point.json
merge m.json partial.json
merge m.json text.json
merge m.json sweep.json
merge m.json no_such_file.json
REQUESTS
test ! -e s.json && test ! -e m.json || { echo "a refused request wrote a file"; status=1; }
exit $status
