#!/usr/bin/env bash
# A real render by Debian's Blender composited (issue 28). tests/blender/render_scene.py renders seed 004's scene
# with Cycles (16 samples, the default 1.5 px filter, Film > Transparent, Position and Depth passes) into one float
# multilayer EXR with two view layers and a Composite output, and exports the camera and sun with the add-on
# (tools/blender/vksky_blender.py). Asserted:
#  - the export and vksky's conventions agree with Blender's camera: each sphere where vksky projects it;
#  - the right layers: two view layers and no --view-layer -> exit 2 naming them; with --view-layer ViewLayer the
#    composite is the one of a file holding that view layer alone (not Composite.Combined, not Other's position);
#  - coverage-correct edges: no edge pixel below 0.5x, the mean within 5 % (blender_check edges);
#  - the coverage identity on every pixel and the sky behind the uncovered part (composite_check, with a plain sky
#    render of the exported scene, and again with one from `--scene` on the composite: its header round trip);
#  - bad inputs: an opaque film, the position from another view layer: exit 2, one line;
#  - the add-on's import: a vksky equirect map of the exported scene as the world, its sun lamp on the map's sun
#    disc as Blender looks it up, and in the exported sun's direction.
# Exit 77 (skipped) without blender.
#
#   blender_test.sh VKSKY COMPOSITE_CHECK BLENDER_CHECK VKSKY_BLENDER_PY
set -u
VKSKY=${1:?usage: blender_test.sh VKSKY COMPOSITE_CHECK BLENDER_CHECK VKSKY_BLENDER_PY}
CHECK=${2:?}
BCHECK=${3:?}
ADDON=${4:?}
HERE=$(cd "$(dirname "$0")" && pwd)
command -v blender >/dev/null || { echo "blender_test: no blender (Debian package blender): skipped"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
mkdir -p "$work/b" "$work/out"
B=$work/b
start=$SECONDS
blender -b --factory-startup -P "$HERE/render_scene.py" -- "$B" "$ADDON" >"$work/blender.log" 2>&1 &&
    [ -s "$B/render.exr" ] && [ -s "$B/scene.args" ] || { cat "$work/blender.log"; echo "FAIL: blender render"; exit 1; }
grep "^render_scene:" "$work/blender.log"
echo "blender_test: blender run (start-up, two renders, export): $((SECONDS - start)) s"
read -r -a FLAGS <"$B/scene.args"
# The flags by name: --camera-position X,Y,Z --yaw Y --pitch P --fov F ...
flag() { local i; for ((i = 0; i < ${#FLAGS[@]}; ++i)); do [ "${FLAGS[i]}" = "$1" ] && echo "${FLAGS[i + 1]}"; done; }

"$BCHECK" camera "$B/render.exr" ViewLayer "$B/spheres.txt" "$(flag --yaw)" "$(flag --pitch)" "$(flag --fov)" \
    "$(flag --camera-position)" || fail "vksky's camera (exported) does not put the spheres where Blender did"

# The right layers.
expect_bad() {
    local what=$1 needle=$2; shift 2
    "$VKSKY" "$@" --validate >"$work/stdout" 2>"$work/stderr"
    local rc=$?
    [ $rc -eq 2 ] || fail "$what: exit status $rc, expected 2 (stderr: $(cat "$work/stderr"))"
    [ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "$what: expected one line on stderr, got: $(cat "$work/stderr")"
    grep -qF -- "$needle" "$work/stderr" || fail "$what: stderr does not mention '$needle': $(cat "$work/stderr")"
    [ ! -e "$work/out/bad.exr" ] || fail "$what: wrote an output file"
}
OUT=(--render "$work/out/bad.exr")
expect_bad "two view layers, no choice" "2 view layers (Other, ViewLayer)" --composite "$B/render.exr" "${FLAGS[@]}" "${OUT[@]}"
expect_bad "position from another view layer" "must come from one view layer" --composite "$B/render.exr" \
    --beauty-layer ViewLayer.Combined --position-layer Other.Position "${FLAGS[@]}" "${OUT[@]}"
expect_bad "opaque film" "transparent film" --composite "$B/opaque.exr" "${FLAGS[@]}" "${OUT[@]}"

"$VKSKY" --composite "$B/render.exr" --view-layer ViewLayer --render "$work/out/c.exr" "${FLAGS[@]}" --validate \
    2>"$work/err" || fail "composite: exit $? ($(cat "$work/err"))"
if command -v oiiotool >/dev/null; then
    oiiotool "$B/render.exr" --ch ViewLayer.Combined.R,ViewLayer.Combined.G,ViewLayer.Combined.B,ViewLayer.Combined.A,ViewLayer.Position.X,ViewLayer.Position.Y,ViewLayer.Position.Z \
        -o "$work/alone.exr" &&
        "$VKSKY" --composite "$work/alone.exr" --render "$work/out/alone.exr" "${FLAGS[@]}" --validate 2>"$work/err" ||
        fail "composite of the view layer alone: exit $? ($(cat "$work/err"))"
    oiiotool "$work/out/c.exr" "$work/out/alone.exr" --fail 0 --failpercent 0 --diff >"$work/diff" 2>&1 ||
        fail "--view-layer ViewLayer did not use that view layer's passes: $(tail -n 3 "$work/diff")"
fi

# Coverage-correct edges and the identity, against a plain sky render of the exported scene (in the composite's units,
# the lesson's: docs/units.md).
"$VKSKY" --scene "$B/scene.json" --render "$work/out/sky.exr" --sky-mode march --render-scale 1 --no-bloom \
    --units relative --validate || fail "sky render of the exported scene: exit $?"
"$BCHECK" edges "$work/out/c.exr" "$B/render.exr" ViewLayer "$work/out/sky.exr" || fail "edges not coverage-correct"
# composite_check reads ViewLayer.* of the input: Blender's names.
"$CHECK" "$work/out/c.exr" "$B/render.exr" "$work/out/sky.exr" || fail "the coverage identity, or the sky behind"
"$VKSKY" --scene "$work/out/c.exr" --render "$work/out/sky2.exr" --sky-mode march --render-scale 1 --no-bloom \
    --units relative --validate 2>"$work/err" || fail "--scene on the composite: exit $? ($(cat "$work/err"))"
"$CHECK" "$work/out/c.exr" "$B/render.exr" "$work/out/sky2.exr" || fail "--scene on the composite: not its sky"

# The add-on's import of a vksky map made from the exported scene.
"$VKSKY" --scene "$B/scene.json" --render "$work/out/map.exr" --projection equirect --width 256 --height 128 \
    --validate || fail "equirect map of the exported scene: exit $?"
blender -b --factory-startup -P "$HERE/import_check.py" -- "$ADDON" "$work/out/map.exr" "$(flag --sun-azimuth)" \
    "$(flag --sun-elevation)" >"$work/import.log" 2>&1 || fail "import: $(grep -E 'FAIL|Error' "$work/import.log")"
grep "^import_check:" "$work/import.log"

[ $fails -eq 0 ] || { echo "blender_test: $fails failure(s)"; exit 1; }
echo "blender_test: ok"
