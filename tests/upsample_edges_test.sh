#!/usr/bin/env bash
# The tone map's class-aware upsample (issue 16: render scale with an edge-aware upsample): a frame at
# --render-scale 0.5 against the same frame at scale 1, both under --validate, bloom and the sun's disc off (the
# disc's limb darkening varies too fast across a pixel for a fixed bound). The views put the horizon across the
# image (sunset, looking at it; tilted down from 10 km), fragment and compute tone maps. upsample_edges requires
# every pixel of the half-size frame within TOL of one of its full-size 3x3 neighbours (relative luminance, floored
# at 5 % of the frame's peak). TOL = 5 %: next to the horizon the sky brightens by up to 10 % a pixel, and a
# half-size texel there holds the sky half a pixel nearer the horizon than any full-size sky pixel (measured: 3.7 %
# at sunset, 2.9 % from 10 km); a bilinear blend of sky and ground misses by far more (the bilinear upsample,
# measured: 490 % and 8.9 %).
# VKSKY_HALF: another vksky for the half-size renders (run with a build whose upsample is plain bilinear, it fails).
set -u
VKSKY=${1:?usage: upsample_edges_test.sh VKSKY UPSAMPLE_EDGES}
CHECK=${2:?usage: upsample_edges_test.sh VKSKY UPSAMPLE_EDGES}
TOL=0.05
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
cases=(
  "sunset   --width 160 --height 90 --sun-elevation 3 --pitch 0 --fov 12 --quality cpu"
  "high     --width 161 --height 91 --altitude 10 --pitch -5 --fov 40 --sun-elevation 40 --quality cpu --post-pass compute"
)
for c in "${cases[@]}"; do
  set -- $c
  name=$1; shift
  for s in 0.5 1; do
    if ! "${VKSKY_HALF:-$VKSKY}" --validate --no-bloom --no-sun-disc "$@" --render-scale $s --render "$work/$name-$s.exr" > "$work/log" 2>&1; then
      echo "FAIL: $name: render at scale $s failed:"; cat "$work/log"; fails=$((fails + 1)); continue 2
    fi
  done
  if "$CHECK" "$work/$name-0.5.exr" "$work/$name-1.exr" $TOL; then echo "ok: $name"
  else echo "FAIL: $name: the half-size frame has a value the full-size one lacks nearby"; fails=$((fails + 1)); fi
done
[ $fails -eq 0 ] && echo "upsample_edges: all cases pass" || echo "upsample_edges: $fails failure(s)"
exit $((fails != 0))
