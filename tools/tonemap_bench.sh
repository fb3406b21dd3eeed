#!/usr/bin/env bash
# The tone map's cost before and after (issue 26 item 1): two vksky binaries, interleaved, each `--bench 5` (medians
# of 5 frames after warm-up) RUNS times per size; prints per binary and size the median over the runs of the
# tone map pass's GPU time (timestamps), the frame's GPU time and the frame's wall time, in ms. A benchmark, not a
# test (docs/horizon.md has the figures). Extra vksky flags after the sizes' defaults: EXTRA="...".
#
#   tools/tonemap_bench.sh OLD/vksky NEW/vksky [RUNS] [SIZES...]     (sizes as WxH; default 640x360 1920x1080)
set -u
OLD=${1:?usage: tonemap_bench.sh OLD/vksky NEW/vksky [RUNS] [WxH...]}
NEW=${2:?}
RUNS=${3:-5}
shift $(($# < 3 ? $# : 3))
SIZES=("$@")
[ ${#SIZES[@]} -gt 0 ] || SIZES=(640x360 1920x1080)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
median() { sort -g | awk '{v[NR] = $1} END {print NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
for size in "${SIZES[@]}"; do
    w=${size%x*} h=${size#*x}
    for run in $(seq 1 "$RUNS"); do
        for which in old new; do
            bin=$OLD
            [ $which = new ] && bin=$NEW
            # shellcheck disable=SC2086
            "$bin" --bench 5 --width "$w" --height "$h" ${EXTRA:-} >"$work/out" 2>&1 || { cat "$work/out"; exit 1; }
            awk '$1 == "pass" && $2 == "tonemap" {print $4}' "$work/out" >>"$work/$which.$size.tonemap"
            awk '$1 == "frame" && $2 == "gpu_ms" {print $3}' "$work/out" >>"$work/$which.$size.gpu"
            awk '$1 == "frame" && $2 == "gpu_ms" {print $5}' "$work/out" >>"$work/$which.$size.wall"
        done
    done
    for which in old new; do
        printf '%-9s %s: tonemap %8.2f ms  frame gpu %8.2f ms  frame wall %8.2f ms  (medians of %d runs)\n' \
            "$size" "$which" "$(median <"$work/$which.$size.tonemap")" "$(median <"$work/$which.$size.gpu")" \
            "$(median <"$work/$which.$size.wall")" "$RUNS"
    done
done
