#!/usr/bin/env bash
# --bench through include/vksky.h (issue 25; app/runs/bench_host.c), validation + synchronization validation on (any
# message fails the run, exit 1):
#  - --bench alone: the frame into the command line's own offscreen image (a renderer without readback, as a host
#    engine's frame); --bench --async-luts (VKSKY_ASYNC_ONE_QUEUE=1 on lavapipe's one queue): the LUT passes recorded
#    with vksky_record_luts and timed on the compute queue's timer (vksky_renderer_get_lut_timings);
#  - each run: exit 0, no validation line, the report's lines (bench_report.c) in their order, every figure a
#    positive number, the async run's frame_luts line marked "async";
#  - a LUT-rebuilding frame's wall time above a steady frame's (lavapipe's timestamps bound nothing: no GPU figure is
#    compared);
#  - --bench of an environment map over the band budget (VKSKY_TILE_PIXELS), alone and with --render: a whole frame,
#    as before;
#  - no file written (a --bench of one frame writes none).
# Usage: bench_api_test.sh path/to/vksky
set -u
VKSKY=$(readlink -f "${1:?usage: bench_api_test.sh VKSKY}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
A=(--bench 2 --width 48 --height 32 --quality low --validate)

check() {   # NAME SUFFIX: the run's report in $work/NAME.out
    local name=$1 suffix=$2 out="$work/$1.out"
    grep -q 'validation' "$work/$name.err" && fail "$name: validation messages: $(grep -m1 validation "$work/$name.err")"
    python3 - "$out" "$suffix" <<'PY' || fail "$name: report: $(tr '\n' '|' <"$out")"
import re, sys
lines = open(sys.argv[1]).read().splitlines()
suffix = sys.argv[2]
num = r"([0-9]+\.[0-9]+)"
passes = [re.fullmatch(r"pass ([a-z_]+) gpu_ms " + num, l) for l in lines if l.startswith("pass ")]
assert passes and all(passes), "pass lines"
names = [m.group(1) for m in passes]
for need in ("transmittance_lut", "multiscatter_lut", "sky", "tonemap"):
    assert need in names, need
frame = [re.fullmatch(r"frame gpu_ms " + num + " wall_ms " + num, l) for l in lines if l.startswith("frame gpu_ms")]
cpu_line = [re.fullmatch(r"frame cpu_ms " + num, l) for l in lines if l.startswith("frame cpu_ms")]
luts = [re.fullmatch(r"frame_luts wall_ms " + num + (" " + suffix if suffix else ""), l)
        for l in lines if l.startswith("frame_luts")]
assert len(frame) == 1 and frame[0] and len(cpu_line) == 1 and cpu_line[0] and len(luts) == 1 and luts[0], "frame lines"
assert lines[-1].startswith("frame_luts"), "order"
values = [float(m.group(2)) for m in passes] + [float(frame[0].group(1)), float(frame[0].group(2)),
                                                float(luts[0].group(1))]
assert all(v > 0 for v in values), "positive"
# The LUT passes were timed in LUT-rebuilding frames (on the compute queue's timer with --async-luts): a frame that
# rebuilds them takes longer than a steady one.
assert float(luts[0].group(1)) > float(frame[0].group(2)), "frame_luts wall above a steady frame's"
PY
}

(cd "$work" && "$VKSKY" "${A[@]}" >"$work/alone.out" 2>"$work/alone.err") || fail "--bench alone exited $?"
check alone ""
(cd "$work" && VKSKY_ASYNC_ONE_QUEUE=1 "$VKSKY" "${A[@]}" --async-luts >"$work/async.out" 2>"$work/async.err") ||
    fail "--bench --async-luts exited $?"
check async async
# An environment map over the band budget, alone (the map's one band into the host's image) and with --render (a
# readback renderer): whole frames, as before.
(cd "$work" && VKSKY_TILE_PIXELS=1000 "$VKSKY" "${A[@]}" --projection cubemap --width 16 \
    >"$work/map.out" 2>"$work/map.err") || fail "--bench of a map exited $?"
check map ""
(cd "$work" && VKSKY_TILE_PIXELS=1000 "$VKSKY" "${A[@]}" --projection equirect --width 64 --render map.exr \
    >"$work/maprender.out" 2>"$work/maprender.err") || fail "--bench --render of a map over the band budget exited $?"
check maprender ""
[ -z "$(find "$work" -name '*.png' -o -name '*.exr')" ] || fail "a file was written"

[ "$fails" -eq 0 ] || exit 1
echo "bench_api: ok"
