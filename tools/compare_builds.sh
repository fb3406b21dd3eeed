#!/usr/bin/env bash
# tools/compare_builds.sh OLD_VKSKY NEW_VKSKY: render the same list of frames with two builds and compare the files:
# EXRs by their pixels, bit for bit (OpenImageIO: their headers record the output path and the command line, which
# differ between two runs), everything else byte for byte. A change that must not change behaviour (a refactor, a file split) passes only if every output is
# identical: the default frame, each quality preset, each shipped scene, the window's screenshot (under Xvfb, when
# Xvfb is present; it adapts its exposure over wall-clock time, so two runs of one build may differ), the CPU reference and the path tracer (images and printed values), and the traces.
#
#   cmake -S . -B build-old ... (at the old commit); cmake -S . -B build ... (now)
#   tools/compare_builds.sh build-old/vksky build/vksky
#
# NEW_ARGS="--units relative" tools/compare_builds.sh OLD NEW: the new build runs every case with these flags added (a
# mode that must reproduce the old build's outputs, issue 32). Its EXR headers then differ where they record the
# command line (and name their units); the comparison is the same.
#
# Exit 0: all identical; 1: some output differs (listed); 2: usage.
set -u
OLD=${1:?usage: compare_builds.sh OLD_VKSKY NEW_VKSKY}
NEW=${2:?usage: compare_builds.sh OLD_VKSKY NEW_VKSKY}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
size=(--width 96 --height 54)

