#!/usr/bin/env bash
# Throughput to disk (issue 27 item 4): frames/s of sequences by resolution, format and setting, HDRI seconds by
# size, the first image's latency, EXR compression size vs time. A benchmark, not a test: run it on an idle machine
# and name the device, the driver and the cores with the figures (docs/performance.md, "Throughput to disk").
#
#   tools/throughput_bench.sh VKSKY [BASELINE_VKSKY] [OUT_DIR]
#
# Files go to a scratch directory (removed at the end); one line per measurement on stdout:
#   case <name> frames <n> wall_s <s> frames_per_s <f> bytes_per_frame <b> [peak_mb <m>]
# SEQ_FRAMES (default 120) sets the sequences' length; QUICK=1 runs only the headline cases; SPECTRAL=1 only the
# spectral sequence (issue 25s, spectral_720p); GOALS=1 only the issue 27
# goal cases with their stage breakdowns (--timings) and the 720p compression table (about 3 minutes on the H100
# host; see "Goals" at the end). PNG cases (issue 27):
# sequences and a 16384x8192 equirect with the default threads against --threads 1, and build/tests/test_png_parallel
# bench (encode alone, medians by thread count) when it is found beside VKSKY.
set -u
V=${1:?usage: throughput_bench.sh VKSKY [BASELINE_VKSKY] [OUT_DIR]}
BASE=${2:-}
# Absolute paths: some cases run from a scratch directory of their own (cd), where a relative path would not resolve.
V=$(readlink -f "$V")
[ -n "$BASE" ] && BASE=$(readlink -f "$BASE")
scratch=$(mktemp -d "${3:-${TMPDIR:-/tmp}}/vksky_tp.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
N=${SEQ_FRAMES:-120}
ANIM=(--animate sun-elevation=-6:30 --quiet)

# measure NAME FRAMES BIN ARGS...: wall time of the whole run (start-up included), files' bytes, peak RSS; with
# --timings among ARGS, the stage table (app/runs/stage_times.c) follows, each line prefixed "  NAME: stage".
measure() {
    local name=$1 frames=$2 bin=$3; shift 3
    rm -rf "$scratch/o"; mkdir -p "$scratch/o"
    local t0 t1 rss
    t0=$(date +%s.%N)
    local timer=()
    [ -x /usr/bin/time ] && timer=(/usr/bin/time -f '%M' -o "$scratch/rss")
    echo -1 >"$scratch/rss"
    "${timer[@]}" "$bin" "$@" >"$scratch/stdout" 2>"$scratch/stderr" ||
        { echo "case $name FAILED: $(tail -1 "$scratch/stderr")"; return; }
    t1=$(date +%s.%N)
    rss=$(tail -1 "$scratch/rss")
    local bytes
    bytes=$(du -sb "$scratch/o" | awk '{print $1}')
    awk -v n="$name" -v f="$frames" -v a="$t0" -v b="$t1" -v by="$bytes" -v r="$rss" 'BEGIN {
        s = b - a; printf "case %s frames %d wall_s %.3f frames_per_s %.2f bytes_per_frame %d peak_mb %.0f\n",
        n, f, s, f / s, by / f, r / 1024 }'
    grep '^sequence ' "$scratch/stdout" | sed "s/^/  $name: /"
    grep -E '^vksky: timings of the (sequence|banded)|^  [a-z.(]' "$scratch/stderr" | sed "s/^/  $name: stage /"
}

seq_case() {   # seq_case NAME BIN W H EXT FRAMES [ARGS...]
    local name=$1 bin=$2 w=$3 h=$4 ext=$5 frames=$6; shift 6
    measure "$name" "$frames" "$bin" --width "$w" --height "$h" "${ANIM[@]}" --frame-count "$frames" \
        --render "$scratch/o/f%04d.$ext" "$@"
}

nproc_all=$(nproc)
echo "host cores $nproc_all"
"$V" --list-devices | head -3
"$V" --width 16 --height 16 --render "$scratch/warm.exr" >/dev/null 2>&1   # driver and shader caches warm

