#!/bin/sh
# corrupt_and_run.sh VECTORS SCRATCH TESTBENCH: the testbench must pass on a copy of VECTORS and
# fail on two corruptions of it: one hex digit of expected.hex changed (a mismatch at that beat)
# and expected.hex one beat short (refused before the run).
set -u
vectors=$1 scratch=$2 testbench=$3
run() {  # run NAME: the testbench on $scratch/NAME; its output in $scratch/NAME.log
    "$testbench" +vectors="$scratch/$1" > "$scratch/$1.log" 2>&1
}
rm -rf "$scratch" && mkdir -p "$scratch" || exit 1
for name in intact digit short; do
    cp -r "$vectors" "$scratch/$name" || exit 1
done
if ! run intact; then
    echo "the intact copy failed"; cat "$scratch/intact.log"; exit 1
fi
# Line 1001 is beat 999 (the first line is a comment): its top data digit (certainty) changes.
awk 'NR == 1001 { d = substr($0, 2, 1); $0 = substr($0, 1, 1) (d == "f" ? "0" : "f") substr($0, 3) } 1' \
    "$vectors/expected.hex" > "$scratch/digit/expected.hex"
if cmp -s "$vectors/expected.hex" "$scratch/digit/expected.hex"; then
    echo "the corruption changed nothing"; exit 1
fi
sed '$d' "$vectors/expected.hex" > "$scratch/short/expected.hex"
status=0
if run digit || ! grep -q "FAIL: beat 999 " "$scratch/digit.log"; then
    echo "a changed digit of beat 999 was not reported:"; cat "$scratch/digit.log"; status=1
fi
if run short || ! grep -q "must hold" "$scratch/short.log"; then
    echo "a short expected.hex was not refused:"; cat "$scratch/short.log"; status=1
fi
[ $status -ne 0 ] || echo "both corruptions failed the testbench, the intact copy passed"
exit $status
