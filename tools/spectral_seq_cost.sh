#!/usr/bin/env bash
# tools/spectral_seq_cost.sh VKSKY [WxH] [RUNS] [N]: a spectral sequence frame's CPU cost on this device against an
# RGB frame's (issue 32, 32j: the groups summed on the GPU), a benchmark, not a test. For each mode (the GPU's sum, the
# default; the host's sum, VKSKY_SPECTRAL_SUM=host; RGB, --spectral 0) it runs the sequence (sun -6 -> 30) of 1 and of
# 4 frames RUNS times (default 3) at WxH (default 960x540, --quality cpu, EXR) and prints the medians of CPU seconds
# (user + system) and wall seconds, and a frame's cost as (4 frames - 1 frame) / 3. Validation off (a benchmark);
# tools/compare_spectral.sh and ctest spectral_gpu validate the same paths. On lavapipe the CPU seconds are the figure.
set -u
V=${1:?usage: spectral_seq_cost.sh VKSKY [WxH] [RUNS] [N]}
SIZE=${2:-960x540}
RUNS=${3:-3}
N=${4:-24}
W=${SIZE%x*} H=${SIZE#*x}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
median() { sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
# run MODE FRAMES: the medians "cpu wall" of RUNS runs
run() {
    local mode=$1 frames=$2 env=() spectral=(--spectral "$N")
    [ "$mode" = host ] && env=(VKSKY_SPECTRAL_SUM=host)
    [ "$mode" = rgb ] && spectral=(--spectral 0)
    for _ in $(seq "$RUNS"); do
        rm -f "$work"/f*.exr
        env "${env[@]}" /usr/bin/time -f "%U %S %e" -o "$work/t" "$V" --width "$W" --height "$H" --quality cpu \
            --animate sun-elevation=-6:30 --frame-count "$frames" "${spectral[@]}" --quiet \
            --render "$work/f%02d.exr" >/dev/null 2>"$work/err" || { echo "run failed: $(cat "$work/err")" >&2; exit 1; }
        awk '{ print $1 + $2, $3 }' "$work/t"
    done >"$work/runs"
    echo "$(awk '{ print $1 }' "$work/runs" | median) $(awk '{ print $2 }' "$work/runs" | median)"
}
"$V" --list-devices | head -2
echo "mode  1-frame cpu/wall  4-frame cpu/wall  frame cpu s  frame wall s  ($SIZE, --spectral $N, medians of $RUNS)"
for mode in gpu host rgb; do
    read -r c1 w1 <<<"$(run "$mode" 1)"
    read -r c4 w4 <<<"$(run "$mode" 4)"
    awk -v m="$mode" -v c1="$c1" -v w1="$w1" -v c4="$c4" -v w4="$w4" \
        'BEGIN { printf "%-5s %6.2f %6.2f      %6.2f %6.2f      %6.3f       %6.3f\n", m, c1, w1, c4, w4, (c4 - c1) / 3, (w4 - w1) / 3 }'
done
