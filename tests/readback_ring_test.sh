#!/usr/bin/env bash
# The readback ring and the parallel encoders (issue 27 items 1, 2). Every run has --validate (validation +
# synchronization validation, threading checks included): any message fails it.
#  - a sequence pipelined through the ring (2 and 3 slots) writes the same files, byte for byte, in the same order
#    (its per-frame lines), as the serial loop (VKSKY_READBACK_SLOTS=1): with the sun animated (the uniform block
#    unchanged: frames overlap) and with mie-g animated too (the uniform block rewritten: ring.drain every frame);
#  - a banded render (an environment map in bands) pipelined equals the serial one;
#  - --threads 1 equals --threads 16 byte for byte (the EXR header leaves --threads out), single frame and banded;
#  - --trace-barriers prints each of the ring's waits as often as the frame count says it must happen;
#  - each wait is needed: left out (VKSKY_DROP_BARRIER=<name>), the run goes wrong in a way this test sees:
#      ring.gpu_done   the consumer reads the slot before the GPU wrote it (frame 0's file differs), and releases
#                      a slot whose command buffer is still pending;
#      ring.slot_free  the producer re-records a slot whose frame is still pending or being written: the command
#                      buffer freed while pending (the validation layer's VUID-vkFreeCommandBuffers-...-00047, or
#                      lavapipe crashes), and with the consumer slowed down (VKSKY_RING_DELAY_MS) a file gets a
#                      later frame's pixels;
#      ring.drain      the host rewrites the uniform block under frames in flight: a file differs;
#  - --quiet: no per-frame lines; --bench with a sequence prints its frames/s to disk.
# Usage: readback_ring_test.sh path/to/vksky
set -u
VKSKY=$(readlink -f "${1:?usage: readback_ring_test.sh path/to/vksky}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
export VKSKY_VALIDATION=1
# The ring's waits as one consumer thread sees them (several frames at once: tests/encode_frames_test.sh).
export VKSKY_ENCODE_FRAMES=1

# The lesson's units: in photometric units the image's HDR scale follows the sun's elevation (app/scene/light.c), so the
# uniform block (and the drain count) would change with it; and auto exposure (the photometric default for PNG)
# meters each frame's own pixels before its tone map, a host dependency that keeps such sequences on the serial loop
# (app/runs/sequence.c). The ring's waits are the same in both units.
SUN=(--width 64 --height 48 --quality lesson --units relative --animate sun-elevation=-2:30 --frame-count 5)
MEDIUM=(--width 64 --height 48 --quality lesson --units relative --animate sun-elevation=-2:30 --animate mie-g=0.7:0.85 --frame-count 4)
EQ=(--width 128 --projection equirect --quality lesson)

# run NAME [ENV=V...] -- ARGS...: vksky in $work/NAME (created), stdout/stderr kept there; the exit status.
run() {
    local name=$1; shift
    local envs=()
    while [ "$1" != -- ]; do envs+=("$1"); shift; done
    shift
    rm -rf "${work:?}/$name"; mkdir -p "$work/$name"
    (cd "$work/$name" && env "${envs[@]}" ${RUN_LIMIT:+timeout -s KILL "$RUN_LIMIT"} "$VKSKY" "$@" >stdout 2>stderr)
}
# files NAME: the checksums of a run's images, one per line.
files() { (cd "$work/$1" && md5sum -- *.exr *.png 2>/dev/null); }
same() {   # same A B WHAT: the two runs wrote the same files
    local a b
    a=$(files "$1"); b=$(files "$2")
    [ -n "$a" ] || { fail "$3: $1 wrote no files"; return; }
    [ "$a" = "$b" ] || fail "$3: files differ ($1 vs $2)"
}
clean() {   # clean NAME WHAT: exit 0 and no validation message
    grep -q 'validation' "$work/$1/stderr" && fail "$2: validation reported: $(grep -m1 validation "$work/$1/stderr")"
}

# 1. Sequences: serial, 2 slots, 3 slots.
run serial VKSKY_READBACK_SLOTS=1 -- "${SUN[@]}" --render f%02d.exr --render f%02d.png || fail "serial sequence exited $?"
run ring2 VKSKY_READBACK_SLOTS=2 -- "${SUN[@]}" --render f%02d.exr --render f%02d.png || fail "ring sequence exited $?"
run ring3 VKSKY_READBACK_SLOTS=3 -- "${SUN[@]}" --render f%02d.exr --render f%02d.png || fail "3-slot sequence exited $?"
for r in serial ring2 ring3; do clean $r "sequence ($r)"; done
same serial ring2 "sequence, 2 slots"
same serial ring3 "sequence, 3 slots"
[ "$(files serial | wc -l)" -eq 10 ] || fail "the serial sequence wrote $(files serial | wc -l) files, expected 10"
frame_lines() { grep -o 'frame [0-9]* (' "$work/$1/stderr" | tr '\n' ' '; }
if [ -z "$(frame_lines serial)" ] || [ "$(frame_lines serial)" != "$(frame_lines ring2)" ]; then
    fail "per-frame lines differ: '$(frame_lines serial)' vs '$(frame_lines ring2)'"
fi

# 2. The uniform block rewritten every frame (ring.drain).
run mserial VKSKY_READBACK_SLOTS=1 -- "${MEDIUM[@]}" --render f%02d.exr || fail "serial medium sequence exited $?"
run mring -- "${MEDIUM[@]}" --render f%02d.exr || fail "ring medium sequence exited $?"
clean mring "medium sequence"
same mserial mring "sequence with mie-g animated"

# 3. Banded renders (VKSKY_TILE_PIXELS: 128x64 in bands of 16 rows), serial and pipelined; 4. --threads.
run bserial VKSKY_READBACK_SLOTS=1 VKSKY_TILE_PIXELS=4096 -- "${EQ[@]}" --threads 1 --render e.exr --render e.png ||
    fail "serial banded render exited $?"
run bring VKSKY_TILE_PIXELS=4096 -- "${EQ[@]}" --threads 16 --render e.exr --render e.png || fail "banded ring exited $?"
clean bring "banded ring"
same bserial bring "banded render, serial --threads 1 vs ring --threads 16"
run t1 -- --width 96 --height 64 --quality lesson --threads 1 --render a.exr || fail "--threads 1 exited $?"
run t16 -- --width 96 --height 64 --quality lesson --threads 16 --render a.exr || fail "--threads 16 exited $?"
same t1 t16 "--threads 1 vs 16"

# 5. The trace: frames 0..4 through 2 slots: 5 gpu_done, 3 slot_free (frames 2..4), no drain (nothing changes);
# the medium sequence's 4 frames: a drain before each frame after the first.
run trace -- "${SUN[@]}" --render f%02d.exr --trace-barriers || fail "traced sequence exited $?"
run mtrace -- "${MEDIUM[@]}" --render f%02d.exr --trace-barriers || fail "traced medium sequence exited $?"
count() { grep -c "^sync $2 " "$work/$1/stdout"; }
[ "$(count trace ring.gpu_done)" -eq 5 ] || fail "ring.gpu_done traced $(count trace ring.gpu_done) times, expected 5"
[ "$(count trace ring.slot_free)" -eq 3 ] || fail "ring.slot_free traced $(count trace ring.slot_free) times, expected 3"
[ "$(count trace ring.drain)" -eq 0 ] || fail "ring.drain traced $(count trace ring.drain) times, expected 0"
[ "$(count mtrace ring.drain)" -eq 3 ] || fail "ring.drain traced $(count mtrace ring.drain) times, expected 3"

# 6. Each wait left out. What goes wrong is undefined behaviour, so it may show in more than one way: a file that
# differs from the serial run's, the validation layer's report (a command buffer freed or a fence reset while
# pending: the producer reused a slot the GPU still works on), or the driver crashing on that freed command buffer
# (lavapipe does), or hanging there: these runs are killed after 30 s (exit 137), a hang counted as going wrong, not
# left to the test's own timeout (a loaded CI machine once ran this test past 600 s). A run that goes right takes
# ~2 s alone (64x48, 5 frames); a hang killed at 120 s was most of this test's 129 s in a -j2 suite run. Any of them is the hazard seen;
# a run that exits 0 with the serial run's files is not.
# went_wrong NAME REFERENCE: the run NAME (exit status in $rc) went wrong.
went_wrong() {
    [ "$rc" -ge 128 ] && return 0
    grep -qE 'VUID-vkFreeCommandBuffers-pCommandBuffers-00047|VUID-vkResetFences-pFences-01123' "$work/$1/stderr" &&
        return 0
    [ "$(files "$2")" != "$(files "$1")" ]
}
RUN_LIMIT=30
run drop_gpu VKSKY_DROP_BARRIER=ring.gpu_done -- "${SUN[@]}" --render f%02d.exr --render f%02d.png; rc=$?
went_wrong drop_gpu serial || fail "ring.gpu_done dropped: nothing went wrong (exit $rc, the serial run's files)"
run drop_slot VKSKY_DROP_BARRIER=ring.slot_free VKSKY_RING_DELAY_MS=300 -- "${SUN[@]}" --render f%02d.exr \
    --render f%02d.png; rc=$?
went_wrong drop_slot serial || fail "ring.slot_free dropped: nothing went wrong (exit $rc, the serial run's files)"
run drop_drain VKSKY_DROP_BARRIER=ring.drain -- "${MEDIUM[@]}" --render f%02d.exr; rc=$?
went_wrong drop_drain mserial || fail "ring.drain dropped: nothing went wrong (exit $rc, the serial run's files)"
RUN_LIMIT=
# ... and the runs that drop nothing exited 0 with the serial files (above): the difference is the wait.

# 7. --quiet and --bench.
run quiet -- "${SUN[@]}" --render f%02d.exr --quiet || fail "--quiet sequence exited $?"
[ ! -s "$work/quiet/stderr" ] || fail "--quiet: stderr has: $(head -2 "$work/quiet/stderr")"
run bench -- "${SUN[@]}" --render f%02d.exr --bench 2 --quiet || fail "--bench sequence exited $?"
grep -qE '^sequence frames 5 outputs 1 wall_s [0-9.]+ frames_per_s [0-9.]+ ' "$work/bench/stdout" ||
    fail "--bench with a sequence: no frames/s line: $(tail -1 "$work/bench/stdout")"
[ "$(files bench | wc -l)" -eq 5 ] || fail "--bench with a sequence wrote $(files bench | wc -l) files, expected 5"

[ $fails -eq 0 ] && echo "readback_ring: all checks pass"
exit $((fails > 0))
