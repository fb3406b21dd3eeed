#!/usr/bin/env bash
# vksky --composite (issue 12): seed 004's scene (tests/gen_composite_scene.c) composited from one Blender-style
# multilayer file (camera from its worldToCamera/worldToNDC) and from two files (camera from flags): both exit 0
# under validation, agree with each other, and their layers satisfy composite = beauty * T + rayleigh + mie
# (composite_check), and their sky pixels are a plain sky render of the same camera; OpenImageIO lists every
# layer; the scene in km, Y up or 500 m higher (--world-unit/--world-up/--ground-altitude) composites the same. Every bad input: exit 2, one line on stderr naming the
# problem, no output file (and no temporary) left.
#
#   composite_test.sh VKSKY GEN_COMPOSITE_SCENE COMPOSITE_CHECK
set -u
VKSKY=${1:?usage: composite_test.sh VKSKY GEN_COMPOSITE_SCENE COMPOSITE_CHECK}
GEN=${2:?}
CHECK=${3:?}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
mkdir -p "$work/scene" "$work/small" "$work/sky" "$work/out"
"$GEN" "$work/scene" 240 135 || { echo "FAIL: gen_composite_scene"; exit 1; }
"$GEN" "$work/small" 120 68 || exit 1
"$GEN" "$work/sky" 120 68 sky || exit 1
S=$work/scene
SUN=(--sun-elevation 20 --sun-azimuth -60)
read -r -a CAMERA <"$S/camera.txt"

# --- Good inputs ---------------------------------------------------------------------------------------------
"$VKSKY" --composite "$S/render.exr" --render "$work/out/multi.exr" "${SUN[@]}" --validate 2>"$work/err" ||
    fail "multilayer composite: exit $? ($(cat "$work/err"))"
[ ! -s "$work/err" ] || fail "multilayer composite (camera from the EXR): stderr not empty: $(cat "$work/err")"
"$CHECK" "$work/out/multi.exr" "$S/render.exr" || fail "multilayer composite: layers do not add up"
"$VKSKY" --composite "$S/beauty.exr" --position "$S/position.exr" "${CAMERA[@]}" --render "$work/out/two.exr" \
    "${SUN[@]}" --validate 2>"$work/err" || fail "two-file composite: exit $? ($(cat "$work/err"))"
# Its sky pixels are vksky's sky along each pixel's ray: a plain sky render of the same camera, without bloom, by
# the same method (the composite marches every pixel; a plain render's default, --quality auto, may pick the
# sky-view LUT instead, which interpolates, and on a CPU device a half-size sky: --render-scale 1).
"$VKSKY" --render "$work/out/sky.exr" --width 240 --height 135 --altitude 0.2188 --yaw -90 --pitch -3 --fov 40 \
    --sky-mode march --render-scale 1 --no-bloom --units relative "${SUN[@]}" --validate || fail "plain sky render: exit $?"
"$CHECK" "$work/out/two.exr" "$S/render.exr" "$work/out/sky.exr" || fail "two-file composite: layers or sky pixels"
# Hillaire's froxel volume (--aerial-perspective volume; its accuracy: ctest ap_volume): exit 0, silent, the
# layers add up and the sky pixels are the same sky; auto takes it when --max-error allows its measured error.
"$VKSKY" --composite "$S/beauty.exr" --position "$S/position.exr" "${CAMERA[@]}" --render "$work/out/vol.exr" \
    "${SUN[@]}" --aerial-perspective volume --validate 2>"$work/err" || fail "volume composite: exit $? ($(cat "$work/err"))"
[ ! -s "$work/err" ] || fail "volume composite: stderr not empty: $(cat "$work/err")"
"$CHECK" "$work/out/vol.exr" "$S/render.exr" "$work/out/sky.exr" || fail "volume composite: layers or sky pixels"
"$VKSKY" --composite "$S/render.exr" --render "$work/out/auto.exr" "${SUN[@]}" --max-error 0.05 --validate \
    2>"$work/err" || fail "auto composite: exit $? ($(cat "$work/err"))"
# The cheapest volume whose worst view class is within 5 % (src/app/quality/ap_trade_table.h): 32x32x32 (2.2 % near steep
# ground); 16x16x16 is cheaper but 5.5 % there.
grep -q "allows the volume 32x32x32 quadratic" "$work/err" ||
    fail "auto with --max-error 0.05: did not take the cheapest volume within it (src/app/quality/ap_trade_table.h): $(cat "$work/err")"
"$VKSKY" --composite "$S/render.exr" --render "$work/out/auto.exr" "${SUN[@]}" --max-error 0.003 --validate \
    2>"$work/err" || fail "auto composite, --max-error 0.003: exit $? ($(cat "$work/err"))"
grep -q "auto: no measured froxel volume" "$work/err" ||
    fail "auto with --max-error 0.003: expected the march: $(cat "$work/err")"
# Without an orientation: geometry composited, sky pixels keep the beauty, one note on stderr.
"$VKSKY" --composite "$S/beauty.exr" --position "$S/position.exr" --camera-position -3.5,-8.5,218.8 \
    --render "$work/out/noorient.exr" --validate 2>"$work/err" || fail "composite without orientation: exit $?"