# Issue 25s: the spectral sequence (24 wavelengths, the sun -6 -> 30) through include/vksky.h: a renderer per
# wavelength group keeping its LUTs, each frame's groups in one submission, the sum on the GPU (32j; the host's sum
# beside it: spectral_720p_hostsum). First a validated
# check (any validation line fails it), then the goal case with the RGB case beside it; the baseline (main's serial
# loop: 3.7 frames/s on the H100, docs/perf/h100-2026-11-28-h) in the same run when given. SPECTRAL=1: only these.
spectral_cases() {
    mkdir -p "$scratch/sp"
    (cd "$scratch/sp" && "$V" --width 320 --height 180 --animate sun-elevation=-6:30 --frame-count 3 --spectral 24 \
        --quiet --validate --render s%02d.exr 2>serr)
    echo "check spectral_sequence rc $? validation_lines $(grep -ci validation "$scratch/sp/serr")"
    seq_case spectral_720p "$V" 1280 720 exr 24 --spectral 24 --timings
    # 32j: the groups summed on the GPU (one readback a frame; the default) against the same build's host sum (each
    # group read back and summed on the encode threads, VKSKY_SPECTRAL_SUM=host), and a PNG sequence (host tone map).
    VKSKY_SPECTRAL_SUM=host seq_case spectral_720p_hostsum "$V" 1280 720 exr 24 --spectral 24
    seq_case spectral_720p_png "$V" 1280 720 png 24 --spectral 24
    seq_case spectral_720p_rgb "$V" 1280 720 exr 24
    [ -n "$BASE" ] && seq_case base_spectral_720p "$BASE" 1280 720 exr 24 --spectral 24
}
if [ "${SPECTRAL:-0}" = 1 ]; then
    spectral_cases
    exit 0
fi

# Goals (issue 27, helper 27e): frames encoding at once (the ring's consumer threads: VKSKY_ENCODE_FRAMES, default
# one per 4 cores, at most 3) against one frame at a time, with where the time goes (--timings: wall and CPU ms per
# stage, summed over threads); the 720p compression table (size vs time, float EXR); the 16384x8192 map's stages.
# First a validated check: several frames at once write the serial loop's bytes on this driver.
if [ "${GOALS:-0}" = 1 ]; then
    G=${SEQ_FRAMES:-120}
    mkdir -p "$scratch/c1" "$scratch/c3"
    CHK=(--width 640 --height 360 --animate sun-elevation=-6:30 --frame-count 12 --quiet --validate)
    (cd "$scratch/c1" && VKSKY_READBACK_SLOTS=1 "$V" "${CHK[@]}" --threads 1 --render f%02d.exr 2>err)
    r1=$?
    (cd "$scratch/c3" && VKSKY_ENCODE_FRAMES=3 "$V" "${CHK[@]}" --render f%02d.exr 2>err)
    r3=$?
    same=no
    [ "$(cd "$scratch/c1" && md5sum f*.exr)" = "$(cd "$scratch/c3" && md5sum f*.exr)" ] && same=yes
    msgs=$(cat "$scratch/c1/err" "$scratch/c3/err" | grep -ci validation)
    echo "check encode_frames serial_rc $r1 three_at_once_rc $r3 identical $same validation_lines $msgs"
    for k in 1 2 3; do
        VKSKY_ENCODE_FRAMES=$k seq_case "720p_exr_frames$k" "$V" 1280 720 exr "$G" --timings
    done
    seq_case 720p_exr_default "$V" 1280 720 exr "$G" --bench 10
    seq_case 720p_exr_zip4 "$V" 1280 720 exr "$G" --exr-compression zip:4
    seq_case 720p_exr_relative_half "$V" 1280 720 exr "$G" --units relative
    for k in 1 3; do
        VKSKY_ENCODE_FRAMES=$k seq_case "1080p_exr_frames$k" "$V" 1920 1080 exr "$G" --timings
    done
    seq_case 1080p_exr_zip4 "$V" 1920 1080 exr "$G" --exr-compression zip:4
    seq_case 720p_png "$V" 1280 720 png "$G" --timings
    # --threads 1: every stage on the calling thread, so the CPU column is the frame's whole cost per stage.
    seq_case 720p_exr_threads1 "$V" 1280 720 exr 24 --threads 1 --timings
    for c in zip zip:1 zip:4 zips piz pxr24 rle b44 none dwaa; do
        seq_case "720p_exr_$c" "$V" 1280 720 exr 60 --exr-compression "$c"
        seq_case "720p_exr_${c}_threads1" "$V" 1280 720 exr 12 --exr-compression "$c" --threads 1 --timings
    done
    for w in 4096 8192 16384; do
        measure "equirect_$w" 1 "$V" --projection equirect --width "$w" --render "$scratch/o/e.exr" --quiet --timings
    done
    measure equirect_16384_relative 1 "$V" --projection equirect --width 16384 --render "$scratch/o/e.exr" --quiet \
        --units relative --timings
    measure equirect_4096_threads1 1 "$V" --projection equirect --width 4096 --render "$scratch/o/e.exr" --quiet \
        --threads 1 --timings
    for i in 1 2 3; do measure "first_1080p_exr_$i" 1 "$V" --width 1920 --height 1080 --render "$scratch/o/a.exr"; done
    # Helper 27f: ZIP chunks through libdeflate and the chunk pool across bands. With BASELINE_VKSKY (a build before
    # them), its headline goal cases in the same run; then zlib vs libdeflate per chunk on a rendered 720p float
    # frame, and libpng's settings on a 720p PNG (build/tests/test_exr_deflate, build/png_settings_bench beside VKSKY).
    if [ -n "$BASE" ]; then
        seq_case base_720p_exr_default "$BASE" 1280 720 exr "$G" --bench 10
        seq_case base_1080p_exr_default "$BASE" 1920 1080 exr "$G"
        seq_case base_720p_exr_threads1 "$BASE" 1280 720 exr 24 --threads 1 --timings
        measure base_equirect_16384 1 "$BASE" --projection equirect --width 16384 --render "$scratch/o/e.exr" --quiet
        for i in 1 2 3; do measure "base_first_1080p_exr_$i" 1 "$BASE" --width 1920 --height 1080 --render "$scratch/o/a.exr"; done
    fi
    spectral_cases
    "$V" --width 1280 --height 720 --render "$scratch/f720.exr" --render "$scratch/p720.png" --quiet
    d=$(dirname "$(readlink -f "$V")")
    [ -x "$d/tests/test_exr_deflate" ] && "$d/tests/test_exr_deflate" bench "$scratch/f720.exr" 7 | sed 's/^/exr_deflate_bench /'
    [ -x "$d/png_settings_bench" ] && "$d/png_settings_bench" "$scratch/p720.png" 5 | sed 's/^/png_settings_bench /'
    exit 0
