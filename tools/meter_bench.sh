#!/usr/bin/env bash
# tools/meter_bench.sh [--runs N] [--size WxH] OLD_VKSKY NEW_VKSKY: what auto exposure costs a headless PNG, before
# (OLD: metered on the CPU, the frame rendered twice) and after (NEW: metered on the GPU inside the one render; issue
# 32). Each build renders the same auto-exposed photometric PNG (default 1920x1080, the default view, --validate off:
# a benchmark) RUNS times (default 5) after one warm-up run (the pipeline cache on disk, the page cache); prints the
# median of the process's CPU time (user + sys: on a CPU device, lavapipe, that is the frame's work whatever else the
# machine runs) and of the wall time, and the medians' difference. Also one validated run of each, so a figure never
# comes from a frame that validation would reject. On a GPU the same script gives wall times (CPU time is then the
# host's share only). Example: tools/meter_bench.sh /work/main/build/vksky build/vksky
set -euo pipefail
runs=5
size=1920x1080
while [ $# -gt 2 ]; do
    case $1 in
    --runs) runs=${2:?}; shift 2 ;;
    --size) size=${2:?}; shift 2 ;;
    *) echo "usage: tools/meter_bench.sh [--runs N] [--size WxH] OLD_VKSKY NEW_VKSKY" >&2; exit 2 ;;
    esac
done
[ $# -eq 2 ] || { echo "usage: tools/meter_bench.sh [--runs N] [--size WxH] OLD_VKSKY NEW_VKSKY" >&2; exit 2; }
w=${size%x*}; h=${size#*x}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
measure() {   # measure LABEL VKSKY: "LABEL cpu_s wall_s" (medians)
    local label=$1 bin=$2 args=(--width "$w" --height "$h" --quiet --render "$work/out.png")
    "$bin" "${args[@]}" --validate >/dev/null 2>"$work/err" || { echo "$label: validated run failed: $(cat "$work/err")" >&2; exit 1; }
    "$bin" "${args[@]}" >/dev/null 2>&1   # warm-up
    : >"$work/times"
    for _ in $(seq "$runs"); do /usr/bin/time -f "%U %S %e" -a -o "$work/times" "$bin" "${args[@]}" >/dev/null 2>&1; done
    echo "$label $(awk '{ print $1 + $2 }' "$work/times" | median) $(awk '{ print $3 }' "$work/times" | median)"
}
device=$("$2" --list-devices 2>/dev/null | head -1 || true)
echo "auto-exposed PNG ${w}x${h}, $runs runs each, medians; device: ${device:-?}"
old=$(measure before "$1"); new=$(measure after "$2")
echo "$old" | awk '{ printf "before (CPU meter, two renders): CPU %.2f s, wall %.2f s\n", $2, $3 }'
echo "$new" | awk '{ printf "after  (GPU meter, one render):  CPU %.2f s, wall %.2f s\n", $2, $3 }'
paste <(echo "$old") <(echo "$new") | awk '{ printf "saved: CPU %.2f s (%.0f %%), wall %.2f s\n", $2 - $5, 100 * ($2 - $5) / $2, $3 - $6 }'
