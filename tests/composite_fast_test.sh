#!/usr/bin/env bash
# The composite's fast defaults (issue 28 item 6, docs/aerial_perspective.md "Cost"): segments camera -> surface
# march a count growing with their length, and the sky is marched at the corners and centre of 8x8 tiles and
# interpolated where the centre agrees. Seed 004's passes (gen_composite_scene, 320x180) composited three ways under
# validation, camera from flags with a narrow field of view (8 degrees: tiles of 0.36 degree, so the sky is
# interpolated; the sky pixels look 10-14 degrees up, the geometry keeps its positions):
#   fast   the defaults (no --max-steps)
#   march  every pixel its own march of the same count (--steps 32 --max-steps 32: the fast paths off, as before)
#   dense  every pixel its own march of 512 steps (the truth up to fp16)
# and compared layer by layer (composite_march_check: T and S = rayleigh + mie, geometry and sky pixels apart):
#   fast vs dense within the march's documented bound (|dT| 1.5e-3: three fp16 ulps below 1, S 1.5 %: the 32-step sky march's own error is
#   ~0.9 %), and fast vs march within 2e-3 relative in S and 1e-3 in T (the fast paths' own error: a few fp16 ulps).
#
#   composite_fast_test.sh VKSKY GEN_COMPOSITE_SCENE COMPOSITE_MARCH_CHECK
set -u
VKSKY=${1:?usage: composite_fast_test.sh VKSKY GEN_COMPOSITE_SCENE COMPOSITE_MARCH_CHECK}
GEN=${2:?}
CHECK=${3:?}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
"$GEN" "$work" 320 180 >/dev/null || { echo "FAIL: gen_composite_scene"; exit 1; }
CAM=(--camera-position -3.5,-8.5,218.8 --yaw -90 --pitch 10 --fov 8 --sun-elevation 20 --sun-azimuth -60)
run() {
    local out=$1; shift
    "$VKSKY" --composite "$work/beauty.exr" --position "$work/position.exr" "${CAM[@]}" --render "$work/$out.exr" \
        --validate "$@" 2>"$work/err" || fail "$out: exit $? ($(cat "$work/err"))"
    [ ! -s "$work/err" ] || fail "$out: stderr not empty: $(cat "$work/err")"
}
run fast
run march --steps 32 --max-steps 32
run dense --steps 512 --max-steps 512
[ $fails -eq 0 ] || exit 1
# The render's alpha and position say which pixels are geometry; the two-file inputs hold them as RGBA / RGB.
echo "fast vs dense:"
"$CHECK" "$work/fast.exr" "$work/dense.exr" "$work/render.exr" 1.5e-3 1.5e-2 || fail "fast composite vs the dense march"
echo "fast vs march (same count, every pixel marched):"
"$CHECK" "$work/fast.exr" "$work/march.exr" "$work/render.exr" 1e-3 2e-3 || fail "fast composite vs the per-pixel march"
echo "march vs dense (for reference):"
"$CHECK" "$work/march.exr" "$work/dense.exr" "$work/render.exr" 1 1
[ $fails -eq 0 ] || exit 1
echo "composite_fast_test: ok"