fi

# Headline: 720p and 1080p EXR sequences; the baseline binary beside them when given.
[ -n "$BASE" ] && seq_case base_720p_exr "$BASE" 1280 720 exr 60
seq_case 720p_exr "$V" 1280 720 exr "$N"
[ -n "$BASE" ] && seq_case base_1080p_exr "$BASE" 1920 1080 exr 30
seq_case 1080p_exr "$V" 1920 1080 exr "$N"
seq_case 720p_exr_bench "$V" 1280 720 exr "$N" --bench 30
[ "${QUICK:-0}" = 1 ] && exit 0

# What each part buys: the ring off (serial loop), one encode thread, both.
VKSKY_READBACK_SLOTS=1 seq_case 720p_exr_serial "$V" 1280 720 exr "$N"
seq_case 720p_exr_threads1 "$V" 1280 720 exr "$N" --threads 1
VKSKY_READBACK_SLOTS=1 seq_case 720p_exr_serial_threads1 "$V" 1280 720 exr "$N" --threads 1
seq_case 720p_png "$V" 1280 720 png "$N"
seq_case 720p_png_threads1 "$V" 1280 720 png "$N" --threads 1   # libpng on one core (today's bytes)
[ -n "$BASE" ] && seq_case base_720p_png "$BASE" 1280 720 png 60
seq_case 1080p_png "$V" 1920 1080 png 60
seq_case 1080p_png_threads1 "$V" 1920 1080 png 60 --threads 1
seq_case 320x180_exr "$V" 320 180 exr "$N"
seq_case 4k_exr "$V" 3840 2160 exr 30

# EXR compression: size vs time (1080p).
for c in zip zip:1 zip:4 zips piz pxr24 b44 rle none; do
    seq_case "1080p_exr_$c" "$V" 1920 1080 exr 60 --exr-compression "$c"
done

# HDRIs (equirect, banded), and the first image.
for w in 4096 8192 16384; do
    measure "equirect_$w" 1 "$V" --projection equirect --width "$w" --render "$scratch/o/e.exr" --quiet
done
[ -n "$BASE" ] && measure base_equirect_16384 1 "$BASE" --projection equirect --width 16384 --render "$scratch/o/e.exr" --quiet
# A large PNG: its image data on worker threads (src/io/png_parallel.c) against libpng on one core.
for t in 0 1; do
    thr=(); [ "$t" = 1 ] && thr=(--threads 1)
    measure "equirect_16384_png_threads${t/0/all}" 1 "$V" --projection equirect --width 16384 \
        --render "$scratch/o/e.png" --quiet "${thr[@]}"
done
[ -n "$BASE" ] && measure base_equirect_16384_png 1 "$BASE" --projection equirect --width 16384 --render "$scratch/o/e.png" --quiet
# PNG encode alone (no render): medians by thread count, when the build's test program is beside the binary.
pb="$(dirname "$V")/tests/test_png_parallel"
if [ -x "$pb" ]; then "$pb" bench 1280 720 9; "$pb" bench 3840 2160 5; fi
for i in 1 2 3; do measure "first_1080p_exr_$i" 1 "$V" --width 1920 --height 1080 --render "$scratch/o/a.exr"; done
[ -n "$BASE" ] && measure base_first_1080p_exr 1 "$BASE" --width 1920 --height 1080 --render "$scratch/o/a.exr"
exit 0
