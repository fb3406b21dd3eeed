#!/usr/bin/env bash
# tests/host_read_barriers_test.sh VKSKY LUT_PROBE: the host-read barriers proven without the layer (issue 31).
#
# The drop list (tests/barrier_drops.txt) expects "none" for readback.linear_to_host, readback.display_to_host,
# aovs.to_host, lut_readback.to_host and capture.to_host: the validation layer does not model host reads of mapped
# memory, so dropping them reports nothing, and lavapipe's and an H200's pixels are the same without them. What the
# barrier must be is known from the spec, not from the program: a fence signal's first access scope holds device
# accesses only ("the results of memory accesses will not be visible to the host" without "a memory barrier or
# other memory dependency", Vulkan spec, vkWaitForFences / 7.3 Fences; Khronos "Synchronization Examples": "a
# transfer writes a buffer, the host reads it": src TRANSFER(COPY) / TRANSFER_WRITE, dst HOST / HOST_READ). So,
# written here as a table of the hazard (a copy writes a buffer, the host reads it after the fence), each barrier's
# traced masks (--trace-barriers, from the masks handed to vkCmdPipelineBarrier2) must have:
#   src stage:  COPY or ALL_COMMANDS        (a stage that contains the copy)
#   src access: TRANSFER_WRITE or MEMORY_WRITE
#   dst stage:  HOST                        (ALL_COMMANDS does not contain the host: it is no command's stage)
#   dst access: HOST_READ or MEMORY_READ
# For a compute shader's write the host reads (the meter's result: meter.result_to_host), the source side is the
# shader's instead: src stage COMPUTE_SHADER or ALL_COMMANDS, src access SHADER_STORAGE_WRITE, SHADER_WRITE or
# MEMORY_WRITE (the spec's "compute shader writes a buffer, the host reads it"). The LUT cache's readback
# (lut_cache.readback_to_host, tests/lut_cache_probe beside LUT_PROBE) is a copy like the others. The meter's host
# read is recorded in three configurations of the drop list (meter, meter_post, window_nobloom): each is checked.
# and its place: in the command buffer of the copy that writes the buffer, after it (the copy's pass, or the
# barrier that makes the copy's source readable, precedes it with no other command buffer between), flushed by a
# batch of its point. Each run is validated (--validate; any message fails the run).
# That the check can fail: the first barrier is weakened field by field (VKSKY_WEAKEN_BARRIER: src stage NONE, src
# access NONE, dst stage ALL_COMMANDS, dst access NONE; a dst access the HOST stage cannot perform is the layer's
# own catch, VUID-VkBufferMemoryBarrier2-dstAccessMask-03905), each other one at its dst stage (ALL_COMMANDS), and
# the check must reject every mutant. 21 validated runs of 16x16 frames (the windows' 64x64): ~12 s of CPU.
# capture.to_host is recorded in the window's screenshot frame (VKSKY_TRACE_CAPTURE=1 traces it): under xvfb;
# without a display and Xvfb the test SKIPs (77).
set -u
VKSKY=${1:?usage: host_read_barriers_test.sh VKSKY LUT_PROBE}
PROBE=${2:?usage: host_read_barriers_test.sh VKSKY LUT_PROBE}
HERE=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
export VKSKY_VALIDATION=1
RENDER=(--width 16 --height 16 --quality lesson --units relative --validate --trace-barriers)
window=1
if [ -z "${DISPLAY:-}" ] && ! command -v Xvfb >/dev/null; then window=0; fi

# run KIND OUT: the configuration that records the barrier, its trace in OUT (status and stderr checked).
run() {
    local kind=$1 out=$2 rc
    case $kind in
        render) "$VKSKY" "${RENDER[@]}" --render "$work/r.png" >"$out" 2>"$work/err" ;;
        aovs) "$VKSKY" "${RENDER[@]}" --aovs --render "$work/a.exr" >"$out" 2>"$work/err" ;;
        probe) "$PROBE" --validate --trace-barriers >"$out" 2>"$work/err" ;;
        meter) "$VKSKY" "${RENDER[@]}" --auto-exposure --render "$work/m.png" >"$out" 2>"$work/err" ;;
        meter_post) "$VKSKY" "${RENDER[@]}" --auto-exposure --post-pass compute --render "$work/m.png" >"$out" 2>"$work/err" ;;
        lutprobe) env -u VKSKY_LUT_CACHE XDG_CACHE_HOME="$work/xdg" "$(dirname "$PROBE")/lut_cache_probe" --validate \
                      --trace-barriers >"$out" 2>"$work/err" ;;
        spectral) "$(dirname "$PROBE")/api/api_drop_probe" --spectral --validate --trace-barriers >"$out" 2>"$work/err" ;;
        window) VKSKY_TRACE_CAPTURE=1 "$HERE/xvfb_run.sh" 640x480x24 "$VKSKY" --frames 2 --width 64 --height 64 \
                    --sky-mode march --render-scale 1 --validate --trace-barriers --screenshot "$work/s.png" \
                    >"$out" 2>"$work/err" ;;
        window_nobloom) "$HERE/xvfb_run.sh" 640x480x24 "$VKSKY" --frames 2 --width 64 --height 64 --sky-mode march \
                            --render-scale 1 --bloom-mips 5 --no-bloom --validate --trace-barriers >"$out" 2>"$work/err" ;;
    esac
    rc=$?
    [ $rc -eq 0 ] && ! grep -qi 'validation' "$work/err" && return 0
    echo "run $kind: exit $rc: $(head -c 400 "$work/err")"
    return 1
}

