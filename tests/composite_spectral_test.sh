#!/usr/bin/env bash
# --composite in spectral colour (issue 32; docs/aerial_perspective.md "Spectral colour"), every run validated:
#  1. gen_composite_scene's render at sunset (sun +2 deg, where RGB's colour is far off), composited with --spectral 24
#     and with --spectral 0 at the same LUT numerics (the multi-scattering LUT's 64 steps: the default 20 leave 3 %
#     in the blue at these wavelengths, docs/aerial_perspective.md);
#  2. composite_spectral_check: both against the 48-wavelength spectral CPU reference at four geometry pixels
#     (in-scattering within 2 % relative, transmittance within 0.02; RGB at least twice as far off);
#  3. composite_check: the coverage identity on every pixel of the spectral composite, and its sky pixels (the sun's
#     disc among them) equal to a plain spectral render of the same camera (the still's own summation:
#     app/runs/spectral_host.c); the RGB composite's sky pixels equal to a plain RGB render's, the disc included;
#  4. --quality auto picks the spectral setting for a sunset composite (said on stdout, recorded in the header's
#     scene) and keeps RGB at noon, byte for byte --spectral 0's;
#  5. --aovs in spectral colour: the top level the plain spectral render's, the layers summed as the composite's.
# Usage: composite_spectral_test.sh VKSKY GEN_COMPOSITE_SCENE COMPOSITE_SPECTRAL_CHECK COMPOSITE_CHECK
set -u
VKSKY=${1:?usage: composite_spectral_test.sh VKSKY GEN_COMPOSITE_SCENE COMPOSITE_SPECTRAL_CHECK COMPOSITE_CHECK}
GEN=${2:?} SPECTRAL_CHECK=${3:?} CHECK=${4:?}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
S=$work/scene
mkdir -p "$S"
"$GEN" "$S" 64 36 >/dev/null || { echo "FAIL: gen_composite_scene"; exit 1; }
SUNSET=(--sun-elevation 2 --sun-azimuth -60)
# The sun (+2 deg, 60 deg left of north) is in the frame: the sky pixels' comparison covers its disc, drawn by the
# composite as by the sky pass (at least a texel wide); the reference's geometry pixels are away from it.
LUTS=(--multiscatter-steps 64 --lut-format f32)

# 1-2: against the spectral reference.
"$VKSKY" --composite "$S/render.exr" --render "$work/spectral.exr" "${SUNSET[@]}" "${LUTS[@]}" --spectral 24 \
    --validate 2>"$work/err" || fail "--spectral 24 composite: exit $?: $(head -c 300 "$work/err")"
[ -s "$work/err" ] && fail "--spectral 24 composite: stderr: $(head -c 300 "$work/err")"
"$VKSKY" --composite "$S/render.exr" --render "$work/rgb.exr" "${SUNSET[@]}" "${LUTS[@]}" --spectral 0 \
    --validate 2>"$work/err" || fail "--spectral 0 composite: exit $?: $(head -c 300 "$work/err")"
"$SPECTRAL_CHECK" "$S/render.exr" "$work/spectral.exr" "$work/rgb.exr" 2 -60 0.02 ||
    fail "the spectral composite against the 48-wavelength reference"

# 3: the identity, and the sky pixels against the plain spectral render of the same camera.
"$VKSKY" --render "$work/sky.exr" --width 64 --height 36 --altitude 0.2188 --yaw -90 --pitch -3 --fov 40 \
    --sky-mode march --render-scale 1 --no-bloom --units relative "${SUNSET[@]}" "${LUTS[@]}" --spectral 24 \
    --validate >/dev/null 2>"$work/err" || fail "plain spectral sky render: exit $?: $(head -c 300 "$work/err")"
"$CHECK" "$work/spectral.exr" "$S/render.exr" "$work/sky.exr" ||
    fail "the spectral composite: the coverage identity or its sky pixels against the plain spectral render"
# The same in RGB: the composite's sun disc is the plain render's (it was point-sampled at the true radius: up to 2x
# off on the pixels at the sun of this 64x36 image).
"$VKSKY" --render "$work/sky_rgb.exr" --width 64 --height 36 --altitude 0.2188 --yaw -90 --pitch -3 --fov 40 \
    --sky-mode march --render-scale 1 --no-bloom --units relative "${SUNSET[@]}" "${LUTS[@]}" --spectral 0 \
    --validate >/dev/null 2>"$work/err" || fail "plain RGB sky render: exit $?: $(head -c 300 "$work/err")"
"$CHECK" "$work/rgb.exr" "$S/render.exr" "$work/sky_rgb.exr" ||
    fail "the RGB composite with the sun in the frame: its sky pixels against the plain render"

