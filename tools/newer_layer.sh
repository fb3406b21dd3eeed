#!/usr/bin/env bash
# What another Khronos validation layer (a newer one, built from source: not a Debian package, so CI keeps Debian
# 12's 1.3.239) reports on the frames of tests/barrier_drops.txt, against what 1.3.239 reports.
#
#   tools/newer_layer.sh LAYER_DIR [--vksky PATH] [--jobs N] [--out DIR] [--skip-matrix]
#
# LAYER_DIR holds VkLayer_khronos_validation.json and the library it names (an install's
# share/vulkan/explicit_layer.d, or a build's layers/ directory). Nothing is fetched: build the layer once (the
# recipe is in docs/synchronization.md §14, "What a newer layer sees"), then this runs offline.
#
# With VK_LAYER_PATH=LAYER_DIR (the loader then takes explicit layers from there only) it
#   1. checks that the loader loads that layer's library, not Debian's (VK_LOADER_DEBUG=layer), and prints its
#      version;
#   2. runs every configuration's clean frame (tests/barrier_drop_test.sh - CONFIG): a new message on an unmutated
#      frame is either a bug of vksky or a false positive of the layer, and is shown in full;
#   3. runs every drop of tests/barrier_drops.txt (tests/barrier_drop_test.sh NAME CONFIG) and records what the
#      layer reports;
#   4. runs the whole mutation matrix (tools/mutation_matrix.sh --out), unless --skip-matrix;
# and writes to DIR (default build/newer_layer):
#   clean.txt      CONFIG RESULT                       (RESULT: RAW/WAR/WAW/layout/other:<id> joined by +, or none)
#   clean.log      the first lines of every clean frame's messages
#   drops.txt      BARRIER CONFIG OLD NEW              (OLD: the expected set in tests/barrier_drops.txt, 1.3.239)
#   mutations.txt  the matrix, as tools/mutation_matrix.sh writes it
#   compare.txt    every drop and mutation whose result differs: KIND NAME CONFIG OLD NEW CLASS
#                  CLASS: new-catch (none -> something), lost-catch (something -> none), changed
# and a summary on stdout. Exit 0 when it ran (differences are findings, not failures), 2 on bad arguments.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
usage="usage: tools/newer_layer.sh LAYER_DIR [--vksky PATH] [--jobs N] [--out DIR] [--skip-matrix]"
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
mkdir -p "$out" || exit 2
out=$(cd "$out" && pwd)
drops=$root/tests/barrier_drops.txt
unset VKSKY_DROP_BARRIER VKSKY_WEAKEN_BARRIER VKSKY_FRAMES VKSKY_VALIDATION
export VK_LAYER_PATH=$layer_dir
export VKSKY_LUT_CACHE=0

# 1. Which layer the loader really loads: the manifest and library of the layer it inserts (VK_LOADER_DEBUG=layer).
version=$(sed -n 's/.*"api_version" *: *"\([^"]*\)".*/\1/p' "$json")
VK_LOADER_DEBUG=layer "$vksky" --render "$out/probe.png" --width 16 --height 16 --quality lesson --units relative \
    --validate >"$out/loader.log" 2>&1
manifest=$(awk '$1 == "LAYER:" && $2 == "Manifest:" { print $3 }' "$out/loader.log" | sort -u)
library=$(awk '$1 == "LAYER:" && $2 == "Library:" { print $3 }' "$out/loader.log" | sort -u)
echo "newer_layer: layer $version; the loader inserted $manifest ($library)"
[ "$manifest" = "$layer_dir/VkLayer_khronos_validation.json" ] || {
    echo "newer_layer: the loader did not insert the layer of $layer_dir (see $out/loader.log)" >&2
    exit 1
}

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

# 3. Drops: every line of the list, run against its 1.3.239 expectation; the reported set is what we keep.
awk '$1 != "config" && $1 !~ /^#/ && NF >= 3 { print $1, $2, $3 }' "$drops" >"$out/drops.in"
# shellcheck disable=SC2016
xargs -P "$jobs" -L 1 sh -c 'r=$("$0" "$3" "$4" "$1" "$2" 2>&1 | sed -n "s/^ok: .*: {\([^}]*\)}\$/\1/p; s/^FAIL: .*validation reported {\([^}]*\)}.*/\1/p" | head -n 1)
    printf "%s %s %s %s\n" "$1" "$2" "$5" "${r:-error}"' "$root/tests/barrier_drop_test.sh" \
    <<<"$(awk -v v="$vksky" -v d="$drops" '{ print $1, $2, v, d, $3 }' "$out/drops.in")" >"$out/drops.unsorted"
awk 'NR == FNR { r[$1 " " $2] = $0; next } ($1 " " $2) in r { print r[$1 " " $2] }' "$out/drops.unsorted" "$out/drops.in" \
    >"$out/drops.txt"
rm -f "$out/drops.in" "$out/drops.unsorted"

# 4. The mutation matrix, into DIR (tests/barrier_mutations.txt stays 1.3.239's).
if [ $matrix -eq 1 ]; then
    "$root/tools/mutation_matrix.sh" --vksky "$vksky" --jobs "$jobs" --out "$out/mutations.txt" || echo "newer_layer: the matrix reported errors (see above)" >&2
fi

# Differences, each classed.
classify='function cls(o, n) { return o == "none" ? "new-catch" : n == "none" ? "lost-catch" : "changed" }'
{
    awk "$classify"' $3 != $4 { print "drop", $1, $2, $3, $4, cls($3, $4) }' "$out/drops.txt"
    if [ -f "$out/mutations.txt" ]; then
        awk "$classify"' $1 ~ /^#/ { next } NR == FNR { old[$1 " " $2] = $3; next }
             ($1 " " $2) in old && old[$1 " " $2] != $3 { print "mutation", $1, $2, old[$1 " " $2], $3, cls(old[$1 " " $2], $3) }' \
            "$root/tests/barrier_mutations.txt" "$out/mutations.txt"
    fi
} >"$out/compare.txt"

echo "newer_layer: layer $version; results in $out"
echo "  clean frames: $(awk '$2 == "none"' "$out/clean.txt" | wc -l) of $(wc -l <"$out/clean.txt") silent$(awk '$2 != "none" { printf " | %s: %s", $1, $2 }' "$out/clean.txt")"
echo "  drops: $(wc -l <"$out/drops.txt") run, $(grep -c '^drop ' "$out/compare.txt") differ from 1.3.239"
[ -f "$out/mutations.txt" ] && echo "  mutations: $(grep -vc '^#' "$out/mutations.txt") results, $(grep -c '^mutation ' "$out/compare.txt") differ from 1.3.239"
for k in new-catch lost-catch changed; do echo "  $k: $(awk -v k="$k" '$6 == k' "$out/compare.txt" | wc -l)"; done
exit 0
