#!/usr/bin/env bash
# The window's present-fence path (VK_EXT_swapchain_maintenance1; docs/synchronization.md §6 and §14) run once on
# Khronos' mock ICD, under a validation layer with synchronization validation on, and shown to have run.
#
#   tools/present_fences.sh MOCK_ICD_JSON LAYER_DIR [--vksky PATH] [--frames N] [--out DIR]
#
# Why a tool and not a ctest: no device CI or a developer here has runs that path. lavapipe 22.3 (Debian 12) lacks
# VK_EXT_swapchain_maintenance1, so the window falls back to vkDeviceWaitIdle; the GPU hosts' drivers have it but no
# display and no headless surface. The mock ICD of Vulkan-Tools advertises every extension and X11 surfaces; it
# executes nothing (no pixel is drawn, a fence wait returns at once), but every call goes through the validation
# layer as on a real device, which is what this checks. Building it takes minutes (recipe below), more than CI has.
#
# MOCK_ICD_JSON: the mock ICD's manifest (its build's icd/VkICD_mock_icd.json). LAYER_DIR: a directory holding
# VkLayer_khronos_validation.json (as tools/newer_layer.sh takes it: Debian's 1.3.239 or a newer one built from source).
#
# It runs the window unchanged (under Xvfb (tests/xvfb_run.sh) when there is no DISPLAY) with --validate, the layer's shader-access
# heuristic on, and VKSKY_TEST_RESIZE=1: the window resizes itself at presented frames 20, 40 and 60 (three swapchain
# recreations with oldSwapchain, each retiring the old images' render-finished semaphores) and minimises at 80; then
# --frames N (default 120) frames and the normal shutdown (the last swapchain's semaphores, the same path). Under gdb
# (batch mode, breakpoints that count and continue) it counts, by their source lines (found by text in
# src/app/window/swapchain.c, so an edited file fails loudly instead of counting the wrong line):
#   fence_armed   swapchain_present_fence handed a present a fence (ctx->present_fences was true): once a present
#   fence_reused  the same image's previous present fence waited for and reset before its next present
#   fence_retire  swapchain_wait_presents waited for a pending present fence before destroying that image's semaphore
#                 (breakpoint hits: gdb may set several locations on one line and one wait may hit two of them)
# and checks: every present was given a fence, fence_retire > 0 (the present fences, not vkDeviceWaitIdle alone,
# retired semaphores), at least 3 recreations, and no validation message. Writes DIR (default build/present_fences):
# window.out, window.err (vksky's), gdb.log, summary.txt. Exit 0 when every check holds, 1 when one fails, 2 on bad
# arguments or a missing tool (gdb, Xvfb).
#
# Building the mock ICD (Vulkan-Tools at the layer's SDK tag; headers from Vulkan-Headers at the same tag, e.g.
# /work/vvl/deps of docs/synchronization.md §14's recipe). Four patches, none touching what the layer checks, are
# needed for vksky to create its device and recreate a swapchain there (the mock is meant to run under the Profiles
# layer, which sets features and limits; we have none):
#   - icd/generated/function_definitions.h DestroySwapchainKHR: swapchain_image_map.erase(swapchain) instead of
#     .clear() (clear() also drops the new swapchain's images, so vkGetSwapchainImagesKHR after a recreation with
#     oldSwapchain throws std::out_of_range);
#   - GetPhysicalDeviceFeatures2KHR: every VkBool32 of VkPhysicalDeviceVulkan12Features/13Features and
#     swapchainMaintenance1 set (the mock leaves dynamicRendering, maintenance4 and swapchainMaintenance1 false);
#   - GetPhysicalDeviceProperties2KHR: Vulkan11Properties.maxMemoryAllocationSize 4 GiB, maxPerSetDescriptors 1024,
#     the Vulkan12Properties update-after-bind limits 2^20 (the mock leaves them 0, which the layer reports on every
#     allocation and pipeline layout);
#   - icd/mock_icd.h SetLimits: maxComputeWorkGroupInvocations and maxComputeWorkGroupSize[0..1] 1024,
#     maxComputeSharedMemorySize 49152 (the mock sets the specification's minimums, 128 and 16384: vksky's 16 x 16
#     workgroups and its single-pass downsampler's shared memory need more, as every device it runs on has);
#   - icd/CMakeLists.txt: -DVK_USE_PLATFORM_XLIB_XRANDR_EXT removed (Debian 12 without libxrandr-dev).
#   git -C Vulkan-Tools-mirror archive --prefix=Vulkan-Tools/ vulkan-sdk-1.4.357.0 | tar x   # then the patches
#   cmake -S Vulkan-Tools -B build -DCMAKE_PREFIX_PATH=/work/vvl/deps -DBUILD_CUBE=OFF -DBUILD_VULKANINFO=OFF \
#     -DBUILD_ICD=ON -DBUILD_TESTS=OFF -DUPDATE_DEPS=OFF -DBUILD_WSI_XCB_SUPPORT=ON -DBUILD_WSI_XLIB_SUPPORT=ON \
#     -DBUILD_WSI_WAYLAND_SUPPORT=OFF -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS='-O1 -g'
#   cmake --build build -j2          # one C++ file; a few minutes
#   tools/present_fences.sh build/icd/VkICD_mock_icd.json /work/vvl/install/share/vulkan/explicit_layer.d
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
usage="usage: tools/present_fences.sh MOCK_ICD_JSON LAYER_DIR [--vksky PATH] [--frames N] [--out DIR]"
icd= layer_dir= vksky=$root/build/vksky frames=120 out=$root/build/present_fences
while [ $# -gt 0 ]; do
    case $1 in
    --vksky) vksky=${2:?--vksky needs a path}; shift ;;
    --frames) frames=${2:?--frames needs a number}; shift ;;
    --out) out=${2:?--out needs a directory}; shift ;;
    -*) echo "present_fences: unknown option '$1'; $usage" >&2; exit 2 ;;
    *) if [ -z "$icd" ]; then icd=$1; elif [ -z "$layer_dir" ]; then layer_dir=$1
       else echo "present_fences: too many arguments; $usage" >&2; exit 2; fi ;;
    esac
    shift
