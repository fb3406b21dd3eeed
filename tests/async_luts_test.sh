#!/usr/bin/env bash
# --async-luts (issue 25 item 4, docs/synchronization.md §10): the LUT passes on a compute queue, ordered against
# the frame by two timeline semaphores. Lavapipe has one queue family with one queue, so the path that runs here is
# VKSKY_ASYNC_ONE_QUEUE=1: the same command buffers, semaphores and trace, both submissions on the one queue (the
# other-family path, with its ownership transfer, is tools/async_bench.sh's on a GPU). Every run has --validate
# (validation + synchronization validation): any message fails it.
#  - without a second queue, --async-luts is refused: exit 2, one line naming what the device lacks, no file;
#  - each variant whose LUT set or first LUT reader differs (default, sky-view, compute sky pass, no
#    multi-scattering, lit ground), two frames each rebuilding the LUTs (VKSKY_FRAMES=2): pixels bit-identical to the
#    single-queue frames (EXR by pixels, PNG byte for byte; tests/async_pixels.sh, shared with tools/async_bench.sh);
#  - the trace: the LUT passes recorded in their own command buffer before the frame's, which records none; each
#    rebuild signals compute_done with the next value, each frame waits for exactly that value at the LUT readers'
#    stages and signals graphics_done, which the next rebuild waits for; the queue line and `qfot none` say why no
#    ownership transfer is recorded (one family);
#  - --spectral 8 --async-luts: the groups' LUT passes on the compute queue, pixels equal to one queue's;
#  - the window (Xvfb): validation clean, the LUTs built on the compute queue, the screenshot equal;
#  - the compute command buffer is checked by validation like the frame's: transmittance.write_to_sample left out
#    there is reported (RAW + layout).
# Usage: async_luts_test.sh path/to/vksky path/to/exr_pixels
set -u
VKSKY=$(readlink -f "${1:?usage: async_luts_test.sh VKSKY EXR_PIXELS}")
PIX=$(readlink -f "${2:?}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
A=(--width 48 --height 32 --quality lesson --units relative --validate)

# Refused where there is no second queue (lavapipe); skipped on a device that has one.
if "$VKSKY" --list-devices 2>/dev/null | grep -qi llvmpipe; then
    "$VKSKY" --render "$work/refused.png" "${A[@]}" --async-luts 2>"$work/refused.err"
    rc=$?
    [ $rc -eq 2 ] || fail "--async-luts on a one-queue device: exit $rc, expected 2"
    [ "$(wc -l <"$work/refused.err")" -eq 1 ] && grep -q 'needs a second queue' "$work/refused.err" \
        || fail "--async-luts refused without one clear line: $(head -c 300 "$work/refused.err")"
    [ ! -e "$work/refused.png" ] || fail "--async-luts refused but wrote a file"
fi

export VKSKY_ASYNC_ONE_QUEUE=1
# shellcheck source=tests/async_pixels.sh
. "$(dirname "$0")/async_pixels.sh"
i=0
while read -r name extra; do
    i=$((i + 1))
    # shellcheck disable=SC2086
    why=$(async_pair "$i" "$name" $extra) || { fail "$why"; continue; }
    # The trace, command buffer by command buffer: 1 = LUTs (compute), 2 = frame, 3 = LUTs, 4 = frame.
    awk -v name="$name" '
        function bad(m) { print "FAIL: " name ": trace: " m > "/dev/stderr"; failed = 1 }
        /^commands$/ { ++cb; next }
        /^pass (transmittance|multiscatter|ground_irradiance)_lut(_first|_sky_ground)?$/ { if (cb % 2 == 0) bad("LUT pass in the frame'"'"'s command buffer " cb); luts[cb]++ }
        /^pass sky$/ { if (cb % 2 == 1) bad("sky pass in the LUTs'"'"' command buffer") }
        /^semaphore compute_done.signal / { ++cs; if ($3 != "queue=compute" || $4 != "value=" cs) bad("compute_done.signal: " $0) }
        /^semaphore compute_done.wait / { ++cw; if ($3 != "queue=graphics" || $4 != "value>=" cs || $5 != "stage=COMPUTE_SHADER|FRAGMENT_SHADER") bad("compute_done.wait: " $0) }
        /^semaphore graphics_done.signal / { ++gs; if ($3 != "queue=graphics" || $4 != "value=" gs) bad("graphics_done.signal: " $0) }
        /^semaphore graphics_done.wait / { ++gw; if ($3 != "queue=compute" || $4 != "value>=" gs || $5 != "stage=COMPUTE_SHADER") bad("graphics_done.wait: " $0) }
        /^queues / { q++; if ($0 !~ /same family/) bad("queues line: " $0) }
        /^qfot none/ { qn++ }
        /^qfot .* (release|acquire) / { bad("an ownership transfer on one family: " $0) }
        END {
            if (cb != 4) bad(cb " command buffers, expected 4 (LUTs, frame, LUTs, frame)")
            if (!luts[1] || !luts[3]) bad("no LUT passes in the compute command buffers")
            if (cs != 2 || cw != 2 || gs != 2 || gw != 1) bad("semaphores: compute_done " cs " signals " cw " waits, graphics_done " gs " signals " gw " waits; expected 2 2 2 1")
            if (q != 1 || qn != 2) bad("queues line " q ", qfot none lines " qn "; expected 1 and 2")
            exit failed
        }' "$work/a$i.trace" || fails=$((fails + 1))
done < <(async_variants)

# --spectral 8 --async-luts (issue 25): the wavelength groups' LUT passes on the compute queue before each frame's
# submission of the groups (one renderer per group, or one renderer given each group's scene on a CPU device: then a
# LUT submission per group); pixels identical to the single-queue spectral image, validation clean, the semaphores
# as for an RGB frame: each LUT submission signals compute_done's next value, the frame after it waits for exactly
# that value and signals graphics_done, which the next LUT submission waits for.
"$VKSKY" --render "$work/ss.exr" --render "$work/ss.png" "${A[@]}" --spectral 8 2>"$work/ss.err" \
    || fail "--spectral 8: failed: $(head -c 300 "$work/ss.err")"
"$VKSKY" --render "$work/sa.exr" --render "$work/sa.png" "${A[@]}" --spectral 8 --async-luts --trace-barriers \
    >"$work/sa.trace" 2>"$work/sa.err"
rc=$?
if [ $rc -ne 0 ] || [ -s "$work/sa.err" ]; then
    fail "--spectral 8 --async-luts: exit $rc: $(head -c 600 "$work/sa.err")"
else
    "$PIX" same "$work/ss.exr" "$work/sa.exr" || fail "--spectral 8 --async-luts: EXR pixels differ from one queue's"
    cmp -s "$work/ss.png" "$work/sa.png" || fail "--spectral 8 --async-luts: PNG differs from one queue's"
    awk '
        function bad(m) { print "FAIL: spectral: trace: " m > "/dev/stderr"; failed = 1 }
        /^commands$/ { ++cb; next }
        /^pass (transmittance|multiscatter|ground_irradiance)_lut(_first|_sky_ground)?$/ { if (cb % 2 == 0) bad("LUT pass in the frame'"'"'s command buffer " cb); luts++ }
        /^pass sky$/ { if (cb % 2 == 1) bad("sky pass in a LUT command buffer"); sky++ }
        /^semaphore compute_done.signal / { ++cs; if ($3 != "queue=compute" || $4 != "value=" cs) bad("compute_done.signal: " $0) }
        /^semaphore compute_done.wait / { ++cw; if ($3 != "queue=graphics" || $4 != "value>=" cs) bad("compute_done.wait: " $0) }
        /^semaphore graphics_done.signal / { ++gs; if ($3 != "queue=graphics" || $4 != "value=" gs) bad("graphics_done.signal: " $0) }
        /^semaphore graphics_done.wait / { ++gw; if ($3 != "queue=compute" || $4 != "value>=" gs) bad("graphics_done.wait: " $0) }
        END {
            if (cs < 1 || !luts) bad("no LUT submission on the compute queue")
            if (cw != cs || gs != cs || gw != cs - 1) bad("semaphores: compute_done " cs " signals " cw " waits, graphics_done " gs " signals " gw " waits")
            if (!sky) bad("no sky pass")
            exit failed
        }' "$work/sa.trace" || fails=$((fails + 1))
fi

# Validation sees the compute command buffer: a LUT barrier left out there is reported.
VKSKY_DROP_BARRIER=transmittance.write_to_sample "$VKSKY" --render "$work/drop.png" "${A[@]}" --async-luts \
    2>"$work/drop.err" >/dev/null
grep -q 'SYNC-HAZARD-READ-AFTER-WRITE' "$work/drop.err" && grep -q 'InvalidImageLayout\|imageLayout-00344' "$work/drop.err" \
    || fail "transmittance.write_to_sample dropped on the compute queue: no RAW + layout reported"

# The window (under Xvfb when there is no DISPLAY; skipped without either): its first frame's LUTs on the compute
# queue, the frame's submit waiting for them beside the acquire semaphore; validation clean, the screenshot equal to
# the single-queue window's.
if [ -n "${DISPLAY:-}" ] || command -v Xvfb >/dev/null; then
    run=("$VKSKY"); [ -z "${DISPLAY:-}" ] && run=("$(dirname "$0")/xvfb_run.sh" 640x480x24 "$VKSKY")
    # A fixed exposure: the window's auto exposure eases toward the meter in wall-clock time (τ 0.5 s), so two runs
    # under load would differ by their frame times, not by where the LUTs were built.
    W=(--frames 3 --width 64 --height 64 --sky-mode march --render-scale 1 --bloom-mips 5 --exposure 12 --validate)
    timeout 120 "${run[@]}" "${W[@]}" --screenshot "$work/w1.png" >"$work/w1.out" 2>&1 || fail "window: single queue failed"
    timeout 120 "${run[@]}" "${W[@]}" --async-luts --trace-barriers --screenshot "$work/w2.png" >"$work/w2.out" 2>&1 \
        || fail "window --async-luts failed: $(grep -v '^barrier\|^batch\|^pass' "$work/w2.out" | head -c 400)"
    grep -q '^validation_messages 0$' "$work/w2.out" || fail "window --async-luts: validation messages"
    grep -q '^semaphore compute_done.signal queue=compute value=1 ' "$work/w2.out" || fail "window: no LUT build on the compute queue"
    cmp -s "$work/w1.png" "$work/w2.png" || fail "window --async-luts: the screenshot differs from the single-queue window's"
fi

[ $fails -eq 0 ] && echo "async_luts: ok" || exit 1