# check NAME BEFORE TRACE [WRITER]: the barrier against the hazard's table (WRITER copy, the default, or compute)
# and its place; prints why not, exit 1.
check() {
    awk -v name="$1" -v before="$2" -v writer="${4:-copy}" '
        function has(list, want,   n, a, i) { n = split(list, a, "|"); for (i = 1; i <= n; ++i) if (a[i] == want) return 1; return 0 }
        $1 == "commands" { cmd++; next }
        ($1 == "pass" && $2 == before) || ($1 == "barrier" && $2 == before) { copy_cmd = cmd; seen_copy = 1; next }
        $1 == "barrier" && $2 == name {
            found++
            if (!seen_copy || copy_cmd != cmd) { printf "%s: not after %s in its command buffer\n", name, before; bad++ }
            for (i = 3; i <= NF; ++i) {
                if ($i ~ /^src=/) { split(substr($i, 5), s, "/"); ss = s[1]; sa = s[2] }
                if ($i ~ /^dst=/) { split(substr($i, 5), d, "/"); ds = d[1]; da = d[2] }
                if ($i ~ /^point=/) point = substr($i, 7)
            }
            if ($0 ~ / point=/) { p = $0; sub(/.* point=/, "", p); sub(/ resource=.*/, "", p); point = p }
            wstage = writer == "compute" ? "COMPUTE_SHADER" : "COPY"
            if (!has(ss, wstage) && !has(ss, "ALL_COMMANDS")) { printf "%s: src stage %s does not contain the %s\n", name, ss, writer; bad++ }
            if (writer == "compute" && !has(sa, "SHADER_STORAGE_WRITE") && !has(sa, "SHADER_WRITE") && !has(sa, "MEMORY_WRITE")) {
                printf "%s: src access %s lacks the shader write\n", name, sa; bad++ }
            if (writer != "compute" && !has(sa, "TRANSFER_WRITE") && !has(sa, "MEMORY_WRITE")) { printf "%s: src access %s lacks the copy write\n", name, sa; bad++ }
            if (!has(ds, "HOST")) { printf "%s: dst stage %s is not HOST\n", name, ds; bad++ }
            if (!has(da, "HOST_READ") && !has(da, "MEMORY_READ")) { printf "%s: dst access %s lacks HOST_READ\n", name, da; bad++ }
            waiting = 1; bcmd = cmd; next
        }
        waiting && $1 == "batch" { b = $0; sub(/^batch point=/, "", b); sub(/ images=.*/, "", b)
                                   if (b == point && cmd == bcmd) flushed = 1; waiting = 0 }
        END {
            if (!found) { printf "%s: not in the trace\n", name; exit 1 }
            if (!flushed) { printf "%s: no batch of its point flushed it\n", name; bad++ }
            exit bad != 0
        }' "$3"
}

# NAME KIND BEFORE (the line the copy leaves in the trace just before the barrier's batch)
cases=("readback.linear_to_host render readback" "readback.display_to_host render readback"
       "aovs.to_host aovs composite_readback" "lut_readback.to_host probe lut_readback.to_copy"
       "capture.to_host window display.write_to_capture" "meter.result_to_host meter meter_average compute"
       "lut_cache.readback_to_host lutprobe lut_cache_readback"
       "meter.result_to_host meter_post meter_average compute" "meter.result_to_host window_nobloom meter_average compute"
       "spectral.resolved_to_host spectral spectral_sum compute")
checked=0
for c in "${cases[@]}"; do
    read -r name kind before writer <<<"$c"
    [ "${kind#window}" != "$kind" ] && [ $window -eq 0 ] && continue
    unset VKSKY_WEAKEN_BARRIER
    if ! run "$kind" "$work/trace"; then fail "$name: the run failed"; continue; fi
    why=$(check "$name" "$before" "$work/trace" "$writer") || { fail "$why"; continue; }
    echo "ok: $name @ $kind ($(grep -m1 "^barrier $name " "$work/trace" | grep -o 'src=[^ ]* dst=[^ ]*'))"
    mutants=(dststage=ALL_COMMANDS)   # the first barrier: every field; the others: the host side's stage
    [ $checked -eq 0 ] && mutants=(srcstage=NONE srcaccess=NONE dststage=ALL_COMMANDS dstaccess=NONE)
    for m in "${mutants[@]}"; do
        export VKSKY_WEAKEN_BARRIER="$name:$m"
        if ! run "$kind" "$work/mutant"; then fail "$name weakened ($m): the run failed"; continue; fi
        grep -q "^barrier $name .*WEAKENED=" "$work/mutant" || { fail "$name: the mutation $m did not apply"; continue; }
        check "$name" "$before" "$work/mutant" "$writer" >/dev/null && fail "$name weakened ($m): the check still passes"
    done
    unset VKSKY_WEAKEN_BARRIER
    checked=$((checked + 1))
done
[ $fails -eq 0 ] || { echo "host_read_barriers: $fails failure(s)"; exit 1; }
[ $window -eq 1 ] || { echo "host_read_barriers: SKIP: capture.to_host needs a display or Xvfb"; exit 77; }
echo "host_read_barriers: ok ($checked barriers, every mutant rejected)"