done
[ -n "$icd" ] && [ -n "$layer_dir" ] || { echo "present_fences: MOCK_ICD_JSON and LAYER_DIR are needed; $usage" >&2; exit 2; }
[ -f "$icd" ] || { echo "present_fences: no ICD manifest '$icd' (the mock ICD build's icd/VkICD_mock_icd.json)" >&2; exit 2; }
[ -f "$layer_dir/VkLayer_khronos_validation.json" ] || { echo "present_fences: no VkLayer_khronos_validation.json in '$layer_dir'" >&2; exit 2; }
[ -x "$vksky" ] || { echo "present_fences: no vksky at '$vksky' (build first, or give --vksky PATH)" >&2; exit 2; }
case $frames in '' | *[!0-9]*) echo "present_fences: --frames must be a whole number >= 100, not '$frames'" >&2; exit 2 ;; esac
[ "$frames" -ge 100 ] || { echo "present_fences: --frames must be >= 100 (the resizes end at frame 80), not $frames" >&2; exit 2; }
command -v gdb >/dev/null || { echo "present_fences: needs gdb (Debian package gdb)" >&2; exit 2; }
run=()
if [ -z "${DISPLAY:-}" ]; then
    command -v Xvfb >/dev/null || { echo "present_fences: no DISPLAY and no Xvfb (Debian package xvfb)" >&2; exit 2; }
    run=("$root/tests/xvfb_run.sh" 640x480x24)
fi
mkdir -p "$out/layer" || exit 2
out=$(cd "$out" && pwd)
icd=$(cd "$(dirname "$icd")" && pwd)/$(basename "$icd")

# The layer's manifest with its library's absolute path (a bare name would resolve to Debian's library): as
# tools/newer_layer.sh does.
json=$layer_dir/VkLayer_khronos_validation.json
lib=$(sed -n 's/.*"library_path" *: *"\([^"]*\)".*/\1/p' "$json")
case $lib in
/*) ;;
*/*) lib=$layer_dir/$lib ;;
*) for cand in "$layer_dir/$lib" "$layer_dir/../../../lib/$lib" "/usr/lib/x86_64-linux-gnu/$lib"; do
       [ -f "$cand" ] && { lib=$cand; break; }; done ;;
esac
[ -f "$lib" ] || { echo "present_fences: the layer's library '$lib' not found beside $json" >&2; exit 2; }
sed 's|"library_path" *: *"[^"]*"|"library_path": "'"$lib"'"|' "$json" >"$out/layer/VkLayer_khronos_validation.json"
layer_version=$(sed -n 's/.*"api_version" *: *"\([^"]*\)".*/\1/p' "$json")

# The lines to count, by their text.
src=$root/src/app/window/swapchain.c
line_of() { # PATTERN WHAT
    local n
    n=$(grep -n -F -- "$1" "$src" | cut -d: -f1)
    if [ "$(wc -w <<<"$n")" != 1 ]; then
        echo "present_fences: '$1' ($2) is not one line of src/app/window/swapchain.c: update this tool" >&2
        exit 1
    fi
    echo "$n"
}
armed=$(line_of 'sc->present_pending[image] = true;' fence_armed) || exit 1
reused=$(line_of 'VK_CHECK(vkResetFences(ctx->device, 1, &sc->present_done[image]));' fence_reused) || exit 1
retire=$(line_of 'VK_CHECK(vkWaitForFences(ctx->device, 1, &sc->present_done[i], VK_TRUE, UINT64_MAX));' fence_retire) || exit 1
cat >"$out/gdb.cmd" <<EOF
set pagination off
set confirm off
set breakpoint pending on
break swapchain.c:$armed
commands
silent
continue
end
break swapchain.c:$reused
commands
silent
continue
end
break swapchain.c:$retire
commands
silent
continue
end
run
info breakpoints
EOF

