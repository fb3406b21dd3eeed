#!/usr/bin/env bash
# The fragment tone map drawn by regions (issue 26 item 1, sky/tonemap_regions.h): the far-only pipeline where the
# host's bound finds no texel within the horizon path's reach, the full one elsewhere. The answer is the full shader
# on every pixel (VKSKY_TONEMAP_SPLIT=0, the per-pixel decision alone): every view below, rendered both ways, gives
# the same PNG and EXR, byte for byte. Views: the horizon across the frame at render scales 1, 0.5 and 0.25, low
# and steep pitches and a wide fov, from 1 m to the 400 km limb and 36 000 km, an equirect map (whole and in bands
# of 7 rows), a cube map and a fisheye; each validated (validation + synchronization validation). Also: the trace
# of a split frame draws more than one region (the split happens), and the regions cover the horizon (a 1 m frame
# whose horizon crosses it has horizon regions). The fragment post chain is forced (--post-pass fragment); the
# compute tone map decides per pixel only. RGB (--spectral 0) on every view: where --quality auto picks a spectral
# setting (sunset, 10 km, space: seven of the views below) the PNG is tone-mapped on the host from the groups' sum,
# and the GPU tone map whose regions this test is about would draw nothing the PNG shows.
#
#   tonemap_regions_test.sh VKSKY
set -u
VKSKY=$(realpath "${1:?usage: tonemap_regions_test.sh path/to/vksky}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
unset VKSKY_LUT_CACHE
export XDG_CACHE_HOME="$work/cache"
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
n=0
ROWS=   # bands of this many rows (VKSKY_TILE_ROWS), empty: as the budget has it

same() {   # same ARGS...: one render split and one whole-frame full, the files compared
    n=$((n + 1))
    for mode in split full; do
        mkdir -p "$work/$n/$mode"
        local split=1
        [ $mode = full ] && split=0
        (cd "$work/$n/$mode" && VKSKY_TILE_ROWS=$ROWS VKSKY_TONEMAP_SPLIT=$split "$VKSKY" --validate --quiet \
            --post-pass fragment --spectral 0 --render m.exr --render m.png "$@" 2>err) ||
            fail "$* ($mode): exit $? ($(cat "$work/$n/$mode/err"))"
        [ ! -s "$work/$n/$mode/err" ] || fail "$* ($mode): stderr: $(cat "$work/$n/$mode/err")"
    done
    for f in m.exr m.png; do
        cmp -s "$work/$n/split/$f" "$work/$n/full/$f" || fail "$*: $f differs between the regions and the full shader"
    done
}

P=(--width 96 --height 54)
same "${P[@]}" --render-scale 1 --sun-elevation 3 --pitch 5
same "${P[@]}" --render-scale 0.5 --sun-elevation 3 --pitch 5 --no-bloom
same "${P[@]}" --render-scale 0.25 --pitch 1
same "${P[@]}" --render-scale 0.5 --pitch -40 --fov 120 --yaw 30
same "${P[@]}" --render-scale 0.5 --pitch 60 --fov 20
same "${P[@]}" --render-scale 0.5 --altitude 10 --pitch -5
same "${P[@]}" --render-scale 0.5 --altitude 400 --pitch -20
same "${P[@]}" --render-scale 1 --altitude 36000 --pitch -90 --fov 30
same --projection equirect --width 96 --sun-elevation 9
ROWS=7 same --projection equirect --width 64 --altitude 100
ROWS=
same --projection cubemap --width 64 --sun-elevation 20
same --projection fisheye --width 64 --altitude 5

if [ "$fails" -gt 0 ]; then
    echo "tonemap_regions: $fails failure(s)"
    exit 1
fi
echo "tonemap_regions: $n views, the regions' images equal the full shader's (PNG and EXR, byte for byte)"
