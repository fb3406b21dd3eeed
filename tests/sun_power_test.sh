#!/usr/bin/env bash
# tests/sun_power_test.sh VKSKY EXR_PROBE: the sun's power does not depend on the image's resolution. Where a texel
# is wider than the sun's disc (a small or wide-angle image, a render scale below 1) the sky pass draws the disc
# at the texel's size with its radiance scaled by the ratio of solid angles (sky_common.glsl, sun_drawn_radius);
# point-sampled at its true size such a sun vanishes (a 240x135 frame at render scale 0.5 lost it). The power is
# sum over pixels of (frame - the same frame with --no-sun-disc) x the pixel's solid angle, around the sun at the
# centre of the view; a 960x540 frame (the disc 7 pixels across) is the measure, every coarser frame must match it
# within 8 %, at two sun positions relative to the pixel grid. Every render under --validate, bloom off.
set -u
VKSKY=${1:?usage: sun_power_test.sh VKSKY EXR_PROBE}
PROBE=${2:?usage: sun_power_test.sh VKSKY EXR_PROBE}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The LUT cache on in the test's own directory: 28 renders of three LUT settings, and the checks are about the sun's
# disc in the sky pass, not the LUT passes (tests/lib/own_lut_cache.sh).
# shellcheck source=lib/own_lut_cache.sh
source "$(dirname "$0")/lib/own_lut_cache.sh"
own_lut_cache "$work"
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
FOV=40
# power W H EXTRA...: the sun's power in the frame (luminance x sr), the sun near the view axis.
power() {
    local w=$1 h=$2; shift 2
    for disc in on off; do
        local flag=""; [ $disc = off ] && flag=--no-sun-disc
        "$VKSKY" --validate --no-bloom --width "$w" --height "$h" --fov $FOV --sun-elevation 30 --sun-azimuth 0 \
            "$@" $flag --render "$work/$disc.exr" >"$work/log" 2>&1 || { fail "render $w x $h $* failed: $(cat "$work/log")"; echo nan; return; }
    done
    # pixels within 2.2 degrees of the centre (the widest drawn disc here: 0.71 x 1.2 degrees), or 3.6 texels: the
    # disc that carries the sun's power (photometric units, the default; issue 32) reaches 3 texels from the sun
    local texel r
    texel=$(awk -v h="$h" -v f=$FOV 'BEGIN { d = atan2(0, -1) / 180; print 2 * sin(f / 2 * d) / cos(f / 2 * d) / h }')
    r=$(awk -v t="$texel" 'BEGIN { d = atan2(0, -1) / 180; a = 2.2 * d; if (3.6 * t > a) a = 3.6 * t; r = int(a / t) + 1; print r }')
    local args=() x y
    for ((y = h / 2 - r; y <= h / 2 + r; y++)); do for ((x = w / 2 - r; x <= w / 2 + r; x++)); do
        [ $x -ge 0 ] && [ $y -ge 0 ] && [ $x -lt "$w" ] && [ $y -lt "$h" ] && args+=("$x" "$y"); done; done
    # (to files first: a process substitution's exit status is lost)
    "$PROBE" "$work/on.exr" "${args[@]}" >"$work/on.px" && "$PROBE" "$work/off.exr" "${args[@]}" >"$work/off.px" ||
        { fail "exr_pixels $w x $h: exit $?"; echo nan; return; }
    paste "$work/on.px" "$work/off.px" |
        awk -v t="$texel" '{ s += (0.2126 * ($1 - $4) + 0.7152 * ($2 - $5) + 0.0722 * ($3 - $6)) } END { printf "%.6g\n", s * t * t }'
}
for pos in "--yaw 0 --pitch 30" "--yaw 0.21 --pitch 30.13"; do
    # shellcheck disable=SC2086
    reference=$(power 960 540 --quality medium $pos)
    echo "sun power, $pos: 960x540 $reference"
    for c in "240 135 --quality medium" "240 135 --quality medium --render-scale 0.5" "120 68 --quality medium" \
             "60 34 --quality medium" "240 135 --quality lesson --render-scale 0.5" "240 135"; do
        # shellcheck disable=SC2086
        p=$(power $c $pos)
        awk -v p="$p" -v q="$reference" 'BEGIN { exit !(q > 0 && p / q > 0.92 && p / q < 1.08) }' ||
            fail "$pos, $c: the sun's power $p differs from the 960x540 frame's $reference by more than 8 %"
        echo "  $c: $p"
    done
done
[ $fails -eq 0 ] && echo "sun_power: the sun's power is the same at every resolution within 8 %"
exit $((fails > 0))
