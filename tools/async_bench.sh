#!/usr/bin/env bash
# --async-luts on a GPU (issue 25 item 4, docs/synchronization.md §10). A benchmark plus a correctness check, for a
# device with a second queue (an NVIDIA H100: a compute-only queue family, so the path with the queue-family
# ownership transfer). Lavapipe has one queue: run it there with VKSKY_ASYNC_ONE_QUEUE=1 (both submissions on the
# one queue).
#
#   tools/async_bench.sh [VKSKY] [EXR_PIXELS] [FRAMES]     (defaults build/vksky build/tests/exr_pixels 200)
#   e.g. on lavapipe: VKSKY_ASYNC_ONE_QUEUE=1 BENCH_SIZE=320x180 tools/async_bench.sh build/vksky '' 30
#
# (a) Correctness, under --validate (validation + synchronization validation; any message fails): each LUT variant
#     (default, sky-view, compute sky pass, no multi-scattering, lit ground), two frames each rebuilding the LUTs
#     (VKSKY_FRAMES=2), with and without --async-luts: the EXR pixels must be bit-identical; the trace's `queues` and
#     `qfot` lines say which path ran (release + acquire barriers for another family). The validation layer's
#     version is printed: synchronization validation before 1.3.250 does not check hazards across submissions, so
#     there the semaphores are only checked by the pixels and by the core layer's ownership-transfer checks. Then
#     each release/acquire barrier and semaphore wait left out in turn: what validation reports (a report).
# (b) Speed: `vksky --bench FRAMES` at 1920x1080 (warm-up, medians), with and without --async-luts, alternated
#     twice: `frame_luts wall_ms` is a frame that rebuilds its LUTs (as a frame whose atmosphere changes every frame;
#     the bench's forced-LUT frames), submit to fence; `frame gpu_ms` / `wall_ms` the steady frame (no LUT rebuild);
#     the LUT passes' GPU ms (on the compute queue with --async-luts). Report the device and driver with the figures.
set -u
V=$(readlink -f "${1:-build/vksky}")
P=${2:-}
PIX=$(readlink -f "${P:-$(dirname "$V")/tests/exr_pixels}")
N=${3:-200}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
echo "# device: $("$V" --list-devices 2>/dev/null | head -1)"
echo "# validation layer: $(dpkg-query -W -f '${Version}' vulkan-validationlayers 2>/dev/null || ls /usr/share/vulkan/explicit_layer.d 2>/dev/null | tr '\n' ' ')"
for v in /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json; do
    [ -f "$v" ] && echo "# layer json: $(grep -o '"implementation_version": *"[^"]*"\|"api_version": *"[^"]*"' "$v" | tr '\n' ' ')"
done

A=(--width 96 --height 64 --quality lesson --units relative --validate)
VKSKY=$V
# shellcheck source=tests/async_pixels.sh
. "$(dirname "$(readlink -f "$0")")/../tests/async_pixels.sh"
i=0
while read -r name extra; do
    i=$((i + 1))
    # shellcheck disable=SC2086
    why=$(async_pair "$i" "$name" $extra)
    case $? in
        0) same=identical ;;
        2) same=DIFFERENT; echo "$why"; fails=$((fails + 1)) ;;
        *) echo "FAIL $why"; fails=$((fails + 1)); continue ;;
    esac
    echo "check $name pixels=$same $(grep -m1 '^queues ' "$work/a$i.trace") releases=$(grep -c '^qfot .* release ' "$work/a$i.trace") acquires=$(grep -c '^qfot .* acquire ' "$work/a$i.trace")"
done < <(async_variants)
# The ownership-transfer barriers, once, as traced (another family only).
grep -m6 -E '^(qfot|barrier [a-z_]+\.(release|acquire)|semaphore)' "$work/a1.trace" | sed 's/^/trace: /'

# What validation reports when one piece of the cross-queue synchronization is left out (VKSKY_DROP_BARRIER; the
# trace marks it DROPPED): a report, not a check; docs/synchronization.md §10 records it.
drops="compute_done.wait graphics_done.wait"
grep -q '^qfot .* release ' "$work/a1.trace" && drops="transmittance.release multiscatter.release transmittance.acquire multiscatter.acquire $drops"
for d in $drops; do
    VKSKY_DROP_BARRIER=$d VKSKY_FRAMES=2 "$V" --render "$work/d.exr" "${A[@]}" --async-luts >/dev/null 2>"$work/d.err"
    rc=$?
    ids=$(grep -o '\[ [A-Za-z0-9_-]* \]' "$work/d.err" | tr -d '[] ' | sort -u | paste -sd+ -)
    echo "drop $d exit=$rc reported=${ids:-none} pixels=$("$PIX" same "$work/s1.exr" "$work/d.exr" 2>/dev/null && echo identical || echo different)"
done

SIZE=${BENCH_SIZE:-1920x1080}   # BENCH_SIZE=WxH: smaller on lavapipe
B=(--width "${SIZE%x*}" --height "${SIZE#*x}" --bench "$N")
for round in 1 2; do
    for mode in single async; do
        flag=(); [ $mode = async ] && flag=(--async-luts)
        "$V" "${B[@]}" "${flag[@]}" >"$work/bench" 2>"$work/bench.err" || { echo "FAIL bench $mode: $(head -c 300 "$work/bench.err")"; fails=$((fails + 1)); continue; }
        echo "bench round=$round mode=$mode $(awk '/^frame_luts / { l = $3 } /^frame gpu_ms/ { g = $3; w = $5 }
            /^pass transmittance_lut/ { t = $4 } /^pass multiscatter_lut/ { m = $4 }
            END { printf "frame_luts_wall_ms=%s steady_gpu_ms=%s steady_wall_ms=%s transmittance_lut_gpu_ms=%s multiscatter_lut_gpu_ms=%s", l, g, w, t, m }' "$work/bench")"
    done
done
[ $fails -eq 0 ] && echo "async_bench: ok" || { echo "async_bench: $fails failure(s)"; exit 1; }
