#!/usr/bin/env bash
# What another Khronos validation layer (a newer one, built from source: not a Debian package, so CI keeps Debian
# 12's 1.3.239) reports on the frames of tests/barrier_drops.txt, against what 1.3.239 reports.
#
#   tools/newer_layer.sh LAYER_DIR [--vksky PATH] [--jobs N] [--out DIR] [--skip-matrix] [--shader-accesses]
#
# --shader-accesses turns on the layer setting syncval_shader_accesses_heuristic: from some 1.4 release on,
# synchronization validation ignores what shaders access through descriptors unless it is on (it is off by
# default), so without it every storage/sampled access of a dispatch or draw is invisible to the layer.
#
# LAYER_DIR holds VkLayer_khronos_validation.json and the library it names (an install's
# share/vulkan/explicit_layer.d, or a build's layers/ directory). Nothing is fetched: build the layer once (the
# recipe is in docs/synchronization.md §14, "What a newer layer sees"), then this runs offline.
#
# With VK_LAYER_PATH=LAYER_DIR (the loader then takes explicit layers from there only) it
#   1. checks that the loader inserts that layer, not Debian's (VK_LOADER_DEBUG=layer), and prints its version;
#   2. runs every configuration's clean frame (tests/barrier_drop_test.sh - CONFIG): a new message on an unmutated
#      frame is either a bug of vksky or a false positive of the layer; its messages go to clean.log;
#   3. runs every drop of tests/barrier_drops.txt (tests/barrier_drop_test.sh NAME CONFIG);
#   4. runs every mutation of tests/barrier_mutations.txt (1.3.239's matrix: every drop-tested barrier x field and
#      the explicit masks; fields already minimal, "same", are not run), the ones 1.3.239 found silent first,
#      unless --skip-matrix. (VK_LAYER_PATH=LAYER_DIR tools/mutation_matrix.sh --out FILE writes the same matrix
#      in that tool's format.)
# Results are appended as each run ends, so an interrupted run keeps what it measured. Written to DIR (default
# build/newer_layer):
#   clean.txt      CONFIG RESULT             RESULT: RAW/WAR/WAW/layout/other:<id>, joined by +, or none
#   clean.log      the messages of every clean frame that was not silent
#   drops.txt      BARRIER CONFIG OLD NEW    OLD: what 1.3.239 reports (tests/barrier_drops.txt's expected set)
#   mutations.txt  MUTATION CONFIG OLD NEW   OLD: tests/barrier_mutations.txt's result
#   compare.txt    every drop and mutation whose result differs: KIND NAME CONFIG OLD NEW CLASS
#                  CLASS: new-catch (none -> something), lost-catch (something -> none), changed
# and a summary on stdout. Exit 0 when it ran (differences are findings, not failures), 2 on bad arguments.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
usage="usage: tools/newer_layer.sh LAYER_DIR [--vksky PATH] [--jobs N] [--out DIR] [--skip-matrix] [--shader-accesses]"
layer_dir=
vksky=$root/build/vksky
jobs=2
out=$root/build/newer_layer
matrix=1
while [ $# -gt 0 ]; do
    case $1 in
    --vksky) vksky=${2:?--vksky needs a path}; shift ;;
    --jobs) jobs=${2:?--jobs needs a number}; shift ;;
    --out) out=${2:?--out needs a directory}; shift ;;
    --skip-matrix) matrix=0 ;;
    --shader-accesses) export VK_KHRONOS_VALIDATION_SYNCVAL_SHADER_ACCESSES_HEURISTIC=1 ;;
    -*) echo "newer_layer: unknown option '$1'; $usage" >&2; exit 2 ;;
    *) [ -z "$layer_dir" ] || { echo "newer_layer: one LAYER_DIR only; $usage" >&2; exit 2; }; layer_dir=$1 ;;
    esac
    shift
done
[ -n "$layer_dir" ] || { echo "newer_layer: no LAYER_DIR given; $usage" >&2; exit 2; }
json=$layer_dir/VkLayer_khronos_validation.json
[ -f "$json" ] || { echo "newer_layer: no VkLayer_khronos_validation.json in '$layer_dir' (give the directory that holds the layer's manifest)" >&2; exit 2; }
[ -x "$vksky" ] || { echo "newer_layer: no vksky at '$vksky' (build first, or give --vksky PATH)" >&2; exit 2; }
case $jobs in '' | *[!0-9]* | 0) echo "newer_layer: --jobs must be a positive integer, not '$jobs'" >&2; exit 2 ;; esac
layer_dir=$(cd "$layer_dir" && pwd)
mkdir -p "$out/layer" || exit 2
out=$(cd "$out" && pwd)
drops=$root/tests/barrier_drops.txt
unset VKSKY_DROP_BARRIER VKSKY_WEAKEN_BARRIER VKSKY_FRAMES VKSKY_VALIDATION
# An installed manifest names its library by bare name ("libVkLayer_khronos_validation.so"), which the dynamic
# linker would resolve to Debian's 1.3.239 library. So the manifest is copied with the library's absolute path:
# beside the manifest (a build's layers/ directory) or in the install's lib/ (share/vulkan/explicit_layer.d/../../../lib).
lib=$(sed -n 's/.*"library_path" *: *"\([^"]*\)".*/\1/p' "$json")
case $lib in
/*) ;;
*/*) lib=$layer_dir/$lib ;;
*) for cand in "$layer_dir/$lib" "$layer_dir/../../../lib/$lib"; do [ -f "$cand" ] && { lib=$cand; break; }; done ;;
esac
[ -f "$lib" ] || { echo "newer_layer: the layer's library '$lib' is neither beside $json nor in ../../../lib" >&2; exit 2; }
lib=$(cd "$(dirname "$lib")" && pwd)/$(basename "$lib")
sed 's|"library_path" *: *"[^"]*"|"library_path": "'"$lib"'"|' "$json" >"$out/layer/VkLayer_khronos_validation.json"
json=$out/layer/VkLayer_khronos_validation.json
export VK_LAYER_PATH=$out/layer
export VKSKY_LUT_CACHE=0

