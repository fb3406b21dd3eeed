#!/usr/bin/env bash
# The example host (examples/sky_host.c) offscreen on this machine's device (lavapipe in CI), validation and
# synchronization validation on (any message fails it), then its picture against `vksky --render` of the same view
# and the CPU reference (tests/example_host_check.c).
#   example_host_test.sh HOST_BINARY VKSKY CHECKER
set -u
HOST=${1:?usage: example_host_test.sh HOST VKSKY CHECKER}
VKSKY=${2:?}
CHECK=${3:?}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
W=96 H=64
"$HOST" --validate --offscreen $W $H "$work/host.exr" || { echo "FAIL: the example host failed (status $?)"; exit 1; }
# The same frame as a PNG through the host's tone map (checked against the EXR's pixels below).
"$HOST" --validate --offscreen $W $H "$work/host.png" || { echo "FAIL: the example host (PNG) failed (status $?)"; exit 1; }
# Bad output names: exit 2, one line, nothing written.
"$HOST" --offscreen $W $H "$work/host.tiff" 2>"$work/err"; rc=$?
[ $rc -eq 2 ] && [ "$(wc -l <"$work/err")" -eq 1 ] && [ ! -e "$work/host.tiff" ] ||
    { echo "FAIL: --offscreen OUT.tiff: status $rc, stderr: $(cat "$work/err")"; exit 1; }
# The same view by the CLI (examples/sky_host_scene.h): 200 m up, north, 5 degrees up, fov 60, the sun at azimuth
# 180 and 25 degrees, the lesson's units, the "high" preset with its sky marched per pixel at full size, no bloom.
"$VKSKY" --render "$work/cli.exr" --width $W --height $H --altitude 0.2 --yaw 0 --pitch 5 --fov 60 \
    --sun-azimuth 180 --sun-elevation 25 --units relative --quality high --sky-mode march --render-scale 1 \
    --no-bloom --validate || { echo "FAIL: vksky --render failed"; exit 1; }
"$CHECK" "$work/host.exr" "$work/cli.exr" "$work/host.png"