# 4: --quality auto: spectral at sunset (the pick said and recorded), RGB at noon on a CPU device (its table forced:
# on a GPU noon picks 8, docs/spectral.md "Auto by the device's kind"), byte for byte --spectral 0's.
"$VKSKY" --composite "$S/render.exr" --render "$work/auto.exr" "${SUNSET[@]}" --validate >"$work/out" 2>"$work/err" ||
    fail "auto composite at sunset: exit $?: $(head -c 300 "$work/err")"
grep -q "^vksky: --quality auto: .*picked --spectral [0-9]*" "$work/out" ||
    fail "auto at sunset did not say it picked a spectral setting: $(cat "$work/out")"
picked=$(grep -o 'picked --spectral [0-9]*' "$work/out" | grep -o '[0-9]*$')
"$VKSKY" --scene "$work/auto.exr" --dump-scene 2>/dev/null | grep -qE "\"spectral\":[[:space:]]*${picked:-x}\b" ||
    fail "the auto composite's header does not record --spectral ${picked:-?}"
NOON=(--sun-elevation 60 --sun-azimuth -60)
VKSKY_QUALITY_TABLE=cpu "$VKSKY" --composite "$S/render.exr" --render "$work/noon_auto.exr" "${NOON[@]}" --validate \
    >"$work/out" 2>&1 || fail "auto composite at noon: exit $?"
grep -q "picked --spectral" "$work/out" && fail "auto at noon picked a spectral setting: $(cat "$work/out")"
VKSKY_QUALITY_TABLE=cpu "$VKSKY" --composite "$S/render.exr" --render "$work/noon_rgb.exr" "${NOON[@]}" --spectral 0 \
    --validate >/dev/null 2>&1 || fail "--spectral 0 composite at noon: exit $?"
# The command line is in the header: compare the pixels (every layer's channels, as raw bytes).
if command -v oiiotool >/dev/null; then
    oiiotool "$work/noon_auto.exr" "$work/noon_rgb.exr" --diff >"$work/diff" 2>&1 ||
        fail "auto at noon differs from --spectral 0: $(tail -3 "$work/diff")"
fi

# 5: --aovs in spectral colour: its top level is the plain spectral render's (the same pixels), its layers the
#    spectral composite's of a frame without geometry (rayleigh + mie + the lit ground = sky: no ground here); auto
#    picks the spectral setting for it at sunset.
# At part 1's LUT numerics: the 24 wavelengths' eight groups read the LUTs parts 1-3 computed (the suite's LUT cache)
# instead of computing them again at the default numerics (the identities checked here hold at any numerics).
AOVS=(--width 48 --height 27 --units relative "${SUNSET[@]}" "${LUTS[@]}" --spectral 24 --validate)
"$VKSKY" --render "$work/aovs.exr" --aovs "${AOVS[@]}" >/dev/null 2>"$work/err" ||
    fail "--aovs --spectral 24: exit $?: $(head -c 300 "$work/err")"
"$VKSKY" --render "$work/plain.exr" "${AOVS[@]}" >/dev/null 2>"$work/err" ||
    fail "plain --spectral 24 render: exit $?: $(head -c 300 "$work/err")"
if command -v oiiotool >/dev/null; then
    oiiotool "$work/aovs.exr" --ch R,G,B,A "$work/plain.exr" --diff >"$work/diff" 2>&1 ||
        fail "--aovs --spectral 24's top level differs from the plain spectral render: $(tail -3 "$work/diff")"
    oiiotool "$work/aovs.exr" --ch sky.R,sky.G,sky.B --chnames R,G,B "$work/aovs.exr" \
        --ch rayleigh.R,rayleigh.G,rayleigh.B --chnames R,G,B "$work/aovs.exr" --ch mie.R,mie.G,mie.B \
        --chnames R,G,B --add --fail 2e-3 --diff >"$work/diff" 2>&1 ||
        fail "--aovs --spectral 24: sky is not rayleigh + mie: $(tail -3 "$work/diff")"
fi
"$VKSKY" --render "$work/aovs_auto.exr" --aovs --width 16 --height 9 "${SUNSET[@]}" --validate >"$work/out" 2>&1 ||
    fail "--aovs at sunset under auto: exit $?"
grep -q "picked --spectral" "$work/out" || fail "--aovs at sunset: auto did not pick a spectral setting: $(cat "$work/out")"

if [ $fails -ne 0 ]; then echo "composite_spectral_test: $fails failure(s)"; exit 1; fi
echo "composite_spectral_test: ok"