unset VKSKY_DROP_BARRIER VKSKY_WEAKEN_BARRIER VKSKY_FRAMES VKSKY_VALIDATION VKSKY_TEST_REPORT
export VK_ICD_FILENAMES=$icd VK_DRIVER_FILES=$icd VK_LAYER_PATH=$out/layer VKSKY_LUT_CACHE=0 VKSKY_TEST_RESIZE=1
export VK_KHRONOS_VALIDATION_SYNCVAL_SHADER_ACCESSES_HEURISTIC=1
# The loader's view: the mock is the only driver and the layer is the one given.
VK_LOADER_DEBUG=driver,layer "${run[@]}" "$vksky" --validate --frames 1 --width 64 --height 64 >"$out/loader.log" 2>&1
"${run[@]}" gdb -batch -x "$out/gdb.cmd" --args "$vksky" --validate --frames "$frames" --width 320 --height 180 \
    >"$out/gdb.log" 2>"$out/window.err"
# vksky's own stdout is inside gdb's: its lines are those gdb did not write.
grep -v -E '^(Breakpoint|Num |[0-9]+ +breakpoint|[0-9]+\.[0-9]+ |\s+breakpoint already hit|\s+silent|\s+continue|\[|Using host|Downloading|warning:)' \
    "$out/gdb.log" >"$out/window.out"

# gdb's "info breakpoints": "N breakpoint keep y ADDR in FN at FILE:LINE" (or <MULTIPLE> with "N.M ... FILE:LINE" rows,
# an inlined function), then "breakpoint already hit K times" when it was hit.
hits() {
    awk -v want="swapchain.c:$1" '$2 == "breakpoint" && $1 ~ /^[0-9]+$/ { num = $1 }
        /breakpoint already hit/ { hit[num] = $4 }
        $0 ~ (want "([^0-9]|$)") { split($1, p, "."); which = (p[1] ~ /^[0-9]+$/) ? p[1] : num }
        END { print (which != "" && hit[which] != "") ? hit[which] : 0 }' "$out/gdb.log"
}
n_armed=$(hits "$armed"); n_reused=$(hits "$reused"); n_retire=$(hits "$retire")
n_armed=${n_armed:-0} n_reused=${n_reused:-0} n_retire=${n_retire:-0}
# gdb sets one location per code address of a line: an inlined or split line has several ("N.M" rows), and one pass
# may hit more than one of them (with gcc 12 -O2 the wait's call and its return: each wait counts twice).
locations() { awk -v want="swapchain.c:$1" '$1 ~ /^[0-9]+(\.[0-9]+)?$/ && $0 ~ (want "([^0-9]|$)") { n++ } END { print n + 0 }' "$out/gdb.log"; }
loc_retire=$(locations "$retire")
presented=$(awk '$1 == "frames" { print $2 }' "$out/window.out")
recreated=$(grep -c '^swapchain ' "$out/window.out")
messages=$(awk '$1 == "validation_messages" { print $2 }' "$out/window.out")
device=$(grep -m1 -o 'Vulkan Mock Device' "$out/window.err" "$out/window.out" "$out/loader.log" 2>/dev/null | head -n 1)
loaded_icd=$(grep -c -F "$(basename "$icd")" "$out/loader.log")
{
    echo "layer $layer_version ($lib); ICD $icd"
    echo "loader: mock ICD manifest named $loaded_icd times in VK_LOADER_DEBUG=driver,layer"
    echo "presented $presented; swapchains created $recreated (the first + recreations); validation messages $messages"
    echo "breakpoint hits: fence_armed $n_armed (swapchain.c:$armed); fence_reused $n_reused (swapchain.c:$reused); fence_retire $n_retire (swapchain.c:$retire, $loc_retire code locations)"
} >"$out/summary.txt"
fails=0
check() { if eval "$1"; then echo "ok: $2"; else echo "FAIL: $2"; fails=$((fails + 1)); fi; }
{
    check '[ -n "$presented" ] && [ "$presented" -ge 100 ]' "the window presented $presented frames (>= 100)"
    check '[ "$recreated" -ge 4 ]' "the swapchain was created $recreated times (the first and >= 3 recreations)"
    check '[ "$n_armed" -ge "${presented:-1}" ]' "every present carried a fence: $n_armed fences for $presented presents (ctx->present_fences)"
    check '[ "$n_reused" -gt 0 ]' "a present fence waited for and reset before its image's next present: $n_reused times"
    check '[ "$n_retire" -gt 0 ]' "render-finished semaphores retired through present fences at recreation and shutdown: $n_retire breakpoint hits"
    check '[ "${messages:-x}" = 0 ]' "no validation message ($messages)"
} | tee -a "$out/summary.txt"
cat "$out/summary.txt" | head -n 4
echo "present_fences: results in $out"
[ "$(grep -c '^FAIL' "$out/summary.txt")" = 0 ] || exit 1
exit 0
