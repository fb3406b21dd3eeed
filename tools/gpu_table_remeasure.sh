#!/usr/bin/env bash
# tools/gpu_table_remeasure.sh [BUILD] [OUT]: re-measure the GPU quality table (src/app/quality/quality_table.h) on the
# GPU this runs on, at the frame size the promise is held at, and check the promise with it (issue 31 item 4).
#
# Why not swap in docs/perf/h100-issue31/: its two tables bracket the promise test's 640x360 frames and neither
# holds it. The table's own method (error of 96x54 frames) keeps twilight's row of
# medium-skyview96-s24-scale0.5-bloomq at 0.498 % (the H100 measured 0.52 % at 640x360: --max-error 0.005 fails as
# before); the 1920x1080-frame variant fixes twilight (0.504 %: the pick moves to medium) but puts afternoon's
# medium-skyview96-scale0.5 at 0.976 % (1.50 % with 96x54 frames), which auto and --max-error 0.01 would then pick
# with no measurement at 640x360 behind it. A table measured at 640x360 frames is the promise's own size: a
# configuration's error only shrinks on larger frames (its LUT and render scale are fixed).
#
# Steps (validation on for the promise's renders, as in ctest): tradeoff at 1920x1080 cost, 640x360 error frames
# sampled at 96x54; the emitted table (with this build's key) replaces quality_table.h; rebuild; ctest promise,
# quality_auto, claims and cli. The README's H100 preset table (ctest claims) must then be updated from the new rows.
# Run on the device (not on the 2-core machine): about 5-10 minutes on an H100.
set -u
BUILD=${1:-build}
OUT=${2:-${OUT:-/tmp/gpu_table}}
mkdir -p "$OUT"
"$BUILD/tradeoff" --size 1920x1080 --frames 30 --error-render 640x360 --error-size 96x54 \
    --csv "$OUT/tradeoff_640x360frames.csv" --emit-table "$OUT/quality_table.h" >"$OUT/tradeoff.log" 2>&1 ||
    { echo "tradeoff failed: $(tail -5 "$OUT/tradeoff.log")"; exit 1; }
cp "$OUT/quality_table.h" src/app/quality/quality_table.h
cmake --build "$BUILD" -j"$(nproc)" >"$OUT/build.log" 2>&1 || { echo "build failed: $(tail -5 "$OUT/build.log")"; exit 1; }
(cd "$BUILD" && VKSKY_VALIDATION=1 ctest -R '^(promise|quality_auto|claims|cli)$' --output-on-failure) >"$OUT/ctest.log" 2>&1
rc=$?
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >"$OUT/device.txt" 2>/dev/null
tail -30 "$OUT/ctest.log"
echo "table: $OUT/quality_table.h (copy it to src/app/quality/quality_table.h if the promise passed); ctest exit $rc"
exit $rc