[ "$(wc -l <"$work/err")" -eq 1 ] && grep -q "orientation is unknown" "$work/err" ||
    fail "composite without orientation: expected one note on stderr, got: $(cat "$work/err")"
# An orientation without a field of view: composited, with one note that the sky pixels assume the default fov.
"$VKSKY" --composite "$S/beauty.exr" --position "$S/position.exr" --camera-position -3.5,-8.5,218.8 --yaw -90 \
    --render "$work/out/nofov.exr" --validate 2>"$work/err" || fail "composite without --fov: exit $?"
[ "$(wc -l <"$work/err")" -eq 1 ] && grep -q "no --fov given" "$work/err" ||
    fail "composite without --fov: expected one note on stderr, got: $(cat "$work/err")"
if command -v oiiotool >/dev/null; then
    info=$(oiiotool --info -v "$work/out/multi.exr")
    for ch in R G B A sky.R sky.G sky.B sun_disk.R sun_disk.G sun_disk.B transmittance.R transmittance.G \
        transmittance.B rayleigh.R rayleigh.G rayleigh.B mie.R mie.G mie.B; do
        grep -Eq "channel list:.*(^| |,)$ch( |,|$)" <<<"$info" || fail "oiiotool does not list channel $ch: $info"
    done
    # The camera from the EXR's matrices and from the flags: the same image to fp16 (the matrices are float).
    oiiotool "$work/out/multi.exr" "$work/out/two.exr" --fail 0.01 --diff >"$work/diff" 2>&1 ||
        fail "multilayer vs two-file composite differ: $(tail -n 3 "$work/diff")"
    # The same render as one tiled, float file (oiiotool keeps the camera attributes): the same composite.
    oiiotool "$S/render.exr" -d float --tile 32 32 -o "$work/tiled.exr" &&
        "$VKSKY" --composite "$work/tiled.exr" --render "$work/out/tiled.exr" "${SUN[@]}" --validate 2>"$work/err" ||
        fail "tiled float composite: exit $? ($(cat "$work/err"))"
    oiiotool "$work/out/multi.exr" "$work/out/tiled.exr" --fail 0.001 --diff >"$work/diff" 2>&1 ||
        fail "tiled float input vs scanline half input: $(tail -n 3 "$work/diff")"
    # The world conventions: the same scene re-expressed in other units, axes or ground height composites to the
    # same image (every layer, within 1e-3 absolute: fp16 near 1): positions in km with --world-unit 1000; Y up
    # ((x, y, z) -> (x, z, -y), a rotation) with --world-up y; everything 500 m higher with --ground-altitude -0.5.
    # (--yaw/--pitch and the sun are in the local frame, unchanged.)
    CAM_ANGLES=(--yaw -90 --pitch -3 --fov 40)
    conv() {   # conv NAME OIIOTOOL-OPS -- VKSKY-ARGS...
        local name=$1 ops=() ; shift
        while [ "$1" != "--" ]; do ops+=("$1"); shift; done; shift
        oiiotool "$S/position.exr" "${ops[@]}" -o "$work/pos_$name.exr" || { fail "$name: oiiotool"; return; }
        "$VKSKY" --composite "$S/beauty.exr" --position "$work/pos_$name.exr" "$@" "${CAM_ANGLES[@]}" \
            --render "$work/out/$name.exr" "${SUN[@]}" --validate 2>"$work/err" ||
            { fail "$name composite: exit $? ($(cat "$work/err"))"; return; }
        oiiotool "$work/out/two.exr" "$work/out/$name.exr" --fail 0.001 --diff >"$work/diff" 2>&1 ||
            fail "$name: not the same composite as metres, Z up, ground at 0: $(tail -n 3 "$work/diff")"
    }
    conv km --mulc 0.001 -- --world-unit 1000 --camera-position -0.0035,-0.0085,0.2188
    conv yup --ch R,B,G --chnames R,G,B --mulc 1,1,-1 -- --world-up y --camera-position -3.5,218.8,8.5
    conv ground --addc 0,0,500 -- --ground-altitude -0.5 --camera-position -3.5,-8.5,718.8
    # A plain sky render with --aovs carries the same layers.
    "$VKSKY" --render "$work/out/aovs.exr" --width 64 --height 36 --aovs --validate 2>"$work/err" ||
        fail "--aovs render: exit $? ($(cat "$work/err"))"
    info=$(oiiotool --info -v "$work/out/aovs.exr" 2>&1)
    for ch in sky.R sun_disk.G transmittance.B rayleigh.R mie.B; do
        grep -Eq "channel list:.*(^| |,)$ch( |,|$)" <<<"$info" || fail "--aovs: oiiotool does not list $ch: $info"
    done
else
    echo "note: no oiiotool (openimageio-tools): layer listing not checked"
fi

