#!/usr/bin/env bash
# The composite's cost table of the README ("Compositing", **Cost**) on the device this runs on (issue 28 item 6: the
# table predates the fast defaults of 28b and the tile marks of 28c). Seed 004's passes (tests/gen_composite_scene)
# at 1920x1080 and 3840x2160, composited by `vksky --composite --bench N` under validation (--validate: any
# validation message fails the row), the whole image in one band (VKSKY_COMPOSITE_BAND_ROWS: --bench times the first
# band only), medians of N frames after warm-up (the LUTs, built once, not included):
#   default      the defaults (fast paths: the segments' ramp, the sky tiles)
#   march        --steps 32 --max-steps 32 (every pixel its own march: the table's old rows)
#   converged    converged LUTs and 256 steps (--max-steps 256: a fixed count)
# then one whole composite per size without --bench for its CPU seconds (GNU time, user + sys) and wall seconds.
# Prints a Markdown table and writes the raw lines to OUT_DIR.
#
#   tools/composite_cost.sh [BUILD_DIR] [OUT_DIR] [FRAMES]      (defaults: build, composite_cost, 60)
#   COMPOSITE_COST_SIZES="320x180" for a quick check of the script itself
set -u
BUILD=${1:-build}
OUT=${2:-composite_cost}
FRAMES=${3:-60}
VKSKY=$BUILD/vksky
GEN=$BUILD/tests/gen_composite_scene
if [ ! -x "$VKSKY" ] || [ ! -x "$GEN" ]; then
    echo "composite_cost.sh: build vksky and gen_composite_scene in $BUILD first" >&2
    exit 2
fi
mkdir -p "$OUT"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
SUN=(--sun-elevation 20 --sun-azimuth -60)
CONVERGED=(--lut-format f32 --multiscatter-lut 64 --multiscatter-dirs 4096 --multiscatter-steps 64 --steps 256
           --max-steps 256)
status=0
echo "| | upload (host → GPU) | composite pass | readback (6 layers) | frame wall (submit → fence) |"
echo "|---|---|---|---|---|"
for size in ${COMPOSITE_COST_SIZES:-1920x1080 3840x2160}; do
    w=${size%x*} h=${size#*x}
    mkdir -p "$work/$size"
    "$GEN" "$work/$size" "$w" "$h" >/dev/null || { echo "composite_cost.sh: gen_composite_scene failed" >&2; exit 1; }
    for variant in default march converged; do
        case $variant in
            default) extra=() ;;
            march) extra=(--steps 32 --max-steps 32) ;;
            converged) extra=("${CONVERGED[@]}") ;;
        esac
        log=$OUT/bench_${size}_$variant.txt
        if ! VKSKY_COMPOSITE_BAND_ROWS=$h "$VKSKY" --composite "$work/$size/render.exr" --render "$work/out.exr" \
            "${SUN[@]}" "${extra[@]}" --bench "$FRAMES" --validate >"$log" 2>&1; then
            echo "composite_cost.sh: $size $variant failed (see $log)" >&2
            status=1
            continue
        fi
        ms() { awk -v p="$1" '$1 == "pass" && $2 == p { print $4 }' "$log"; }
        wall=$(awk '/composite frame wall_ms/ { print $4 }' "$log")
        echo "| $size, $variant | $(ms composite_upload) ms | $(ms composite) ms | $(ms composite_readback) ms | $wall ms |"
    done
    # The whole composite as a user runs it (bands, the EXR written), CPU and wall.
    /usr/bin/time -f "%U %S %e %M" -o "$OUT/time_$size.txt" "$VKSKY" --composite "$work/$size/render.exr" \
        --render "$work/out.exr" "${SUN[@]}" --validate >"$OUT/run_$size.txt" 2>&1 || status=1
    read -r user sys wall rss <"$OUT/time_$size.txt"
    echo "| $size, whole run (defaults) | CPU $(awk -v u="$user" -v s="$sys" 'BEGIN { print u + s }') s | wall $wall s | peak RSS $((rss / 1024)) MiB | |"
done
"$VKSKY" --version 2>/dev/null | head -1
exit $status
