#!/usr/bin/env bash
# tools/spectral_cost.sh VKSKY [WxH] [RUNS] [N...]: the GPU's cost of --spectral N per wavelength (issue 32 item 1),
# a benchmark, not a test. For each N (default 0 4 8 16 24 32 48) and each packing (four wavelengths a pass, the
# default, and three: VKSKY_SPECTRAL_PACK=3, as before the four-wide build): one warm-up render, then RUNS (default 5) renders
# of a still EXR frame at WxH (default 640x360; --quality high, --no-bloom, sunset), each timed as a whole process:
# wall seconds and CPU seconds (user + system). Prints the medians, the passes (renderer runs) each N takes, and the
# cost per wavelength over RGB: (median(N) - median(0)) / N. Every render runs with --validate (a validation
# message fails the run).
#   tools/spectral_cost.sh build/vksky 640x360 5            # lavapipe: CPU seconds are the figure to read
#   tools/spectral_cost.sh build/vksky 1920x1080 9          # a GPU: wall seconds (whole process, device start included)
#   tools/spectral_cost.sh build/vksky 1920x1080 9 0 16 24 32 48   # the H100 lines for the coordinator (issue 32)
set -euo pipefail
VKSKY=${1:?usage: tools/spectral_cost.sh path/to/vksky [WxH] [RUNS] [N...]}
size=${2:-640x360}
runs=${3:-5}
shift $(($# < 3 ? $# : 3))
counts=("$@")
[ ${#counts[@]} -gt 0 ] || counts=(0 4 8 16 24 32 48)
w=${size%x*} h=${size#*x}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
# The renderer runs --spectral N takes: four wavelengths a run (the four-wide build, the default) or three
# (VKSKY_SPECTRAL_PACK=3: the RGB shaders, the packing before issue 32's SPECTRAL4 build).
passes() { if [ "$1" -eq 0 ]; then echo 1; else echo $((($1 + $2 - 1) / $2)); fi; }
device=$("$VKSKY" --list-devices 2>/dev/null | head -1 || true)
echo "device: ${device:-unknown}; $VKSKY at ${w}x${h}, median of $runs after one warm-up"
printf '%-6s %-5s %-7s %-10s %-10s %-22s\n' N pack passes wall_s cpu_s "cpu_s per wavelength"
base_cpu=""
for n in "${counts[@]}"; do
    args=(--width "$w" --height "$h" --quality high --no-bloom --sun-elevation 2 --pitch 10 --validate
          --render "$work/s.exr")
    [ "$n" -eq 0 ] || args+=(--spectral "$n")
    packs=(4 3)
    [ "$n" -gt 0 ] || packs=(-)
    for pack in "${packs[@]}"; do
        env=()   # the packing forced (by itself --spectral takes three where the horizon is in the frame)
        [ "$pack" = - ] || env=(VKSKY_SPECTRAL_PACK="$pack")
        env "${env[@]}" "$VKSKY" "${args[@]}" >/dev/null   # warm-up (pipeline cache, page cache)
        : >"$work/wall"; : >"$work/cpu"
        for _ in $(seq "$runs"); do
            env "${env[@]}" /usr/bin/time -f '%e %U %S' -o "$work/t" "$VKSKY" "${args[@]}" >/dev/null
            read -r e u s <"$work/t"
            echo "$e" >>"$work/wall"
            awk -v u="$u" -v s="$s" 'BEGIN { print u + s }' >>"$work/cpu"
        done
        wall=$(median <"$work/wall") cpu=$(median <"$work/cpu")
        [ -n "$base_cpu" ] || base_cpu=$cpu
        per=$([ "$n" -eq 0 ] && echo "-" || awk -v c="$cpu" -v b="$base_cpu" -v n="$n" 'BEGIN { printf "%.3f", (c - b) / n }')
        printf '%-6s %-5s %-7s %-10s %-10s %-22s\n' "$n" "$pack" "$(passes "$n" "${pack/-/4}")" "$wall" "$cpu" "$per"
    done
done
