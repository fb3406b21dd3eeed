#!/usr/bin/env bash
# The 4K composite's wall and CPU seconds, two builds alternating (issue 28 item 6: <= 5.57 s wall on an idle 2-core
# lavapipe machine). Seed 004's passes at 3840x2160 (tests/gen_composite_scene), composited by
#   vksky --composite DIR/render.exr --render out.exr --sun-elevation 20 --sun-azimuth -60
# with OLD and NEW in turn, RUNS times each (OLD, NEW, OLD, NEW, ...: a load that changes during the runs falls on
# both alike); prints the medians of wall and CPU (user + sys, GNU time) per build and NEW/OLD's ratios. On a loaded
# machine wall seconds are the load's; CPU seconds and their ratio are the measure.
#
#   tools/composite_wall.sh OLD_VKSKY NEW_VKSKY [RUNS]          (RUNS: 3)
#   COMPOSITE_WALL_TASKSET="0,1"   run each under taskset -c 0,1 (two cores, as the CI machine)
#   COMPOSITE_WALL_SIZE=1920x1080  another size (default 3840x2160)
#   COMPOSITE_WALL_SCENE=DIR       reuse a scene generated before (DIR/render.exr)
#   COMPOSITE_WALL_GEN=PATH        gen_composite_scene (default: NEW's build dir/tests/gen_composite_scene)
set -u
if [ $# -lt 2 ]; then
    echo "usage: tools/composite_wall.sh OLD_VKSKY NEW_VKSKY [RUNS]" >&2
    exit 2
fi
OLD=$1 NEW=$2 RUNS=${3:-3}
case $RUNS in ''|*[!0-9]*|0) echo "composite_wall.sh: RUNS must be a positive integer, got '$RUNS'" >&2; exit 2 ;; esac
for b in "$OLD" "$NEW"; do
    [ -x "$b" ] || { echo "composite_wall.sh: $b is not an executable vksky" >&2; exit 2; }
done
[ -x /usr/bin/time ] || { echo "composite_wall.sh: needs GNU time (/usr/bin/time, Debian package time)" >&2; exit 2; }
SIZE=${COMPOSITE_WALL_SIZE:-3840x2160}
W=${SIZE%x*} H=${SIZE#*x}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
SCENE=${COMPOSITE_WALL_SCENE:-}
LABEL=$SIZE
[ -n "$SCENE" ] && LABEL=$SCENE/render.exr
if [ -z "$SCENE" ]; then
    GEN=${COMPOSITE_WALL_GEN:-$(dirname "$NEW")/tests/gen_composite_scene}
    [ -x "$GEN" ] || { echo "composite_wall.sh: no gen_composite_scene at $GEN (set COMPOSITE_WALL_GEN)" >&2; exit 2; }
    SCENE=$work/scene
    mkdir -p "$SCENE"
    "$GEN" "$SCENE" "$W" "$H" >/dev/null || { echo "composite_wall.sh: gen_composite_scene failed" >&2; exit 1; }
fi
PIN=()
[ -n "${COMPOSITE_WALL_TASKSET:-}" ] && PIN=(taskset -c "$COMPOSITE_WALL_TASKSET")

# One run: "wall cpu" on stdout.
run_one() {
    /usr/bin/time -f "%e %U %S" -o "$work/time" "${PIN[@]}" "$1" --composite "$SCENE/render.exr" \
        --render "$work/out.exr" --sun-elevation 20 --sun-azimuth -60 >/dev/null 2>"$work/err" ||
        { echo "composite_wall.sh: $1 failed:" >&2; cat "$work/err" >&2; exit 1; }
    awk '{ printf "%.2f %.2f\n", $1, $2 + $3 }' "$work/time"
}
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

: >"$work/old" && : >"$work/new"
for i in $(seq "$RUNS"); do
    r=$(run_one "$OLD") || exit 1; echo "$r" >>"$work/old"; echo "run $i old: wall $r (wall cpu)" | sed 's/wall \([^ ]*\) \([^ ]*\) (wall cpu)/wall \1 s, cpu \2 s/'
    r=$(run_one "$NEW") || exit 1; echo "$r" >>"$work/new"; echo "run $i new: wall $r (wall cpu)" | sed 's/wall \([^ ]*\) \([^ ]*\) (wall cpu)/wall \1 s, cpu \2 s/'
done
ow=$(cut -d' ' -f1 "$work/old" | median) oc=$(cut -d' ' -f2 "$work/old" | median)
nw=$(cut -d' ' -f1 "$work/new" | median) nc=$(cut -d' ' -f2 "$work/new" | median)
echo "$LABEL composite, medians of $RUNS (load at the end: $(cut -d' ' -f1-3 /proc/loadavg)):"
echo "  old $OLD: wall $ow s, cpu $oc s"
echo "  new $NEW: wall $nw s, cpu $nc s"
awk -v ow="$ow" -v oc="$oc" -v nw="$nw" -v nc="$nc" \
    'BEGIN { printf "  new/old: wall %.3f, cpu %.3f (speed-up %.2fx wall, %.2fx cpu)\n", nw / ow, nc / oc, ow / nw, oc / nc }'
