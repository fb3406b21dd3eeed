#!/usr/bin/env bash
# The GPU tone map, exposure, sRGB encoding and bloom as written to the PNG, against the formula applied on the CPU to
# the same run's EXR (tests/tonemap_check.c says how; issue 31). Validated renders, exit statuses checked. RGB
# (--spectral 0): where --quality auto picks a spectral setting the PNG is tone-mapped on the host (ctest
# spectral_png checks that one), not by the GPU tone map this test is about.
# Usage: tonemap_png_test.sh VKSKY TONEMAP_CHECK
set -u
VKSKY=${1:?usage: tonemap_png_test.sh path/to/vksky path/to/tonemap_check}
CHECK=${2:?usage: tonemap_png_test.sh path/to/vksky path/to/tonemap_check}
export VKSKY_VALIDATION=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
# case: units EV operator [extra flags]; views with sky, sun and horizon at 160x90.
run() {
    local units=$1 ev=$2 op=$3; shift 3
    local name="$units-$op-$ev"
    # Undithered: within one level of the formula; dithered (the default): the noise's one level more (tonemap_check.c).
    for d in --no-dither ""; do
        "$VKSKY" --render "$work/$name.exr" --render "$work/$name.png" --width 160 --height 90 --units "$units" \
            --exposure "$ev" --tonemap "$op" --spectral 0 $d "$@" 2>"$work/err" ||
            { fail "$name $d: vksky exit $?: $(head -c 400 "$work/err")"; return; }
        "$CHECK" "$work/$name.exr" "$work/$name.png" "$units" "$ev" "$op" ${d:+} $([ -z "$d" ] && echo dither) ||
            fail "$name $d ($*): the PNG is not the formula's"
    done
}
run relative -1 aces --sun-elevation 20 --pitch 10 --yaw 30
run relative 2 reinhard --sun-elevation 5 --pitch 2 --yaw 0 --no-bloom
run relative 0 clamp --sun-elevation 60 --pitch 30 --no-bloom
run photometric 12 aces --sun-elevation 20 --pitch 10 --yaw 30
run photometric 9 aces --sun-elevation 2 --pitch 4 --yaw 0 --quality low
[ $fails -eq 0 ] || { echo "tonemap_png: $fails failure(s)"; exit 1; }
echo "tonemap_png: ok"
