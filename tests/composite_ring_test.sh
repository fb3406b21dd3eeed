#!/usr/bin/env bash
# The composite's ring of bands (issue 28 item 6; docs/synchronization.md, "The composite's bands"): a generated
# 120x68 scene in bands of 16 rows composited through two slots (band k + 1 on the GPU while band k is encoded) and one
# band at a time (VKSKY_COMPOSITE_SLOTS=1) gives the same file byte for byte, validation clean; its trace has one
# composite.band_done wait per band and a composite.slot_free hand-over per reused slot; and with the band_done wait
# left out (VKSKY_DROP_BARRIER=composite.band_done) validation reports the slot's fence reused while in flight and
# the run fails. --timings reports the start and the 5 bands' stages and changes nothing in the file. A few seconds on
# lavapipe.
#
#   composite_ring_test.sh VKSKY GEN_COMPOSITE_SCENE
set -u
VKSKY=${1:?usage: composite_ring_test.sh VKSKY GEN_COMPOSITE_SCENE}
GEN=${2:?usage: composite_ring_test.sh VKSKY GEN_COMPOSITE_SCENE}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
"$GEN" "$work" 120 68 >/dev/null || { echo "FAIL: gen_composite_scene"; exit 1; }
run() {   # name env...: the output named out.exr in a directory of its own (the header records the path as given)
  local name=$1; shift
  mkdir -p "$work/$name"
  (cd "$work/$name" && env VKSKY_COMPOSITE_BAND_ROWS=16 "$@" "$VKSKY" --composite ../render.exr --render out.exr \
    --sun-elevation 20 --sun-azimuth -60 --validate --trace-barriers >"$work/$name.out" 2>"$work/$name.err")
}
run ring || fail "two slots: exit $? ($(head -c 300 "$work/ring.err"))"
run serial VKSKY_COMPOSITE_SLOTS=1 || fail "one slot: exit $? ($(head -c 300 "$work/serial.err"))"
cmp -s "$work/ring/out.exr" "$work/serial/out.exr" || fail "two slots and one slot wrote different files"
# 68 rows in bands of 16: 5 bands, each waited for once; slots reused from band 2 on.
[ "$(grep -c '^sync composite.band_done ' "$work/ring.out")" = 5 ] || fail "not 5 band_done waits"
[ "$(grep -c '^sync composite.slot_free ' "$work/ring.out")" = 3 ] || fail "not 3 slot_free hand-overs"
grep -q '^sync composite' "$work/serial.out" && fail "one slot: the ring's lines in its trace"
# The barriers themselves, band after band, are the one-slot run's (only the ring's sync lines added).
cmp -s <(grep -v '^sync ' "$work/ring.out") "$work/serial.out" || fail "the barrier trace differs from one slot's"
# --timings: the start and the bands' stages on stderr, the file byte for byte the ring's (the header leaves the
# flag out), no validation message.
mkdir -p "$work/timed"
(cd "$work/timed" && VKSKY_COMPOSITE_BAND_ROWS=16 "$VKSKY" --composite ../render.exr --render out.exr --sun-elevation 20 \
    --sun-azimuth -60 --validate --trace-barriers --timings >"$work/timed.out" 2>"$work/timed.err") ||
    fail "--timings: exit $? ($(head -c 300 "$work/timed.err"))"
cmp -s "$work/ring/out.exr" "$work/timed/out.exr" || fail "--timings changed the file"
grep -q "^vksky: timings of the composite's start (ms): the device, renderer and pipelines [0-9.]* wall" "$work/timed.err" ||
    fail "--timings: no line for the start"
grep -q "^vksky: timings of the composite (.*; 5 bands, " "$work/timed.err" || fail "--timings: no table of 5 bands"
grep -Eq "^  (produce|gpu wait|write) .* [0-9]+\.[0-9]" "$work/timed.err" || fail "--timings: no stage lines"
grep -qi 'validation' "$work/timed.err" && fail "--timings: $(grep -m1 -i validation "$work/timed.err")"
run drop VKSKY_DROP_BARRIER=composite.band_done && fail "band_done dropped: exit 0"
grep -q 'VUID-vkQueueSubmit2-fence' "$work/drop.err" ||
  fail "band_done dropped: validation did not report the fence ($(head -c 300 "$work/drop.err"))"
[ $fails -eq 0 ] && echo "composite_ring: two slots equal one, 5 waits traced, the dropped wait reported, --timings reported"
exit $((fails > 0))
