#!/usr/bin/env bash
# tools/qfot_drops.sh [VKSKY]: the LUTs' queue-family ownership transfer, drop-tested on a device that has it (issue
# 25 item 4; docs/synchronization.md §10, "Drop tests"). For a GPU with a compute-only queue family (an NVIDIA H100:
# family 2): `--async-luts` then builds the LUTs on family 2 and hands them to the graphics family 0 with a release
# (compute command buffer) and an acquire (the frame's) barrier per LUT. Lavapipe has one family: there every line
# skips and this script exits 77 with one line.
#
# Runs every line of tests/qfot_drops.txt through tests/barrier_drop_test.sh (validation + synchronization
# validation, two frames each rebuilding the LUTs, VKSKY_DROP_BARRIER=<name>; the trace must mark the barrier
# DROPPED) and prints
#   clean CONFIG: ok | reported IDS               each config undropped: must be validation-clean
#   dropped NAME (CONFIG): seen by IDS [as expected {SET} | EXPECTED {SET}]
#   dropped NAME (CONFIG): NOT SEEN [...]         the layer reported nothing for the missing barrier
# (IDS: the layer's message ids; SET: tests/barrier_drops.txt's kinds: no_release, pending_release, layout, RAW...).
# Then the traced transfer of one frame (both families on each `qfot` line), the device, driver and layer.
#
# From the GPU bundle (docs: /work/shared/notes/gpu-device.md): build Release, `../shared/tools/gpu-bundle
# build/vksky`, then with the device tool, carry [".gpu"]:
#   source .gpu/env.sh && tools/qfot_drops.sh | tee $OUT/qfot.txt
# (vksky from PATH, i.e. .gpu/bin, unless VKSKY is given; default build/vksky when there is none on PATH.)
#
# Exit 0: every config clean and every drop reported as tests/qfot_drops.txt expects; 1: a difference (the lines say
# which: a NOT SEEN or a different set is a finding to record in the list and the guide, not a crash); 2: usage;
# 77: the device has no compute-only queue family.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
V=${1:-$(command -v vksky || echo "$root/build/vksky")}
V=$(readlink -f "$V" 2>/dev/null || echo "$V")
[ -x "$V" ] || { echo "qfot_drops.sh: '$V' is not an executable (give the path of vksky)" >&2; exit 2; }
list=${QFOT_DROPS_LIST:-$root/tests/qfot_drops.txt}   # another list of that format: QFOT_DROPS_LIST=FILE
drop_test=$root/tests/barrier_drop_test.sh
if [ ! -f "$list" ] || [ ! -x "$drop_test" ]; then echo "qfot_drops.sh: run it from a vksky checkout (no $list)" >&2; exit 2; fi
export BARRIER_IDS=1
unset VKSKY_DROP_BARRIER VKSKY_WEAKEN_BARRIER VKSKY_ASYNC_ONE_QUEUE
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "# device: $("$V" --list-devices 2>/dev/null | head -n 1)"
layer_json=${VK_LAYER_PATH:-/usr/share/vulkan/explicit_layer.d}
layer_json=${layer_json%%:*}/VkLayer_khronos_validation.json
[ -f "$layer_json" ] || layer_json=
echo "# validation layer: $([ -n "$layer_json" ] && grep -o '"api_version": *"[^"]*"' "$layer_json" | head -n 1 || echo "not found")"
echo "# $(date -u +%FT%TZ), $("$V" --version 2>/dev/null)"

fails=0
seen=0
notseen=0
# The undropped frames first: a message there would make every drop's report meaningless.
for cfg in $(awk '$1 == "config" { print $2 }' "$list"); do
    out=$("$drop_test" "$V" "$list" - "$cfg" 2>&1)
    rc=$?
    if [ $rc -eq 77 ]; then
        echo "qfot_drops.sh: skipped: ${out#SKIP: }"
        exit 77
    fi
    ids=$(sed -n 's/^ids: //p' <<<"$out")
    if [ $rc -eq 0 ]; then echo "clean $cfg: ok"
    else echo "clean $cfg: reported ${ids:-an error}"; grep -v '^ids: ' <<<"$out" | head -n 8 | sed 's/^/  /'; fails=$((fails + 1)); fi
done

while read -r name cfg expected _; do
    out=$("$drop_test" "$V" "$list" "$name" "$cfg" 2>&1)
    rc=$?
    ids=$(sed -n 's/^ids: //p' <<<"$out")
    got=$(sed -n 's/^ok: .*: {\(.*\)}$/\1/p; s/^FAIL: .*validation reported {\([^}]*\)}.*/\1/p' <<<"$out" | head -n 1)
    if [ $rc -eq 77 ]; then echo "dropped $name ($cfg): skipped: ${out#SKIP: }"; continue; fi
    verdict=$([ $rc -eq 0 ] && echo "as expected {$expected}" || echo "EXPECTED {$expected}, got {${got:-?}}")
    if [ -n "$ids" ]; then
        echo "dropped $name ($cfg): seen by $ids [$verdict]"
        seen=$((seen + 1))
    else
        echo "dropped $name ($cfg): NOT SEEN [$verdict]"
        notseen=$((notseen + 1))
    fi
    # Not a report of the layer's: the barrier was not left out, or the run failed otherwise.
    grep '^FAIL: ' <<<"$out" | grep -v 'validation reported' | sed 's/^/  /'
    [ $rc -eq 0 ] || { fails=$((fails + 1)); grep -v '^ids: \|^FAIL: \|^ok: ' <<<"$out" | head -n 6 | sed 's/^/  /'; }
done < <(awk '$1 != "config" && $1 != "requires" && $1 !~ /^#/ && NF >= 3 { print $1, $2, $3 }' "$list")

# The transfer as traced, one frame of the first config: release lines on the compute queue, acquires on the graphics.
args=$(awk '$1 == "config" { $1 = $2 = $3 = ""; sub(/^ +/, ""); print; exit }' "$list")
# shellcheck disable=SC2086  # ARGS are words
VKSKY_LUT_CACHE=0 "$V" ${args//OUT/$work/out} --trace-barriers >"$work/trace" 2>"$work/trace.err"
grep -E '^(queues|qfot|barrier [a-z_]+\.(release|acquire)|semaphore)' "$work/trace" | sed 's/^/trace: /'

echo "qfot_drops.sh: $seen drops seen, $notseen not seen, $fails difference(s) from $(basename "$list")"
[ $fails -eq 0 ]
