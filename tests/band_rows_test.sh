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
#   band_rows_test.sh VKSKY
set -u
VKSKY=${1:?usage: band_rows_test.sh path/to/vksky}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
unset VKSKY_LUT_CACHE
export XDG_CACHE_HOME="$work/cache"
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
MAP=(--projection equirect --width 64 --height 32 --sun-elevation 9)

render() {   # render DIR [ROWS]: the map into DIR/m.exr and DIR/m.png (ROWS: bands of that many rows)
    mkdir -p "$work/$1"
    (cd "$work/$1" && VKSKY_TILE_ROWS=${2:-} "$VKSKY" --validate --quiet --render m.exr --render m.png "${MAP[@]}" \
        2>err) || fail "$1: exit $? ($(cat "$work/$1/err"))"
    [ ! -s "$work/$1/err" ] || fail "$1: stderr not empty: $(cat "$work/$1/err")"
}

render one
for rows in $(seq 1 32); do
    render "b$rows" "$rows"
    for f in m.exr m.png; do
        cmp -s "$work/one/$f" "$work/b$rows/$f" || fail "bands of $rows rows: $f differs from the whole map"
    done
done
[ -s "$work/one/m.exr" ] && [ -s "$work/one/m.png" ] || fail "the whole map: no files"
if [ "$fails" -gt 0 ]; then
    echo "band_rows: $fails failure(s)"
    exit 1
fi
echo "band_rows: a 64x32 map in bands of every height 1..32 is byte-identical to the whole map (EXR and PNG)"