# name | arguments (FILE stands for the output path without extension; outputs are FILE.exr and FILE.png)
cases=(
  "default|--render FILE.exr --render FILE.png ${size[*]}"
  "sunset|--render FILE.exr --render FILE.png ${size[*]} --sun-elevation 1 --sun-azimuth 30 --yaw 30"
  "space|--render FILE.exr ${size[*]} --altitude 400 --pitch -60"
  "fragment|--render FILE.exr ${size[*]} --sky-pass fragment"
  "nobloom|--render FILE.exr ${size[*]} --no-bloom --tonemap reinhard"
  "scale|--render FILE.exr ${size[*]} --render-scale 0.5"
  "spd|--render FILE.exr --render FILE.png ${size[*]} --post-pass compute --bloom-downsample single-pass"
  "reference|--reference --render FILE.exr --width 24 --height 14 --sun-elevation -2"
  "path_trace|--path-trace --samples 16 --render FILE.exr --width 16 --height 9"
  "reference_print|--reference --sun-elevation 3"
)
for q in low medium high ultra; do cases+=("quality_$q|--render FILE.exr ${size[*]} --quality $q"); done
for s in "$ROOT"/scenes/*.json; do
  n=$(basename "$s" .json)
  cases+=("scene_$n|--scene $s --render FILE.exr ${size[*]}")
  cases+=("dump_$n|--scene $s --dump-scene")
done
cases+=("trace|--render FILE.exr ${size[*]} --trace-barriers --trace-passes")
# Environment maps (rendered in bands, app/runs/tiles.c): each projection, EXR and PNG at a given exposure, traced.
for p in equirect:64 cubemap:16 fisheye:48; do
  cases+=("map_${p%%:*}|--render FILE.exr --render FILE.png --projection ${p%%:*} --width ${p##*:} --exposure 13 --trace-barriers --trace-passes")
done

fail=0
NEW_ARGS=${NEW_ARGS:-}
run_case() { # build tag name args
  local bin=$1 tag=$2 name=$3 args=$4 out=$work/$2/$3
  [ "$tag" = new ] && args="$args $NEW_ARGS"
  mkdir -p "$work/$tag"
  # shellcheck disable=SC2086 # the argument list is word-split on purpose
  "$bin" ${args//FILE/$out} >"$out.stdout" 2>"$out.stderr"
  echo $? >"$out.status"
}
for c in "${cases[@]}"; do
  name=${c%%|*} args=${c#*|}
  run_case "$OLD" old "$name" "$args"
  run_case "$NEW" new "$name" "$args"
done

# Banded renders: a perspective image and an equirect map over a small band budget (VKSKY_TILE_PIXELS), quiet (the
# progress line names the output's path); pipelined through the readback ring, and traced in the serial loop (the
# ring's consumer prints its waits on its own thread: their place among the producer's lines varies run to run).
for tag in old new; do
  bin=$OLD; [ $tag = new ] && bin=$NEW
  VKSKY_TILE_PIXELS=1600 run_case "$bin" $tag bands_perspective "--render FILE.exr --render FILE.png ${size[*]} --exposure 13 --quiet"
  VKSKY_TILE_PIXELS=1024 run_case "$bin" $tag bands_equirect "--render FILE.exr --render FILE.png --projection equirect --width 64 --exposure 13 --quiet"
  VKSKY_TILE_PIXELS=1600 VKSKY_READBACK_SLOTS=1 run_case "$bin" $tag bands_trace "--render FILE.png ${size[*]} --exposure 13 --quiet --trace-barriers --trace-passes"
  # Cube and fisheye maps in 16-row bands, auto-exposed (metered band by band); --async-luts over two frames in one
  # run (VKSKY_FRAMES, one queue), traced (25i: both through include/vksky.h).
  VKSKY_TILE_ROWS=16 run_case "$bin" $tag bands_cubemap "--render FILE.exr --render FILE.png --projection cubemap --width 16 --quiet"
  VKSKY_TILE_ROWS=16 run_case "$bin" $tag bands_fisheye "--render FILE.exr --render FILE.png --projection fisheye --width 48 --quiet"
  VKSKY_ASYNC_ONE_QUEUE=1 VKSKY_FRAMES=2 run_case "$bin" $tag async_frames "--render FILE.exr --render FILE.png ${size[*]} --async-luts --trace-barriers --trace-passes"
done

# The window: a few frames and a screenshot (skipped without Xvfb).
if command -v Xvfb >/dev/null; then
  for tag in old new; do
    bin=$OLD; [ $tag = new ] && bin=$NEW
    extra=""; [ $tag = new ] && extra=$NEW_ARGS
    # shellcheck disable=SC2086 # NEW_ARGS is word-split on purpose
    "$ROOT/tests/xvfb_run.sh" 640x480x24 "$bin" --frames 3 --width 160 --height 90 $extra \
      --screenshot "$work/$tag/window.png" >"$work/$tag/window.stdout" 2>/dev/null
    echo $? >"$work/$tag/window.status"
  done
else
  echo "compare_builds: no Xvfb, window screenshot skipped"
fi

# Sequences, --bench and --timings (issue 25 item 1: through include/vksky.h since 25h): the frames' files, their
# progress lines (paths made relative) and traces; the reports of --bench and --timings with every number as N. The ring's trace is compared sorted (its consumer thread's "sync ring.gpu_done" lines
# interleave with the producer's as the threads run); the serial loop's (VKSKY_READBACK_SLOTS=1) as printed.
seq=(--width 64 --height 36 --frame-count 4 --animate sun-elevation=-2:30 --animate yaw=0:40)
run_seq() { # name env args (FILE: the output path without extension)
  local name=$1 env=$2 args=$3 tag bin out
  for tag in old new; do
    bin=$OLD; [ "$tag" = new ] && bin=$NEW
    out=$work/$tag/$name
    mkdir -p "$work/$tag"
    # shellcheck disable=SC2086 # the argument list is word-split on purpose
    env $env "$bin" ${args//FILE/$out} >"$out.raw_stdout" 2>"$out.raw_stderr"
    echo $? >"$out.status"
    sed "s|$work/$tag/||g" "$out.raw_stderr" >"$out.stderr"
    case $name in
      *ring*) sort "$out.raw_stdout" >"$out.stdout" ;;
      # --bench and --timings: figures differ from run to run, the report's structure does not.
      bench*|timings*) sed -E 's/-?[0-9]+(\.[0-9]+)?/N/g; s/ +/ /g' "$out.raw_stdout" >"$out.stdout"
                       sed -E 's/-?[0-9]+(\.[0-9]+)?/N/g; s/ +/ /g' "$out.stderr" >"$out.norm" && mv "$out.norm" "$out.stderr" ;;
      *) cp "$out.raw_stdout" "$out.stdout" ;;
    esac
    rm -f "$out.raw_stdout" "$out.raw_stderr"
  done
}
run_seq seq_ring "" "--render FILE_%d.exr --render FILE_%d.png ${seq[*]} --trace-barriers --trace-passes"
run_seq seq_serial "VKSKY_READBACK_SLOTS=1" "--render FILE_%d.exr --render FILE_%d.png ${seq[*]} --trace-barriers"
run_seq seq_range "" "--render FILE_%d.exr --render FILE_%d.png ${seq[*]} --frame-range 1:2"
run_seq seq_exposure "" "--render FILE_%d.png --width 64 --height 36 --frame-count 3 --animate exposure=10:14 --animate mie-g=0.7:0.85"
run_seq seq_altitude "" "--render FILE_%d.exr --width 64 --height 36 --frame-count 3 --animate altitude=0:30 --quality high"
# --skip-existing: frames 0 and 2 written by a first job, then the whole sequence resumed (and one frame alone).
run_seq seq_skip "" "--render FILE_%d.exr --render FILE_%d.png ${seq[*]} --frame-range 0:0"
run_seq seq_skip "" "--render FILE_%d.exr --render FILE_%d.png ${seq[*]} --frame-range 2:2"
run_seq seq_skip "" "--render FILE_%d.exr --render FILE_%d.png ${seq[*]} --skip-existing"
run_seq skip_one "" "--render FILE.png --width 64 --height 36 --skip-existing"
run_seq skip_one "" "--render FILE.png --width 64 --height 36 --skip-existing"
run_seq bench_one "" "--render FILE.png --width 64 --height 36 --bench 2"
run_seq bench_seq "" "--render FILE_%d.exr ${seq[*]} --bench 2"
run_seq timings_one "" "--render FILE.png --width 64 --height 36 --timings --no-cache"
run_seq timings_seq "VKSKY_READBACK_SLOTS=1" "--render FILE_%d.exr ${seq[*]} --timings --no-cache"

# Two EXRs' pixels (and channel types and sizes), bit for bit.
same_pixels() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import sys
import OpenImageIO as oiio
a, b = (oiio.ImageBuf(p) for p in sys.argv[1:3])
same = (a.spec().width, a.spec().height, a.spec().channelnames, str(a.spec().format)) == \
       (b.spec().width, b.spec().height, b.spec().channelnames, str(b.spec().format)) and \
       a.get_pixels(oiio.UINT16).tobytes() == b.get_pixels(oiio.UINT16).tobytes() and \
       a.get_pixels(oiio.FLOAT).tobytes() == b.get_pixels(oiio.FLOAT).tobytes()
sys.exit(0 if same else 1)
PY
}

# Timing lines (the path tracer's seconds, bench medians) are not outputs: drop lines that carry a time.
for f in "$work"/old/* ; do
  b=$(basename "$f")
  g=$work/new/$b
  case $b in
    *.stdout|*.stderr) cmp -s <(grep -v -E 'time|seconds| s$|ms' "$f") <(grep -v -E 'time|seconds| s$|ms' "$g") ;;
    *.exr) same_pixels "$f" "$g" ;;
    *) cmp -s "$f" "$g" ;;
  esac || { echo "DIFFERS: $b"; fail=1; }
done
n=$(ls "$work"/old | wc -l)
[ $fail -eq 0 ] && echo "compare_builds: all $n outputs identical"
exit $fail