# --- Bad inputs ----------------------------------------------------------------------------------------------
# expect_bad "what" "text in stderr" args...   (every run writes $work/out/bad.exr if it writes anything)
expect_bad() {
    local what=$1 needle=$2; shift 2
    "$VKSKY" "$@" --validate >"$work/stdout" 2>"$work/stderr"
    local rc=$?
    [ $rc -eq 2 ] || fail "$what: exit status $rc, expected 2 (stderr: $(cat "$work/stderr"))"
    [ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "$what: expected exactly one line on stderr, got: $(cat "$work/stderr")"
    grep -qF -- "$needle" "$work/stderr" || fail "$what: stderr does not mention '$needle': $(cat "$work/stderr")"
    [ ! -e "$work/out/bad.exr" ] || fail "$what: wrote an output file"
    [ -z "$(ls -A "$work/out" | grep '^\.')" ] || fail "$what: left a temporary: $(ls -A "$work/out")"
}
OUT=(--render "$work/out/bad.exr")
echo "not an image" >"$work/text.exr"
expect_bad "missing file" "nosuch.exr" --composite "$work/nosuch.exr" "${OUT[@]}"
expect_bad "not an EXR" "text.exr" --composite "$work/text.exr" "${OUT[@]}"
expect_bad "position not an EXR" "text.exr" --composite "$S/beauty.exr" --position "$work/text.exr" "${OUT[@]}"
expect_bad "size mismatch" "same size" --composite "$S/beauty.exr" --position "$work/small/position.exr" \
    "${CAMERA[@]}" "${OUT[@]}"
expect_bad "no position layer" "no position layer" --composite "$S/beauty.exr" "${CAMERA[@]}" "${OUT[@]}"
expect_bad "named beauty layer missing" "no beauty layer 'Foo'" --composite "$S/render.exr" --beauty-layer Foo "${OUT[@]}"
expect_bad "named position layer missing" "no position layer 'Bar'" --composite "$S/render.exr" --position-layer Bar \
    "${OUT[@]}"
expect_bad "no beauty in a position file" "no beauty layer" --composite "$S/position.exr" --position "$S/position.exr" \
    --beauty-layer Combined "${CAMERA[@]}" "${OUT[@]}"
expect_bad "every position non-finite" "no finite pixel" --composite "$work/sky/render.exr" "${OUT[@]}"
expect_bad "camera inside the planet" "inside the planet" --composite "$S/beauty.exr" --position "$S/position.exr" \
    --camera-position 0,0,-50 "${OUT[@]}"
expect_bad "camera below a raised ground" "inside the planet" --composite "$S/render.exr" --ground-altitude -1 \
    --world-unit 0.001 "${OUT[@]}"
expect_bad "no camera" "--camera-position" --composite "$S/beauty.exr" --position "$S/position.exr" "${OUT[@]}"
expect_bad "PNG output" "--render FILE.exr" --composite "$S/render.exr" --render "$work/out/bad.png"
expect_bad "no output" "--render FILE.exr" --composite "$S/render.exr"
expect_bad "volume without an orientation" "orientation is unknown" --composite "$S/beauty.exr" \
    --position "$S/position.exr" --camera-position -3.5,-8.5,218.8 --aerial-perspective volume "${OUT[@]}"
expect_bad "--ap-volume-size" "WxHxD" --composite "$S/render.exr" --ap-volume-size 32x32 "${OUT[@]}"
expect_bad "--ap-volume-size 0" "WxHxD" --composite "$S/render.exr" --ap-volume-size 0x32x32 "${OUT[@]}"
expect_bad "--ap-volume-range" "km in" --composite "$S/render.exr" --ap-volume-range 0 "${OUT[@]}"
expect_bad "--ap-volume-slices" "linear or quadratic" --composite "$S/render.exr" --ap-volume-slices cubic "${OUT[@]}"
expect_bad "unknown method" "march, volume or auto" --composite "$S/render.exr" --aerial-perspective fast "${OUT[@]}"
expect_bad "--position alone" "only with --composite" --position "$S/position.exr" "${OUT[@]}"
expect_bad "--world-up" "y or z" --composite "$S/render.exr" --world-up x "${OUT[@]}"
expect_bad "--world-unit" "metres per world unit" --composite "$S/render.exr" --world-unit 0 "${OUT[@]}"
expect_bad "--camera-position" "X,Y,Z" --composite "$S/render.exr" --camera-position 1,2 "${OUT[@]}"
expect_bad "--width with --composite" "the size is the input's" --composite "$S/render.exr" --width 64 "${OUT[@]}"
expect_bad "--aovs with --composite" "--aovs" --composite "$S/render.exr" --aovs "${OUT[@]}"
expect_bad "--aovs to PNG" "--aovs" --render "$work/out/bad.png" --aovs --width 32 --height 32

[ $fails -eq 0 ] || { echo "composite_test: $fails failure(s)"; exit 1; }
# A section skipped is not a pass (issue 31): ctest shows SKIP (SKIP_RETURN_CODE 77), and CI fails on any skip.
if ! command -v oiiotool >/dev/null; then echo "composite_test: SKIP: the oiiotool sections need openimageio-tools"; exit 77; fi
echo "composite_test: ok"
