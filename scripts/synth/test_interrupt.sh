#!/bin/sh
# test_interrupt.sh SYNTH_PY PYTHON: a long `synth.py estimate` shows progress lines (elapsed
# time and the Yosys pass) and, stopped by SIGTERM, exits 130 with one error line naming the pass
# and leaves a partial report in its --out file (ctest synth.progress_and_partial_report).
set -u
synth=$1 python=$2
rm -rf interrupt && mkdir interrupt && cd interrupt || exit 1
STEREO_SYNTH_PROGRESS_SECONDS=1 "$python" "$synth" estimate --target xilinx --ndisp 4 --window 3 \
    --width 64 --height 48 --work work --out partial.json 2> err.txt &
pid=$!
waited=0
until grep -q "^synth.py: yosys [0-9]* s: pass " err.txt; do
    sleep 1
    waited=$((waited + 1))
    if [ $waited -gt 300 ] || ! kill -0 $pid 2> /dev/null; then
        echo "no progress line within ${waited} s:"; cat err.txt; kill $pid 2> /dev/null; exit 1
    fi
done
kill -TERM $pid
wait $pid
status=$?
cat err.txt
[ $status -eq 130 ] || { echo "exit status $status, expected 130"; exit 1; }
tail -n 1 err.txt | grep -q "^synth.py: error: interrupted after [0-9]* s in yosys pass .*; partial report in partial.json$" \
    || { echo "the last line is not the interruption"; exit 1; }
grep -q '"partial": true' partial.json && grep -q '"last_pass": "[0-9]' partial.json \
    && grep -q '"command": "estimate"' partial.json && test -s work/yosys.log \
    || { echo "no partial report:"; cat partial.json; exit 1; }
echo "progress shown, partial report kept"
