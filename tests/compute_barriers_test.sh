#!/usr/bin/env bash
# tests/compute_barriers_test.sh VKSKY: the compute -> compute barriers proven without the layer (issue 31).
#
# The drop list (tests/barrier_drops.txt) expects "none" for meter.partials_to_average (config meter) and
# meter.result_to_tonemap with the compute tone map (config meter_post): a compute shader writes a storage buffer,
# a later dispatch's compute shader reads it, and the validation layer of Debian 12 (1.3.239) reports nothing when
# the barrier is left out (its sync validation does not flag this buffer's dispatch -> dispatch RAW), so the drop
# test cannot fail for the barrier's absence. What the barrier must be is known from the spec, not from the program:
# Vulkan spec 7.1 "Execution and Memory Dependencies": a memory dependency makes the writes of its first access
# scope available and visible to its second; an access scope holds only the accesses of the stages *explicitly*
# in its stage mask (logically earlier/later stages give execution order, not memory access), and only the access
# types named (MEMORY_WRITE / MEMORY_READ name all; SHADER_WRITE is SHADER_STORAGE_WRITE for a buffer, SHADER_READ
# contains SHADER_STORAGE_READ). ALL_COMMANDS is "the logical OR of every stage". The Khronos "Synchronization
# Examples" (Vulkan-Docs wiki), "Compute to compute, first dispatch writes a storage buffer, second dispatch reads
# it": src COMPUTE_SHADER / SHADER_WRITE, dst COMPUTE_SHADER / SHADER_READ. So, written here as the hazard's table
# (a compute shader's storage write, then a compute shader's storage read of the same buffer), each barrier's traced
# masks (--trace-barriers: the masks handed to vkCmdPipelineBarrier2) must have:
#   src stage:  COMPUTE_SHADER or ALL_COMMANDS       (FRAGMENT_SHADER, TOP_OF_PIPE, NONE hold no compute write)
#   src access: SHADER_STORAGE_WRITE, SHADER_WRITE or MEMORY_WRITE   (a read makes nothing available)
#   dst stage:  COMPUTE_SHADER or ALL_COMMANDS       (BOTTOM_OF_PIPE or FRAGMENT_SHADER: not the reader's stage)
#   dst access: SHADER_STORAGE_READ, SHADER_READ or MEMORY_READ      (SHADER_SAMPLED_READ is another access type)
# and its place: in the command buffer of the writing dispatch, its batch (a vkCmdPipelineBarrier2 of its point)
# recorded after the writer's pass and before the reader's pass (a barrier orders only what was recorded before it
# against what is recorded after it).
# That the check can fail: each barrier is weakened field by field (VKSKY_WEAKEN_BARRIER), two mutants a field (the
# empty mask and a plausible wrong one), and the check must reject every mutant. Each run is validated (--validate;
# a message fails the run, except a mutant's masks the layer itself rejects, counted as rejected). 18 validated runs
# of 16x16 frames: ~15 s of CPU on lavapipe.
set -u
VKSKY=${1:?usage: compute_barriers_test.sh VKSKY}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
export VKSKY_VALIDATION=1
RENDER=(--width 16 --height 16 --quality lesson --units relative --validate --trace-barriers --auto-exposure)

# run CONFIG OUT: the configuration that records the barrier (tests/barrier_drops.txt's meter / meter_post), its trace
# in OUT. Returns 0 (clean), 1 (failed), 2 (only the layer's complaint about the barrier's own masks: a VUID).
run() {
    local config=$1 out=$2 rc extra=()
    [ "$config" = meter_post ] && extra=(--post-pass compute)
    "$VKSKY" "${RENDER[@]}" "${extra[@]}" --render "$work/m.png" >"$out" 2>"$work/err"
    rc=$?
    grep -v '^vksky: auto exposure: ' "$work/err" >"$work/err.other"
    [ $rc -eq 0 ] && [ ! -s "$work/err.other" ] && return 0
    grep -q 'VUID-VkBufferMemoryBarrier2-\(src\|dst\)\(Stage\|Access\)Mask' "$work/err.other" && return 2
    echo "run $config: exit $rc: $(head -c 400 "$work/err.other")"
    return 1
}