# 1. Which layer the loader really loads: the manifest and library of the layer it inserts (VK_LOADER_DEBUG=layer).
version=$(sed -n 's/.*"api_version" *: *"\([^"]*\)".*/\1/p' "$json")
VK_LOADER_DEBUG=layer "$vksky" --render "$out/probe.png" --width 16 --height 16 --quality lesson --units relative \
    --validate >"$out/loader.log" 2>&1
# The loader lists each active layer as "LAYER: <name>", then its "Manifest:" and "Library:" lines.
active() { awk -v k="$1" '$1 == "LAYER:" && NF == 2 { name = $2 } $1 == "LAYER:" && $2 == k && name == "VK_LAYER_KHRONOS_validation" { print $3 }' "$out/loader.log" | sort -u; }
manifest=$(active Manifest:)
library=$(active Library:)
echo "newer_layer: layer $version; the loader inserted $manifest ($library)"
if [ "$manifest" != "$json" ] || [ "$library" != "$lib" ]; then
    echo "newer_layer: the loader did not insert the layer of $layer_dir (see $out/loader.log)" >&2
    exit 1
fi

# The set a barrier_drop_test.sh line reports: "ok: LABEL: {SET}" or "FAIL: LABEL: validation reported {SET}, ...".
reported() { sed -n 's/^ok: .*: {\([^}]*\)}$/\1/p; s/^FAIL: .*validation reported {\([^}]*\)}.*/\1/p' | head -n 1; }

# 2. Clean frames.
: >"$out/clean.txt"
: >"$out/clean.log"
for cfg in $(awk '$1 == "config" { print $2 }' "$drops"); do
    log=$("$root/tests/barrier_drop_test.sh" "$vksky" "$drops" - "$cfg" 2>&1)
    rc=$?
    got=$(reported <<<"$log")
    [ $rc -eq 77 ] && got=skipped
    echo "$cfg ${got:-error}" >>"$out/clean.txt"
    [ "$got" = none ] || printf '== %s\n%s\n' "$cfg" "$log" >>"$out/clean.log"
done

# 3 and 4. One run per line "NAME CONFIG OLD" of a list: "NAME CONFIG OLD NEW" appended to a file as each ends.
# NEW is what the layer reports (barrier_drop_test.sh's "ok: ...: {SET}" or "... validation reported {SET} ...").
run_list() { # LIST_FOR_CONFIGS INPUT OUTPUT
    : >"$3"
    # shellcheck disable=SC2016
    xargs -P "$jobs" -L 1 sh -c 'r=$("$0" "$1" "$2" "$3" "$4" 2>&1 | sed -n "s/^ok: .*: {\([^}]*\)}\$/\1/p; s/^FAIL: .*validation reported {\([^}]*\)}.*/\1/p" | head -n 1)
        printf "%s %s %s %s\n" "$3" "$4" "$5" "${r:-error}" >>"$6"' "$root/tests/barrier_drop_test.sh" \
        <<<"$(awk -v v="$vksky" -v l="$1" -v o="$3" '{ print v, l, $1, $2, $3, o }' "$2")"
}
awk '$1 != "config" && $1 !~ /^#/ && NF >= 3 { print $1, $2, $3 }' "$drops" >"$out/drops.in"
run_list "$drops" "$out/drops.in" "$out/drops.txt"
# A mutation is checked against its expected set only when its list has one; any set is printed either way.
if [ $matrix -eq 1 ]; then
    m=$root/tests/barrier_mutations.txt
    { awk '$1 !~ /^#/ && $3 == "none"' "$m"; awk '$1 !~ /^#/ && $3 != "none" && $3 != "same"' "$m"; } >"$out/mutations.in"
    run_list "$m" "$out/mutations.in" "$out/mutations.txt"
fi
rm -f "$out/drops.in" "$out/mutations.in"

# Differences, each classed.
mutations=()
[ -f "$out/mutations.txt" ] && mutations=("$out/mutations.txt")
awk 'function cls(o, n) { return o == "none" ? "new-catch" : n == "none" ? "lost-catch" : "changed" }
     $3 != $4 { print (FILENAME ~ /drops\.txt$/ ? "drop" : "mutation"), $1, $2, $3, $4, cls($3, $4) }' \
    "$out/drops.txt" "${mutations[@]}" >"$out/compare.txt"

echo "newer_layer: layer $version; results in $out"
echo "  clean frames: $(awk '$2 == "none"' "$out/clean.txt" | wc -l) of $(wc -l <"$out/clean.txt") silent$(awk '$2 != "none" { printf " | %s: %s", $1, $2 }' "$out/clean.txt")"
echo "  drops: $(wc -l <"$out/drops.txt") run, $(grep -c '^drop ' "$out/compare.txt") differ from 1.3.239"
[ -f "$out/mutations.txt" ] && echo "  mutations: $(wc -l <"$out/mutations.txt") run, $(grep -c '^mutation ' "$out/compare.txt") differ from 1.3.239"
for k in new-catch lost-catch changed; do echo "  $k: $(awk -v k="$k" '$6 == k' "$out/compare.txt" | wc -l)"; done
exit 0
