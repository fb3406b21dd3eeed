#!/usr/bin/env bash
# tools/composite_wall.sh OLD_VKSKY NEW_VKSKY [RUNS]: issue 28 item 6's figure, the 3840x2160 composite's wall and CPU
# seconds (GNU time: elapsed, user + sys) of two builds, RUNS (default 3) runs each, alternating OLD, NEW, OLD, ...
# after one warm-up run of each (the LUT and pipeline caches warm), medians printed; the two outputs must be the same
# pixels. Run it on an idle machine; TASKSET="0,1" pins both to those cores (the 2-core CI machine's shape).
# The scene: gen_composite_scene DIR 3840 2160 (GEN, default build/tests/gen_composite_scene next to NEW_VKSKY);
# the command: vksky --composite DIR/render.exr --render OUT.exr --sun-elevation 20 --sun-azimuth -60.
set -u
OLD=${1:?usage: composite_wall.sh OLD_VKSKY NEW_VKSKY [RUNS]}
NEW=${2:?usage: composite_wall.sh OLD_VKSKY NEW_VKSKY [RUNS]}
RUNS=${3:-3}
GEN=${GEN:-$(dirname "$NEW")/tests/gen_composite_scene}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$GEN" "$work" 3840 2160 >/dev/null || { echo "gen_composite_scene failed ($GEN)"; exit 2; }
pin=()
[ -n "${TASKSET:-}" ] && pin=(taskset -c "$TASKSET")
one() {   # bin tag -> appends "wall cpu" to $work/tag.times
  /usr/bin/time -f '%e %U %S' -o "$work/t" "${pin[@]}" "$1" --composite "$work/render.exr" --render "$work/$2.exr" \
    --sun-elevation 20 --sun-azimuth -60 >/dev/null 2>"$work/$2.err" || { echo "$1 failed: $(cat "$work/$2.err")"; exit 1; }
  awk '{ printf "%s %.2f\n", $1, $2 + $3 }' "$work/t" >>"$work/$2.times"
}
one "$OLD" warm_old; one "$NEW" warm_new
for ((i = 0; i < RUNS; i++)); do one "$OLD" old; one "$NEW" new; done
median() { sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
for tag in old new; do
  wall=$(cut -d' ' -f1 "$work/$tag.times" | median) cpu=$(cut -d' ' -f2 "$work/$tag.times" | median)
  echo "$tag: wall ${wall} s, cpu ${cpu} s (median of $RUNS; runs: $(cut -d' ' -f1 "$work/$tag.times" | paste -sd' '))"
done
/usr/bin/python3 - "$work/old.exr" "$work/new.exr" <<'PY' && echo "outputs: the same pixels" || { echo "outputs DIFFER"; exit 1; }
import sys
import OpenImageIO as oiio
a, b = (oiio.ImageBuf(p) for p in sys.argv[1:3])
sys.exit(0 if a.get_pixels(oiio.FLOAT).tobytes() == b.get_pixels(oiio.FLOAT).tobytes() else 1)
PY
