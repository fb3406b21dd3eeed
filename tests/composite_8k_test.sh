#!/usr/bin/env bash
# The composite of a 7680x4320 render (issue 28 item 6): generated passes (gen_composite_scene "flat": cheap to make
# and to composite, every row through the whole band pipeline), composited under validation; exit 0, a 7680x4320
# output with every layer, and peak resident memory (GNU time) under 1 GiB. Before the bands: refused ("6 layers
# of 2730 rows at most"), and 2.9 GB at 3840x2160.
#
#   composite_8k_test.sh VKSKY GEN_COMPOSITE_SCENE
set -u
VKSKY=${1:?usage: composite_8k_test.sh VKSKY GEN_COMPOSITE_SCENE}
GEN=${2:?}
TIME=/usr/bin/time
[ -x "$TIME" ] || { echo "composite_8k_test: no GNU time (Debian package time): skipped"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$GEN" "$work" 7680 4320 flat || { echo "FAIL: gen_composite_scene"; exit 1; }
limit_kb=$((1024 * 1024))
"$TIME" -f "%M" -o "$work/rss" "$VKSKY" --composite "$work/render.exr" --render "$work/out.exr" \
    --camera-position -3.5,-8.5,218.8 --validate 2>"$work/err"
rc=$?
fails=0
[ $rc -eq 0 ] || { echo "FAIL: exit $rc ($(cat "$work/err"))"; fails=1; }
rss=$(tail -n 1 "$work/rss")
echo "composite_8k_test: 7680x4320 composite, peak resident memory $((rss / 1024)) MiB (limit $((limit_kb / 1024)) MiB)"
[ "$rss" -lt "$limit_kb" ] 2>/dev/null || { echo "FAIL: peak memory ${rss} KiB over ${limit_kb} KiB"; fails=1; }
if command -v oiiotool >/dev/null; then
    info=$(oiiotool --info "$work/out.exr" 2>&1)
    grep -q "7680 x 4320, 19 channel" <<<"$info" || { echo "FAIL: output is not 7680x4320 with 19 channels: $info"; fails=1; }
fi
[ $fails -eq 0 ] || exit 1
# The size check needs oiiotool: without it the test SKIPs (77), never passes (issue 31).
command -v oiiotool >/dev/null || { echo "composite_8k_test: SKIP: the size check needs oiiotool (openimageio-tools)"; exit 77; }
echo "composite_8k_test: ok"
