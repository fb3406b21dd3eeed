#!/usr/bin/env bash
# Every EXR compression vksky writes, read by OpenImageIO (not by vksky's reader nor by the writer's own library
# build) and compared with the same frame written uncompressed (issue 27: ZIP and ZIPS chunks now come from
# libdeflate, the other compressions from OpenEXRCore; a streamed file's bands share one chunk pool):
#  - photometric float frames (the default) and relative half frames: zip (default level, 1, 9), zips, piz, rle
#    equal the uncompressed pixels bit for bit; pxr24 (24-bit floats) and b44/b44a (half: 4x4 blocks quantized,
#    up to 19 % in a dark pixel beside bright ones here, 0.3 % on average) within their loss;
#  - a banded equirect (VKSKY_TILE_ROWS: bands of 5 rows, a chunk split across bands): zip, zips and piz equal the
#    uncompressed map, and --threads 1 and --threads 4 write the same bytes;
#  - the composite's streamed writer (issue 28) too: seed 004's passes (gen_composite_scene) composited in bands of
#    16 rows (PIZ rounds them up to its 32-row chunks); zip, zips, piz, rle and pxr24 (half channels: lossless) equal
#    the uncompressed composite bit for bit, every layer;
#  - every run exits 0 with the validation layer on and silent.
#   exr_compressions_test.sh path/to/vksky path/to/gen_composite_scene
set -u
VKSKY=$(readlink -f "${1:?usage: exr_compressions_test.sh path/to/vksky path/to/gen_composite_scene}")
GEN=${2:?usage: exr_compressions_test.sh path/to/vksky path/to/gen_composite_scene}
CHECK=$(dirname "$(readlink -f "$0")")/exr_compressions_check.py
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
export VKSKY_VALIDATION=1
# The LUT cache on in the test's own directory: ~40 renders of a few LUT settings, and the checks are about the
# files' compression (tests/lib/own_lut_cache.sh).
# shellcheck source=lib/own_lut_cache.sh
source "$(dirname "$0")/lib/own_lut_cache.sh"
own_lut_cache "$work"
/usr/bin/python3 -c 'import OpenImageIO, numpy' 2>/dev/null ||
    { echo "FAIL: /usr/bin/python3 with OpenImageIO and numpy (python3-openimageio, python3-numpy) not found" >&2; exit 1; }

run() {   # run NAME [ENV=V...] -- ARGS...: in $work (DIR=D: in $work/D); fails on a non-zero exit or a validation message
    local name=$1; shift
    local envs=() d=$work
    while [ "$1" != -- ]; do case $1 in DIR=*) d=$work/${1#DIR=}; mkdir -p "$d" ;; *) envs+=("$1") ;; esac; shift; done
    shift
    (cd "$d" && env "${envs[@]}" "$VKSKY" "$@" --validate --quiet >"$name.out" 2>"$name.err") || fail "$name: exit $?"
    grep -qi 'validation' "$d/$name.err" && fail "$name: $(grep -m1 -i validation "$d/$name.err")"
}
check() {   # check REF FILE EXPECT COMPRESSION
    COMPRESSION=$4 /usr/bin/python3 "$CHECK" "$work/$1" "$work/$2" "$3" >/dev/null 2>"$work/check.err" ||
        fail "$(cat "$work/check.err")"
}

FRAME=(--width 64 --height 40 --quality low --sun-elevation 8)
# name | compression | flags | expected (exact or a relative bound) for float, then for half
cases=(
  "zip|zip|exact|exact" "zip1|zip:1|exact|exact" "zip9|zip:9|exact|exact" "zips|zips|exact|exact"
  "piz|piz|exact|exact" "rle|rle|exact|exact" "pxr24|pxr24|2e-4|exact" "b44|b44|exact|0.25,0.01" "b44a|b44a|exact|0.25,0.01"
)
for type in float half; do
    if [ $type = float ]; then T=(--exr-type float); else T=(--units relative --exr-type half); fi
    run "${type}_none" -- "${FRAME[@]}" "${T[@]}" --exr-compression none --render "${type}_none.exr"
    for c in "${cases[@]}"; do
        IFS='|' read -r name comp ef eh <<<"$c"
        expect=$ef; [ $type = half ] && expect=$eh
        run "${type}_$name" -- "${FRAME[@]}" "${T[@]}" --exr-compression "$comp" --render "${type}_$name.exr"
        check "${type}_none.exr" "${type}_$name.exr" "$expect" "${comp%%:*}"
    done
done

# A streamed equirect in bands of 5 rows (ZIP chunks of 16 rows straddle them; ZIPS chunks are one row).
EQ=(--projection equirect --width 64 --quality low)
run eq_none VKSKY_TILE_ROWS=5 -- "${EQ[@]}" --exr-compression none --render eq_none.exr
for comp in zip zips piz; do
    for t in 1 4; do
        # The same relative path in two folders: the header records the command line.
        run "eq_${comp}_$t" DIR=t$t VKSKY_TILE_ROWS=5 -- "${EQ[@]}" --threads "$t" --exr-compression "$comp" \
            --render "eq_$comp.exr"
    done
    check eq_none.exr "t4/eq_$comp.exr" exact "$comp"
    cmp -s "$work/t1/eq_$comp.exr" "$work/t4/eq_$comp.exr" || fail "equirect $comp: --threads 1 and 4 differ"
done

# The composite: its six layers through io_exr_layers_stream (before, ZIP whatever --exr-compression said).
mkdir -p "$work/cs" && "$GEN" "$work/cs" 64 72 >/dev/null || fail "gen_composite_scene"
COMP=(--composite "$work/cs/render.exr" --sun-elevation 20 --sun-azimuth -60)
run comp_none VKSKY_COMPOSITE_BAND_ROWS=16 -- "${COMP[@]}" --exr-compression none --render comp_none.exr
for comp in zip zips piz rle pxr24; do
    run "comp_$comp" VKSKY_COMPOSITE_BAND_ROWS=16 -- "${COMP[@]}" --exr-compression "$comp" --render "comp_$comp.exr"
    check comp_none.exr "comp_$comp.exr" exact "$comp"
done

[ "$fails" = 0 ] && echo "exr_compressions: all checks passed"
exit $((fails > 0))
