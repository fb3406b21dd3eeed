#!/usr/bin/env bash
# --max-color-error X keeps its promise (issue 32 item 5): what it picks, rendered on the GPU (lavapipe, 12x7,
# --validate), is within CIEDE2000 X of the 48-wavelength spectral CPU reference of the same view on every pixel,
# measured by the test's comparison (spectral_compare: CIELAB with the white at the reference pixel's luminance,
# metrics_ciede2000, which ctest metrics holds to Sharma, Wu & Dalal 2005's published pairs) — not by the table the
# pick was made from. Two cases:
#   - twilight (sun -4), X = 1: the RGB renderer's own image of the same view is measured too and must be over X
#     (RGB cannot keep this promise), so the pick must be a spectral setting, and that setting keeps it;
#   - noon, X = 3: RGB keeps it (the pick may be RGB), and what is picked keeps it.
# Single scattering on both sides (--no-multiscatter: the reference without its 16 Psi tables, ~40 s, so the test
# stays short); the sun disc and bloom off (the reference has neither). About 25 s of CPU on lavapipe.
set -u
VKSKY=${1:?usage: spectral_pick_test.sh path/to/vksky path/to/spectral_compare}
COMPARE=${2:?usage: spectral_pick_test.sh path/to/vksky path/to/spectral_compare}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }

# de_max TEST.exr REF.exr: the largest CIEDE2000 over the compared pixels (spectral_compare's "max" after CIEDE2000).
de_max() { "$COMPARE" "$1" "$2" | tee -a "$work/log" | sed -n 's/.*CIEDE2000 mean [0-9.]* p95 [0-9.]* max \([0-9.infa]*\) .*/\1/p'; }

# case NAME X RGB_MUST_FAIL view...: pick, render, reference, compare.
case_pick() {
    local name=$1 x=$2 rgb_must_fail=$3; shift 3
    local f=(--width 12 --height 7 --no-bloom --no-sun-disc --no-multiscatter "$@")
    "$VKSKY" "${f[@]}" --reference --spectral 48 --render "$work/$name.ref.exr" 2>"$work/err" ||
        { fail "$name: spectral reference: exit $? ($(cat "$work/err"))"; return; }
    "$VKSKY" "${f[@]}" --quality high --max-color-error "$x" --validate --render "$work/$name.pick.exr" \
        >"$work/pick" 2>"$work/err" || { fail "$name: --max-color-error $x: exit $? ($(cat "$work/err"))"; return; }
    [ ! -s "$work/err" ] || fail "$name: --max-color-error $x wrote to stderr: $(cat "$work/err")"
    local n
    n=$(sed -n 's/.*picked --spectral \([0-9]*\) .*/\1/p' "$work/pick")
    [ -n "$n" ] || { fail "$name: no pick printed: $(cat "$work/pick")"; return; }
    local pick_de rgb_de
    pick_de=$(de_max "$work/$name.pick.exr" "$work/$name.ref.exr")
    echo "$name: --max-color-error $x picked --spectral $n: CIEDE2000 max $pick_de against the 48-wavelength reference"
    awk "BEGIN { exit !($pick_de <= $x) }" ||
        fail "$name: the pick (--spectral $n) is CIEDE2000 $pick_de from the spectral reference, over the promised $x"
    if [ "$rgb_must_fail" = yes ]; then
        "$VKSKY" "${f[@]}" --quality high --validate --render "$work/$name.rgb.exr" 2>"$work/err" ||
            { fail "$name: RGB render: exit $? ($(cat "$work/err"))"; return; }
        rgb_de=$(de_max "$work/$name.rgb.exr" "$work/$name.ref.exr")
        echo "$name: RGB (--spectral 0): CIEDE2000 max $rgb_de"
        awk "BEGIN { exit !($rgb_de > $x) }" || fail "$name: RGB meets $x here ($rgb_de): the case does not test a pick"
        [ "$n" -gt 0 ] || fail "$name: RGB is $rgb_de from the reference, yet --max-color-error $x picked RGB"
    fi
}

case_pick twilight 1 yes --sun-elevation -4 --sun-azimuth 0 --yaw 0 --pitch 35 --fov 60
case_pick noon 3 no --sun-elevation 60 --sun-azimuth 0 --yaw 180 --pitch 30 --fov 70

[ $fails -eq 0 ] && echo "spectral_pick: all checks passed" || cat "$work/log" >&2
exit $((fails > 0))