# check NAME WRITER READER TRACE: the barrier against the hazard's table and its place; prints why not, exit 1.
check() {
    awk -v name="$1" -v writer="$2" -v reader="$3" '
        function has(list, want,   n, a, i) { n = split(list, a, "|"); for (i = 1; i <= n; ++i) if (a[i] == want) return 1; return 0 }
        $1 == "commands" { cmd++; wrote = 0; pending = 0; next }
        $1 == "pass" && $2 == writer { wrote = 1; next }
        $1 == "barrier" && $2 == name {
            found++
            if (!wrote) { printf "%s: not after the %s pass in its command buffer\n", name, writer; bad++ }
            for (i = 3; i <= NF; ++i) {
                if ($i ~ /^src=/) { split(substr($i, 5), s, "/"); ss = s[1]; sa = s[2] }
                if ($i ~ /^dst=/) { split(substr($i, 5), d, "/"); ds = d[1]; da = d[2] }
            }
            p = $0; sub(/.* point=/, "", p); sub(/ resource=.*/, "", p); point = p
            if (!has(ss, "COMPUTE_SHADER") && !has(ss, "ALL_COMMANDS")) { printf "%s: src stage %s does not hold the compute write\n", name, ss; bad++ }
            if (!has(sa, "SHADER_STORAGE_WRITE") && !has(sa, "SHADER_WRITE") && !has(sa, "MEMORY_WRITE")) {
                printf "%s: src access %s lacks the storage write\n", name, sa; bad++ }
            if (!has(ds, "COMPUTE_SHADER") && !has(ds, "ALL_COMMANDS")) { printf "%s: dst stage %s does not hold the compute read\n", name, ds; bad++ }
            if (!has(da, "SHADER_STORAGE_READ") && !has(da, "SHADER_READ") && !has(da, "MEMORY_READ")) {
                printf "%s: dst access %s lacks the storage read\n", name, da; bad++ }
            pending = 1; next
        }
        pending && $1 == "batch" { b = $0; sub(/^batch point=/, "", b); sub(/ images=.*/, "", b)
                                   if (b == point) { pending = 0; flushed_before_read = 1 } ; next }
        $1 == "pass" && $2 == reader && wrote && found { read_after = 1; if (pending) { printf "%s: its batch comes after the %s pass\n", name, reader; bad++ } }
        END {
            if (!found) { printf "%s: not in the trace\n", name; exit 1 }
            if (!flushed_before_read) { printf "%s: no batch of its point flushed it\n", name; bad++ }
            if (!read_after) { printf "%s: no %s pass after it\n", name, reader; bad++ }
            exit bad != 0
        }' "$4"
}

# NAME CONFIG WRITER READER (the passes as the trace names them)
cases=("meter.partials_to_average meter meter meter_average"
       "meter.result_to_tonemap meter_post meter_average tonemap")
mutants=(srcstage=NONE srcstage=FRAGMENT_SHADER srcaccess=NONE srcaccess=SHADER_STORAGE_READ dststage=NONE
         dststage=FRAGMENT_SHADER dstaccess=NONE dstaccess=SHADER_SAMPLED_READ)
checked=0
for c in "${cases[@]}"; do
    read -r name config writer reader <<<"$c"
    unset VKSKY_WEAKEN_BARRIER
    run "$config" "$work/trace" || { fail "$name: the run failed"; continue; }
    why=$(check "$name" "$writer" "$reader" "$work/trace") || { fail "$why"; continue; }
    echo "ok: $name ($(grep -m1 "^barrier $name " "$work/trace" | grep -o 'src=[^ ]* dst=[^ ]*'))"
    for m in "${mutants[@]}"; do
        export VKSKY_WEAKEN_BARRIER="$name:$m"
        run "$config" "$work/mutant"
        case $? in
            0) ;;
            2) echo "   $m: rejected by the layer ($(grep -o 'VUID-[A-Za-z0-9_-]*' "$work/err.other" | head -1))"; continue ;;
            *) fail "$name weakened ($m): the run failed"; continue ;;
        esac
        grep -q "^barrier $name .*WEAKENED=" "$work/mutant" || { fail "$name: the mutation $m did not apply"; continue; }
        if why=$(check "$name" "$writer" "$reader" "$work/mutant"); then
            fail "$name weakened ($m): the check still passes"
        else
            echo "   $m: rejected ($(echo "$why" | paste -sd";" -))"
        fi
    done
    unset VKSKY_WEAKEN_BARRIER
    checked=$((checked + 1))
done
[ $fails -eq 0 ] || { echo "compute_barriers: $fails failure(s)"; exit 1; }
echo "compute_barriers: ok ($checked barriers, every mutant rejected)"
