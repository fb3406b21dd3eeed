#!/usr/bin/env bash
# tools/lut_cache_bench.sh [VKSKY] [RUNS]: the LUT cache's warm start (issue 27), wall and CPU seconds (user + sys),
# medians of RUNS (default 5) after one warm-up run of each: `--list-devices`, a warm 33x33 render without the LUT
# cache (VKSKY_LUT_CACHE=0: the pipeline cache only, as before it) and with it (the LUTs uploaded). Every render
# validated (VKSKY_VALIDATION=1 would add the layer's own start-up; pass VALIDATE=1 to include it). A private cache
# directory; nothing of the user's is touched. Prints one table.
set -u
VKSKY=${1:-$(dirname "$0")/../build/vksky}
RUNS=${2:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export XDG_CACHE_HOME="$work/xdg"
[ -n "${VALIDATE:-}" ] && export VKSKY_VALIDATION=1
cd "$work" || exit 1
# one LABEL ENV... -- ARGS: RUNS timed runs after a warm-up; prints "LABEL wall cpu" medians.
one() {
    local label=$1; shift
    local envs=()
    while [ "$1" != -- ]; do envs+=("$1"); shift; done
    shift
    env "${envs[@]}" "$VKSKY" "$@" >/dev/null 2>&1 || { echo "$label: vksky failed" >&2; return 1; }
    for _ in $(seq "$RUNS"); do
        /usr/bin/time -f '%e %U %S' -o t.txt env "${envs[@]}" "$VKSKY" "$@" >/dev/null 2>&1
        awk '{ printf "%s %.3f\n", $1, $2 + $3 }' t.txt
    done >runs.txt
    local m=$(( (RUNS + 1) / 2 ))
    printf '%-34s %8s %8s\n' "$label" "$(cut -d' ' -f1 runs.txt | sort -n | sed -n "${m}p")" \
        "$(cut -d' ' -f2 runs.txt | sort -n | sed -n "${m}p")"
}
printf '%-34s %8s %8s\n' "median of $RUNS" "wall s" "CPU s"
one "--list-devices" VKSKY_LUT_CACHE=0 -- --list-devices
one "33x33 warm, no LUT cache" VKSKY_LUT_CACHE=0 -- --width 33 --height 33 --render a.png
one "33x33 warm, LUT cache" VKSKY_LUT_CACHE=1 -- --width 33 --height 33 --render a.png
one "--scene mars 33x33, no LUT cache" VKSKY_LUT_CACHE=0 -- --scene mars --width 33 --height 33 --render a.png
one "--scene mars 33x33, LUT cache" VKSKY_LUT_CACHE=1 -- --scene mars --width 33 --height 33 --render a.png
"$VKSKY" --list-devices 2>/dev/null | head -3
