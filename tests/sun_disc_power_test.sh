#!/usr/bin/env bash
# tests/sun_disc_power_test.sh VKSKY: the sun's disc carries the sun's power (issue 32 item 3) in every projection
# and at several sizes: sum over pixels of (L_with_disc - L_without) x the pixel's exact solid angle, as luminance,
# is within 1 % of the header's vksky:sunIlluminanceAtCamera (the CPU reference's transmittance x the solar
# spectrum, computed apart from the image). tests/sun_disc_power.py does the sum. Sizes run from a texel wider than
# the sun (the disc drawn at the texel's scale) to a texel a third of its radius; sun positions off the pixel grid;
# both sky paths (march, sky-view lookup). Photometric units (the default), --exr-type float, bloom off (bloom
# spreads light on purpose), under --validate.
set -u
VKSKY=${1:?usage: sun_disc_power_test.sh VKSKY}
HERE=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The LUT cache on in the test's own directory: the checks are not about the LUT passes (tests/lib/own_lut_cache.sh).
# shellcheck source=lib/own_lut_cache.sh
source "$(dirname "$0")/lib/own_lut_cache.sh"
own_lut_cache "$work"
fails=0
# case: projection | flags (the sun, size, view)
cases=(
  "equirect|--projection equirect --width 96 --sun-elevation 33.3 --sun-azimuth 71"
  "equirect|--projection equirect --width 400 --sun-elevation 12.1 --sun-azimuth 200 --sky-mode skyview"
  "cubemap|--projection cubemap --width 40 --sun-elevation 41 --sun-azimuth 37"
  "cubemap|--projection cubemap --width 150 --sun-elevation 62 --sun-azimuth 300 --sky-mode skyview"
  "fisheye|--projection fisheye --width 64 --sun-elevation 25 --sun-azimuth 130"
  "fisheye|--projection fisheye --width 64 --sun-elevation 40 --sun-azimuth 130 --altitude 10"
  "fisheye|--projection fisheye --width 210 --sun-elevation 55.5 --sun-azimuth 10 --sky-mode skyview"
  "perspective|--width 96 --height 54 --fov 60 --yaw 92 --pitch 28 --sun-elevation 30.2 --sun-azimuth 90"
  "perspective|--width 240 --height 135 --fov 8 --yaw 44.7 --pitch 20.1 --sun-elevation 20 --sun-azimuth 45 --sky-mode skyview"
)
for c in "${cases[@]}"; do
  kind=${c%%|*} args=${c#*|}
  fov=75
  [[ $args =~ --fov\ ([0-9.]+) ]] && fov=${BASH_REMATCH[1]}
  for disc in on off; do
    flag=""; [ $disc = off ] && flag=--no-sun-disc
    # shellcheck disable=SC2086 # the case's flags are word-split on purpose
    "$VKSKY" --validate --quiet --no-bloom --render-scale 1 --exr-type float $args $flag --render "$work/$disc.exr" \
      >"$work/log" 2>&1 || { echo "FAIL: render $args $flag: $(cat "$work/log")"; fails=$((fails + 1)); continue 2; }
  done
  /usr/bin/python3 "$HERE/sun_disc_power.py" "$kind" "$work/on.exr" "$work/off.exr" "$fov" || {
    echo "FAIL: $kind $args: the disc's integral is more than 1 % from vksky:sunIlluminanceAtCamera"; fails=$((fails + 1)); }
done
# Tiny images: a texel wider than the view's distance to the sun (the disc's shape capped at 0.5 rad texels) renders
# finite, non-negative pixels that hold the disc's light (more than the sky alone).
for size in "1 1" "3 3" "7 3"; do
  read -r w h <<<"$size"
  for disc in on off; do
    flag=""; [ $disc = off ] && flag=--no-sun-disc
    "$VKSKY" --validate --quiet --no-bloom --width "$w" --height "$h" --exr-type float $flag --render "$work/t$disc.exr" \
      >"$work/log" 2>&1 || { echo "FAIL: tiny render $w x $h $flag: $(cat "$work/log")"; fails=$((fails + 1)); }
  done
  /usr/bin/python3 - "$work/ton.exr" "$work/toff.exr" <<'PY' || { echo "FAIL: tiny $w x $h: disc pixels not finite or not brighter"; fails=$((fails + 1)); }
import sys
import numpy as np
import OpenImageIO as oiio
on, off = (np.asarray(oiio.ImageBuf(p).get_pixels(oiio.FLOAT))[..., :3] for p in sys.argv[1:3])
sys.exit(0 if np.all(np.isfinite(on)) and np.all(on >= 0) and on.sum() > off.sum() else 1)
PY
done
[ $fails -eq 0 ] && echo "sun_disc_power: every projection's disc within 1 % of the sun's illuminance at the camera"
exit $((fails > 0))
