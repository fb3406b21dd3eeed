#!/usr/bin/env bash
# The masks' proof: weaken one field of one barrier at a time and record what synchronization validation reports.
#
#   tools/mutation_matrix.sh [--vksky PATH] [--jobs N] [--out FILE]
#
# For every line "BARRIER CONFIG ..." of tests/barrier_drops.txt (the drop tests: every barrier of every traced
# frame) and each field srcstage, srcaccess, dststage, dstaccess, runs the frame of CONFIG with
# VKSKY_WEAKEN_BARRIER=BARRIER:FIELD (the field set to NONE; a stage set to NONE takes its accesses with it) under
# --validate, two frames in one command buffer, exactly as tests/barrier_drop_test.sh runs a drop; and every line
# of tests/barrier_mutations_ci.txt (the CI subset, including the named mistakes with explicit masks such as
# "bloom.mip3.to_blend:dstaccess=COLOR_ATTACHMENT_WRITE"). A field that is already NONE is not run: "same".
#
# Writes tests/barrier_mutations.txt ("MUTATION CONFIG RESULT"; RESULT as in barrier_drops.txt: RAW, WAR, WAW,
# layout joined by +, none, or same). tools/sync_doc.sh renders it into the guide's appendix B, and
# `tools/sync_doc.sh --check-list` (ctest barrier_list) fails when it no longer covers every drop-tested barrier x
# field. The ctests barrier_mutate:* run the CI subset against it. About 8 minutes on lavapipe with 2 jobs (268 runs).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
vksky=$root/build/vksky
jobs=2
out=$root/tests/barrier_mutations.txt
while [ $# -gt 0 ]; do
    case $1 in
    --vksky) vksky=${2:?--vksky needs a path}; shift ;;
    --jobs) jobs=${2:?--jobs needs a number}; shift ;;
    --out) out=${2:?--out needs a file}; shift ;; # another layer's matrix (tools/newer_layer.sh) goes elsewhere
    *) echo "usage: tools/mutation_matrix.sh [--vksky PATH] [--jobs N] [--out FILE]" >&2; exit 2 ;;
    esac
    shift
done
[ -x "$vksky" ] || { echo "mutation_matrix: no vksky at $vksky (build first, or give --vksky PATH)" >&2; exit 2; }
drops=$root/tests/barrier_drops.txt
ci=$root/tests/barrier_mutations_ci.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset VKSKY_DROP_BARRIER VKSKY_WEAKEN_BARRIER VKSKY_FRAMES VKSKY_VALIDATION
# The layer that answers: Debian's package, or the one VK_LAYER_PATH names (tools/newer_layer.sh builds one).
layer_version=$(dpkg-query -W -f='${Version}' vulkan-validationlayers 2>/dev/null || echo '?')
if [ -n "${VK_LAYER_PATH:-}" ] && [ -f "${VK_LAYER_PATH%%:*}/VkLayer_khronos_validation.json" ]; then
    layer_version="$(sed -n 's/.*"api_version" *: *"\([^"]*\)".*/\1/p' "${VK_LAYER_PATH%%:*}/VkLayer_khronos_validation.json") from ${VK_LAYER_PATH%%:*}"
fi

# Every mutation, in list order: drop entries x fields, then the CI subset's extra ones.
{
    awk '$1 != "config" && $1 !~ /^#/ && NF >= 3 && $4 != "untraced" {
             print $1 ":srcstage " $2; print $1 ":srcaccess " $2; print $1 ":dststage " $2; print $1 ":dstaccess " $2 }' "$drops"
    awk '$1 !~ /^#/ && NF >= 2 { print $1 " " $2 }' "$ci"
} | awk '!seen[$0]++' >"$tmp/all"

# The current value of each field, from one trace per config: a field already at the mutated value is "same".
for cfg in $(awk '{ print $2 }' "$tmp/all" | sort -u); do
    read -r kind args < <(awk -v id="$cfg" '$1 == "config" && $2 == id { $1 = $2 = ""; sub(/^ +/, ""); print; exit }' "$drops")
    args=${args//OUT/$tmp/out}
    run=("$vksky")
    if [ "$kind" = probe ]; then read -r probe args <<<"$args"; run=("$(dirname "$vksky")/$probe"); fi
    if [ "$kind" = window ] && [ -z "${DISPLAY:-}" ]; then run=("$root/tests/xvfb_run.sh" 640x480x24 "$vksky"); fi
    # shellcheck disable=SC2086
    "${run[@]}" $args --trace-barriers 2>/dev/null | grep '^barrier ' >"$tmp/trace.$cfg" || true
done
awk -v tmp="$tmp" '
    function field(cfg, name, which,   file, line, n, kv, i, k, v) {
        file = tmp "/trace." cfg
        while ((getline line < file) > 0) {
            split(line, kv, " "); if (kv[2] != name) continue
            n = split(line, kv, " ")
            for (i = 1; i <= n; ++i) {
                k = substr(kv[i], 1, index(kv[i], "=") - 1); v = substr(kv[i], index(kv[i], "=") + 1)
                if (k == "src" && which == "srcstage") { close(file); sub(/\/.*/, "", v); return v }
                if (k == "src" && which == "srcaccess") { close(file); sub(/.*\//, "", v); return v }
                if (k == "dst" && which == "dststage") { close(file); sub(/\/.*/, "", v); return v }
                if (k == "dst" && which == "dstaccess") { close(file); sub(/.*\//, "", v); return v }
            }
        }
        close(file); return "?"
    }
    { spec = $1; name = spec; sub(/:.*/, "", name); f = spec; sub(/^[^:]*:/, "", f); want = "NONE"
      if (index(f, "=")) { want = substr(f, index(f, "=") + 1); f = substr(f, 1, index(f, "=") - 1) }
      if (field($2, name, f) == want) print spec, $2, "same" > (tmp "/same"); else print spec, $2 > (tmp "/run") }' "$tmp/all"
touch "$tmp/same" "$tmp/run"
echo "mutation_matrix: $(wc -l <"$tmp/run") runs ($(wc -l <"$tmp/same") fields already minimal), $jobs at a time" >&2

# shellcheck disable=SC2016
xargs -P "$jobs" -L 1 sh -c 'printf "%s %s %s\n" "$1" "$2" "$(BARRIER_REPORT=1 "$0" "$3" "$4" "$1" "$2")"' \
    "$root/tests/barrier_drop_test.sh" <<<"$(awk -v v="$vksky" -v d="$drops" '{ print $1, $2, v, d }' "$tmp/run")" \
    >"$tmp/results"

{
    echo "# Generated by tools/mutation_matrix.sh (do not edit): what synchronization validation reports when one"
    echo "# field of one barrier is weakened (VKSKY_WEAKEN_BARRIER=MUTATION, two frames, --validate, lavapipe,"
    echo "# Khronos validation layer $layer_version)."
    echo "# MUTATION CONFIG RESULT   RESULT: RAW/WAR/WAW/layout joined by +, none (silent), same (field already so)"
    awk 'NR == FNR { r[$1 " " $2] = $0; next } ($1 " " $2) in r { print r[$1 " " $2] }' \
        <(cat "$tmp/results" "$tmp/same") "$tmp/all"
} >"$out"
if grep -q 'error:' "$out"; then
    echo "mutation_matrix: some mutations did not reach their barrier:" >&2
    grep 'error:' "$out" >&2
    exit 1
fi
echo "mutation_matrix: wrote $out" >&2
