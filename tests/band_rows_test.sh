#!/usr/bin/env bash
# A banded render equals the whole image byte for byte, whatever the band's height (issue 26 item 2).
# The 64x32 equirect map at sun 9 degrees (photometric, the disc in it: the HDR image's scale is 2^-16 cd/m2, so the
# dark ground's halves are subnormal, a step of 1/256 cd/m2) rendered in one band and in bands of every height
# 1 .. 32 (VKSKY_TILE_ROWS): the EXR and the PNG must be the same files (each run in its own directory under the same
# relative name, so the headers' command lines agree). Before the fix the tone map's bilinear sample at a pixel's
# centre, (y + 0.5) / h, mixed a neighbour row in at a rounding-sized weight wherever h (the band's image height,
# band + 2 rows) made that inexact, and row 27's ground moved by one half step (docs/horizon.md).
# Every run is validated (validation + synchronization validation; any message fails it). The LUT cache is on, in
# a directory of this test's own, so only the first run computes the LUTs (~15 s of CPU in all).
#
# The second argument picks the image (one ctest each, to keep each under ~15 s of CPU):
#   equirect (default) the 64x32 map above;
#   fisheye            a 20x20 fisheye (its horizon is the circle's rim, so the rim pixels take the horizon path),
#                      in bands of every height 1 .. 20;
#   cube               a cube map of 5-pixel faces (5x30: the horizon crosses four faces), bands of every height 1 .. 30.
# Those two run at a fixed exposure: an auto-exposed PNG's multiplier comes from the meter's float sums, which a band's
# rows group differently (ctest meter_bands bounds it; docs/horizon.md "Bands equal the whole image"). Before the fix
# there the tone map's horizon taps started at floor(uv x size - 0.5), which the interpolated uv put one texel up or
# left on some rows and columns of one image size and not of another; at the fisheye's rim a tap outside the circle
# carries the clamped distance 1e4, so the coverage moved by up to 18/255. Main's shader (1f2b3d0) fails the fisheye
# at every band height 1 .. 19, the cube at 3, 8, 9, 18, 20, 21 and 29 rows.
#
#   band_rows_test.sh VKSKY [equirect|fisheye|cube]
set -u
VKSKY=${1:?usage: band_rows_test.sh path/to/vksky [equirect|fisheye|cube]}
VKSKY=$(cd "$(dirname "$VKSKY")" && pwd)/$(basename "$VKSKY")   # (each run starts in its own directory)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
unset VKSKY_LUT_CACHE
export XDG_CACHE_HOME="$work/cache"
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
case ${2:-equirect} in
    equirect) MAP=(--projection equirect --width 64 --height 32 --sun-elevation 9) height=32 ;;
    fisheye) MAP=(--projection fisheye --width 20 --sun-elevation 9 --exposure 13 --no-bloom) height=20 ;;
    cube) MAP=(--projection cubemap --width 5 --sun-elevation 9 --exposure 13) height=30 ;;
    *) echo "band_rows_test.sh: unknown image '$2' (equirect, fisheye or cube)" >&2; exit 2 ;;
esac

render() {   # render DIR [ROWS]: the map into DIR/m.exr and DIR/m.png (ROWS: bands of that many rows)
    mkdir -p "$work/$1"
    (cd "$work/$1" && VKSKY_TILE_ROWS=${2:-} "$VKSKY" --validate --quiet --render m.exr --render m.png "${MAP[@]}" \
        2>err) || fail "$1: exit $? ($(cat "$work/$1/err"))"
    [ ! -s "$work/$1/err" ] || fail "$1: stderr not empty: $(cat "$work/$1/err")"
}

render one
for rows in $(seq 1 "$height"); do
    render "b$rows" "$rows"
    for f in m.exr m.png; do
        cmp -s "$work/one/$f" "$work/b$rows/$f" || fail "bands of $rows rows: $f differs from the whole map"
    done
done
[ -s "$work/one/m.exr" ] && [ -s "$work/one/m.png" ] || fail "the whole map: no files"
if [ "$fails" -gt 0 ]; then
    echo "band_rows ${2:-equirect}: $fails failure(s)"
    exit 1
fi
echo "band_rows: ${MAP[*]} in bands of every height 1..$height is byte-identical to the whole image (EXR and PNG)"
