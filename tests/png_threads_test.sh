#!/usr/bin/env bash
# The parallel PNG writer through the CLI (issue 27; the writer itself: ctest png_parallel). Images of several
# 256 KiB blocks, written whole, in bands (VKSKY_TILE_PIXELS) and by a pipelined sequence:
#  - --threads 3 and --threads 16 write the same bytes (whole frame, banded, sequence);
#  - --threads 1 writes other bytes (libpng's own writer: the parallel path was taken with 3) that OpenImageIO
#    (idiff) decodes to the same pixels;
#  - a sequence on the readback ring equals the serial loop byte for byte with parallel PNGs;
#  - every run exits 0 with the validation layer on and silent.
#   png_threads_test.sh path/to/vksky
set -u
VKSKY=$(readlink -f "${1:?usage: png_threads_test.sh path/to/vksky}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
export VKSKY_VALIDATION=1
command -v idiff >/dev/null || { echo "FAIL: idiff (openimageio-tools) not found" >&2; exit 1; }

run() {   # run NAME [ENV=V...] -- ARGS...: vksky in $work/NAME; fails on a non-zero exit or a validation message
    local name=$1; shift
    local envs=()
    while [ "$1" != -- ]; do envs+=("$1"); shift; done
    shift
    mkdir -p "$work/$name"
    (cd "$work/$name" && env "${envs[@]}" "$VKSKY" "$@" --validate >stdout 2>stderr) || fail "$name: exit $?"
    grep -qi 'validation' "$work/$name/stderr" && fail "$name: $(grep -m1 -i validation "$work/$name/stderr")"
}
sum() { (cd "$work/$1" && md5sum -- *.png); }

# 96x700: 680 rows a block, 2 blocks. Equirect 512x256 in bands of 32 rows: 127 rows a block, 3 blocks.
FRAME=(--width 96 --height 700 --quality lesson --units relative)
EQ=(--width 512 --projection equirect --quality lesson)
SEQ=("${FRAME[@]}" --animate sun-elevation=2:20 --frame-count 3)
for t in 1 3 16; do
    run "frame$t" -- "${FRAME[@]}" --threads "$t" --render a.png
    run "eq$t" VKSKY_TILE_PIXELS=16384 -- "${EQ[@]}" --threads "$t" --render e.png
done
run seq_ring VKSKY_READBACK_SLOTS=2 -- "${SEQ[@]}" --threads 3 --render f%02d.png
run seq_serial VKSKY_READBACK_SLOTS=1 -- "${SEQ[@]}" --threads 16 --render f%02d.png

for c in frame eq; do
    [ "$(sum "${c}3")" = "$(sum "${c}16")" ] || fail "$c: --threads 3 and 16 wrote different bytes"
    [ "$(sum "${c}1")" != "$(sum "${c}3")" ] || fail "$c: --threads 3 wrote libpng's bytes (the parallel path not taken)"
    f=$(cd "$work/${c}1" && ls -- *.png)
    idiff -q -fail 0 -failpercent 0 -warn 0 "$work/${c}1/$f" "$work/${c}3/$f" >/dev/null 2>&1 ||
        fail "$c: OpenImageIO decodes --threads 1 and --threads 3 to different pixels"
done
[ "$(sum seq_ring | wc -l)" = 3 ] || fail "sequence: $(sum seq_ring | wc -l) frames, expected 3"
[ "$(sum seq_ring)" = "$(sum seq_serial)" ] || fail "sequence: the ring (--threads 3) and the serial loop (16) differ"

[ "$fails" = 0 ] && echo "png_threads: all checks passed"
exit $((fails > 0))
