#!/bin/sh
# slam_bad_yaml.sh STEREO EUROC_FOLDER OUT: `stereo slam` on the EuRoC clip with hostile
# rectification files must fail at once with one error line and exit 2 (expect_error.sh):
#   hang.yaml  the 19 bytes on which OpenCV 4.6's YAML parser spins forever;
#   huge.yaml  the real file declaring 100000 x 100000 images (maps of 40 GB before the fix).
# Exits 77 (skip) without the data.
set -u
stereo=$1
euroc=$2
out=$3
here=$(dirname "$0")
real=$euroc/stereo_rectification_opencv.yaml
[ -f "$real" ] || { echo "no EuRoC clip under $euroc: skipped"; exit 77; }
mkdir -p "$out"
printf '%%YAML:1.\n---[]R:.-' >"$out/hang.yaml"
sed -e 's/^image_width:.*/image_width: 100000/' -e 's/^image_height:.*/image_height: 100000/' \
    "$real" >"$out/huge.yaml"
for calib in hang huge; do
    timeout 20 sh "$here/expect_error.sh" 2 - "$stereo" slam "$euroc" --calib "$out/$calib.yaml" \
        --frames 0:2 || exit 1
done
