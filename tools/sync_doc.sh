#!/usr/bin/env bash
# The generated parts of docs/synchronization.md and the frame diagram, from what `vksky --trace-barriers` prints.
#
#   tools/sync_doc.sh [--vksky PATH]               regenerate: the tables between the <!-- BEGIN GENERATED: x -->
#                                                   and <!-- END GENERATED: x --> markers of the guide,
#                                                   docs/frame_graph.dot, and docs/frame_graph.png (graphviz `dot`)
#   tools/sync_doc.sh --check [--vksky PATH]       regenerate into a temporary directory and fail (exit 1) if the
#                                                   guide or the .dot differ, or the PNG was rendered from another
#                                                   .dot (its checksum is recorded in the guide): text only
#   tools/sync_doc.sh --check-list [--vksky PATH]  fail if a traced barrier has no line in tests/barrier_drops.txt
#                                                   that drop-tests it, or a line names a barrier no frame records
#
# The frames traced are the configurations of tests/barrier_drops.txt ("config" lines); window ones run under
# Xvfb (tests/xvfb_run.sh) when there is no DISPLAY. Exit 77 (skipped) when a window frame cannot be traced at all.
# bash, awk, sed, diff, cksum only (no Python on CI); graphviz only to render the PNG.
set -euo pipefail
# No LUT cache (sky/lut_cache.h): a warm cache would upload the LUTs instead of running their passes, and the
# traced frame would depend on earlier runs. Its own frames are config lut_cache's probe, which turns it on.
export VKSKY_LUT_CACHE=0
root=$(cd "$(dirname "$0")/.." && pwd)
vksky=$root/build/vksky
mode=write
while [ $# -gt 0 ]; do
    case $1 in
    --check) mode=check ;;
    --check-list) mode=list ;;
    --vksky) vksky=${2:?--vksky needs a path}; shift ;;
    *) echo "usage: tools/sync_doc.sh [--check|--check-list] [--vksky PATH]" >&2; exit 2 ;;
    esac
    shift
done
list=$root/tests/barrier_drops.txt
doc=$root/docs/synchronization.md
dotfile=$root/docs/frame_graph.dot
pngfile=$root/docs/frame_graph.png
[ -x "$vksky" ] || { echo "sync_doc: no vksky at $vksky (build first, or give --vksky PATH)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset VKSKY_DROP_BARRIER VKSKY_FRAMES
# Every traced frame runs validated (issue 31): a frame the guide documents must be clean, and a message exits 1.
export VKSKY_VALIDATION=1

# --- 1. Trace every configuration: $tmp/trace.<id> holds its "pass" and "barrier" lines. -------------------
configs=$(awk '$1 == "config" { print $2 }' "$list")
for id in $configs; do
    read -r kind args < <(awk -v id="$id" '$1 == "config" && $2 == id { $1 = $2 = ""; sub(/^ +/, ""); print }' "$list")
    args=${args//OUT/$tmp/out}
    run=("$vksky")
    if [ "$kind" = probe ]; then read -r probe args <<<"$args"; run=("$(dirname "$vksky")/$probe"); fi
    if [ "$kind" = window ] && [ -z "${DISPLAY:-}" ]; then
        if ! command -v Xvfb >/dev/null; then
            echo "sync_doc: SKIP: no DISPLAY and no Xvfb to trace the window frame ($id)" >&2
            exit 77
        fi
        run=("$root/tests/xvfb_run.sh" 640x480x24 "$vksky")
    fi
    # shellcheck disable=SC2086  # ARGS are words
    if ! "${run[@]}" $args --trace-barriers >"$tmp/out.$id" 2>"$tmp/err.$id"; then
        echo "sync_doc: vksky $args --trace-barriers failed:" >&2
        head -n 5 "$tmp/err.$id" >&2
        exit 1
    fi
    grep -E '^(pass|barrier|batch) |^commands$' "$tmp/out.$id" >"$tmp/trace.$id" || true
    [ -s "$tmp/trace.$id" ] || { echo "sync_doc: config $id: the trace is empty" >&2; exit 1; }
done

# Shared awk: parse a trace line into b_name, b_point, b_res, b_mips, b_old, b_new, b_ss, b_sa, b_ds, b_da,
# b_hazard; markdown and dot helpers. The point contains spaces, the other fields do not.
read -r -d '' AWK_LIB <<'EOF' || true
function parse(line,   p, r, rest, n, i, kv, k, v, parts) {
    b_name = ""; split(line, parts, " "); if (parts[1] != "barrier") return 0
    b_name = parts[2]
    p = index(line, " point="); r = index(line, " resource=")
    b_point = substr(line, p + 7, r - p - 7)
    rest = substr(line, r + 1); sub(/ DROPPED$/, "", rest)
    n = split(rest, kv, " ")
    for (i = 1; i <= n; ++i) {
        k = substr(kv[i], 1, index(kv[i], "=") - 1); v = substr(kv[i], index(kv[i], "=") + 1)
        if (k == "resource") b_res = v
        else if (k == "mips") b_mips = v
        else if (k == "layout") { b_old = v; sub(/->.*/, "", b_old); b_new = v; sub(/.*->/, "", b_new) }
        else if (k == "src") { b_ss = v; sub(/\/.*/, "", b_ss); b_sa = v; sub(/.*\//, "", b_sa) }
        else if (k == "dst") { b_ds = v; sub(/\/.*/, "", b_ds); b_da = v; sub(/.*\//, "", b_da) }
        else if (k == "hazard") b_hazard = v
    }
    return 1
}
# A mask in a markdown table cell: code, the bits joined by an escaped pipe.
function md_mask(m) { gsub(/\|/, " \\| ", m); return "`" m "`" }
function md_hazard(h) { gsub(/\+/, " + ", h); return h }
function short_layout(l) { sub(/_OPTIMAL$/, "", l); sub(/_KHR$/, "", l); return l }
# The drop list: expected[name SUBSEP config], note[...], untraced[...]; entry_configs[name] = "c1 c2".
function load_list(file,   line, f, n, i, key, rest) {
    while ((getline line < file) > 0) {
        if (line ~ /^#/ || line ~ /^[ \t]*$/) continue
        n = split(line, f, " ")
        if (f[1] == "config") { cfg_args[f[2]] = line; sub(/^config +[^ ]+ +[^ ]+ */, "", cfg_args[f[2]]); continue }
        key = f[1] SUBSEP f[2]
        expected[key] = f[3]; untraced[key] = (f[4] == "untraced")
        rest = line; for (i = 1; i <= (untraced[key] ? 4 : 3); ++i) sub(/^[^ ]+ +/, "", rest)
        note[key] = (n > (untraced[key] ? 4 : 3)) ? rest : ""
        entry_configs[f[1]] = entry_configs[f[1]] " " f[2]
        entry_order[++entries] = key
    }
    close(file)
}
# The mutation matrix: mres[name SUBSEP config SUBSEP field] = result (tests/barrier_mutations.txt).
function load_mutations(file,   line, f, name, field) {
    while ((getline line < file) > 0) {
        if (line ~ /^#/ || line ~ /^[ \t]*$/) continue
        split(line, f, " "); name = f[1]; sub(/:.*/, "", name); field = f[1]; sub(/^[^:]*:/, "", field)
        if (field ~ /=/) continue
        mres[name SUBSEP f[2] SUBSEP field] = f[3]
    }
    close(file)
}
# What the proof of one barrier is (docs §2): "own access" when weakening its source side (the stage or the access
# of what it protects) is reported as a hazard; "layout only" when only its layout (its transition, or the layout
# checks) shows; "not visible" when nothing does. The fields whose weakening is silent are listed: they are the
# ones the guide justifies by argument. `key` = name SUBSEP config of its drop test.
function proof(name, key,   k, cfg, i, fields, r, silent, own) {
    if (!(key in expected)) return "**not tested**"
    split(key, k, SUBSEP); cfg = k[2]
    split("srcstage srcaccess dststage dstaccess", fields, " ")
    silent = ""; own = 0
    for (i = 1; i <= 4; ++i) {
        r = mres[name SUBSEP cfg SUBSEP fields[i]]
        if (r ~ /RAW|WAR|WAW/ && i <= 2) own = 1
        if (r == "none") silent = silent (silent == "" ? "" : ", ") fields[i]
    }
    if (own) return "own access" (silent != "" ? "; silent: " silent : "")
    if (expected[key] != "none") return "layout only" (silent != "" ? "; silent: " silent : "")
    return "not visible"
}
EOF

# --- 2. The list check: every traced barrier line is drop-tested by some entry, every entry is recorded. -----
check_list() {
    local traces=()
    for id in $configs; do traces+=("$tmp/trace.$id"); done
    cat "$root"/src/*/*.c >"$tmp/all_src.c"
    awk -v list="$list" -v frame_c="$tmp/all_src.c" "$AWK_LIB"'
        BEGIN { load_list(list) }
        FNR == 1 { cfg = FILENAME; sub(/.*\/trace\./, "", cfg) }
        /^barrier / { parse($0); line = $0; sub(/ DROPPED$/, "", line)
                      has[cfg SUBSEP line] = 1; named[cfg SUBSEP b_name] = 1
                      if (!(line in first_cfg)) { first_cfg[line] = cfg; lines[++nl] = line; lname[line] = b_name } }
        END {
            bad = 0
            for (i = 1; i <= nl; ++i) {
                line = lines[i]; n = split(entry_configs[lname[line]], cs, " "); ok = 0
                for (j = 1; j <= n; ++j) if ((cs[j] SUBSEP line) in has) ok = 1
                if (!ok) { bad++
                    printf "barrier_list: untested: \"%s\" (config %s) has no line in tests/barrier_drops.txt whose config records it exactly so:\n  %s\n  add \"%s %s <EXPECTED>\" (run tests/barrier_drop_test.sh to see what a drop reports)\n", lname[line], first_cfg[line], line, lname[line], first_cfg[line] }
            }
            for (e = 1; e <= entries; ++e) {
                split(entry_order[e], k, SUBSEP)
                if (!(k[2] in cfg_args)) { bad++; printf "barrier_list: %s: no \"config %s\" line\n", k[1], k[2]; continue }
                if (untraced[entry_order[e]]) {
                    # Not in any trace: the name must at least still be in the frame spine.
                    found = 0; while ((getline src < frame_c) > 0) if (index(src, "\"" k[1] "\"")) found = 1; close(frame_c)
                    if (!found) { bad++; printf "barrier_list: %s (untraced) is not named in any file of src/\n", k[1] }
                } else if (!((k[2] SUBSEP k[1]) in named)) {
                    bad++; printf "barrier_list: %s: config %s records no barrier of that name (renamed or gone?)\n", k[1], k[2]
                }
            }
            if (bad) { printf "barrier_list: %d problem(s); the list is tests/barrier_drops.txt\n", bad; exit 1 }
            printf "barrier_list: ok: %d distinct barriers traced in %d configs, %d drop tests\n", nl, ncfg, entries
        }' ncfg="$(wc -w <<<"$configs")" "${traces[@]}"
}

# One vkCmdPipelineBarrier2 per point: between two passes (or a pass and the start or end of a command buffer,
# "commands") at most one `batch` line; and every drop-tested barrier x field has a result in the mutation matrix.
check_batches() {
    local bad=0
    for id in $configs; do
        awk -v id="$id" '/^pass / || /^commands$/ { n = 0; next }
            /^batch / { if (++n == 2) { printf "barrier_list: config %s: two vkCmdPipelineBarrier2 calls with no pass between them (%s); merge them into one batch\n", id, $0; bad = 1 } }
            END { exit bad }' "$tmp/trace.$id" || bad=1
    done
    local mut=$root/tests/barrier_mutations.txt ci=$root/tests/barrier_mutations_ci.txt
    awk -v mut="$mut" -v ci="$ci" '
        BEGIN { while ((getline l < mut) > 0) if (l !~ /^#/) { split(l, f, " "); have[f[1] " " f[2]] = 1 }
                split("srcstage srcaccess dststage dstaccess", fields, " ") }
        FILENAME == ci && $1 !~ /^#/ && NF >= 2 { if (!(($1 " " $2) in have)) { printf "barrier_list: %s %s (tests/barrier_mutations_ci.txt) has no result in tests/barrier_mutations.txt: run tools/mutation_matrix.sh\n", $1, $2; bad = 1 } next }
        FILENAME != ci && $1 != "config" && $1 !~ /^#/ && NF >= 3 && $4 != "untraced" {
            for (i = 1; i <= 4; ++i) if (!(($1 ":" fields[i] " " $2) in have)) { missing++; if (missing <= 5) printf "barrier_list: %s:%s %s has no result in tests/barrier_mutations.txt: run tools/mutation_matrix.sh\n", $1, fields[i], $2; bad = 1 } }
        END { if (missing > 5) printf "barrier_list: ... %d mutations in all without a result\n", missing; exit bad }' "$ci" "$list" || bad=1
    # The lesson frame's count, as §4 of the guide states it ("**N barriers in M calls**").
    local nb nc
    nb=$(grep -c '^barrier ' "$tmp/trace.render") nc=$(grep -c '^batch ' "$tmp/trace.render")
    if ! grep -q "\*\*$nb barriers in $nc calls\*\*" "$doc"; then
        echo "barrier_list: the lesson frame records $nb barriers in $nc vkCmdPipelineBarrier2 calls; docs/synchronization.md §4 says otherwise"
        bad=1
    fi
    [ $bad -eq 0 ] && echo "barrier_list: ok: one barrier call per point in every config ($nb barriers in $nc calls in the lesson frame); the mutation matrix covers every barrier"
    return $bad
}

if [ "$mode" = list ]; then
    rc=0
    check_list || rc=1
    check_batches || rc=1
    exit $rc
fi

# --- 3. The tables. ------------------------------------------------------------------------------------------
# A barrier table: the trace of one config; lines also found in the traces given by -v skip="a b" are left out.
# Columns: where it sits (the pass before and after it), the barrier, what it covers, the two scopes, the hazard
# it prevents, and what validation reports without it (tests/barrier_drops.txt).
barrier_table() {   # config [skip configs] [label column: config name]
    local id=$1 skip=${2:-} label=${3:-}
    local skipfiles=()
    for s in $skip; do skipfiles+=("$tmp/trace.$s"); done
    awk -v list="$list" -v mutations="$root/tests/barrier_mutations.txt" -v id="$id" -v label="$label" "$AWK_LIB"'
        BEGIN { load_list(list); load_mutations(mutations) }
        FNR == 1 { f++ }
        # First the traces to skip (f < last), then the config itself (two passes over it: passes after barriers).
        f < nfiles && /^barrier / { l = $0; sub(/ DROPPED$/, "", l); skipped[l] = 1; next }
        f < nfiles { next }
        /^pass / { pass = $2; if (pending) for (i = first_pending; i <= n; ++i) after[i] = pass; pending = 0; next }
        /^batch / { ++calls; for (i = assigned + 1; i <= n; ++i) call[i] = calls; assigned = n; next }
        /^barrier / {
            parse($0); l = $0; sub(/ DROPPED$/, "", l)
            ++n; before[n] = pass; row_line[n] = l; name[n] = b_name; point[n] = b_point; res[n] = b_res; mips[n] = b_mips
            old[n] = b_old; new[n] = b_new; ss[n] = b_ss; sa[n] = b_sa; ds[n] = b_ds; da[n] = b_da; hz[n] = b_hazard
            if (!pending) { first_pending = n; pending = 1 }
        }
        END {
            if (n == 0) { print "*(none)*"; exit }
            printf "| # | call |%s point: between passes | barrier | resource, mips | layout | src stage / access | dst stage / access | prevents | left out, validation reports | proof (appendix B) |\n", label != "" ? " frame |" : ""
            printf "|---|---|%s---|---|---|---|---|---|---|---|---|\n", label != "" ? "---|" : ""
            rows = 0
            for (i = 1; i <= n; ++i) {
                if (row_line[i] in skipped) continue
                b = before[i] == "" ? "*frame start*" : "`" before[i] "`"
                a = (i in after) ? "`" after[i] "`" : (da[i] ~ /HOST/ ? "*host, after the fence*" : (new[i] ~ /PRESENT/ ? "*present*" : "*frame end*"))
                lay = mips[i] == "-" ? "*buffer*" : (mips[i] == "*" ? "*global*" : "`" old[i] "` → `" new[i] "`")
                rm = mips[i] == "-" || mips[i] == "*" ? "`" res[i] "`" : "`" res[i] "` " mips[i]
                key = name[i] SUBSEP id
                if (!(key in expected)) {   # drop-tested in another config that records it identically
                    c = entry_configs[name[i]]; split(c, cs, " "); key = name[i] SUBSEP cs[1]
                }
                rep = (key in expected) ? md_hazard(expected[key]) : "**not tested**"
                if (note[key] != "" && note[key] != "idem") rep = rep " — " note[key]
                else if (note[key] == "idem") rep = rep " — idem"
                printf "| %d | %s |%s *%s*: %s → %s | `%s` | %s | %s | %s / %s | %s / %s | %s | %s | %s |\n", ++rows,
                       (i in call) ? call[i] : "–", label != "" ? " " label " |" : "", point[i], b, a, name[i], rm, lay,
                       md_mask(ss[i]), md_mask(sa[i]), md_mask(ds[i]), md_mask(da[i]), md_hazard(hz[i]), rep,
                       proof(name[i], key)
            }
            if (rows == 0) print "*(none)*"
        }' nfiles=$((${#skipfiles[@]} + 1)) "${skipfiles[@]}" "$tmp/trace.$id"
}

render_configs=$(awk '$1 == "config" && ($3 == "render" || $3 == "probe") && $2 != "render" { print $2 }' "$list")
window_configs=$(awk '$1 == "config" && $3 == "window" { print $2 }' "$list")
{
    echo "<!-- BEGIN GENERATED: frame table -->"
    echo "<!-- tools/sync_doc.sh, from: vksky $(awk '$1 == "config" && $2 == "render" { $1 = $2 = $3 = ""; sub(/^ +/, ""); print }' "$list") --trace-barriers -->"
    barrier_table render
    echo "<!-- END GENERATED: frame table -->"
} >"$tmp/gen.frame"
{
    echo "<!-- BEGIN GENERATED: present table -->"
    id=$(head -n 1 <<<"$window_configs")
    if [ -n "$id" ]; then
        echo "<!-- vksky $(awk -v id="$id" '$1 == "config" && $2 == id { $1 = $2 = $3 = ""; sub(/^ +/, ""); print }' "$list") --trace-barriers: the barriers that differ from the headless frame -->"
        barrier_table "$id" render
    fi
    echo "<!-- END GENERATED: present table -->"
} >"$tmp/gen.present"
{
    echo "<!-- BEGIN GENERATED: variant table -->"
    echo "<!-- the barriers of the other configurations of tests/barrier_drops.txt that the frame and window tables do not show -->"
    first_window=$(head -n 1 <<<"$window_configs")
    seen="render $first_window"
    for id in $render_configs $(tail -n +2 <<<"$window_configs"); do
        flags=$(awk -v id="$id" '$1 == "config" && $2 == id { w = $3 == "window" ? "window: " : ""; $1 = $2 = $3 = ""; sub(/^ +/, ""); sub(/^--render OUT[^ ]* /, ""); sub(/--width [0-9]+ --height [0-9]+ ?/, ""); sub(/--frames 2 /, ""); print w $0 }' "$list")
        rows=$(barrier_table "$id" "$seen" "\`${flags:-default}\`" | tail -n +3)
        if [ -n "$rows" ] && [ "$rows" != "*(none)*" ]; then
            [ -s "$tmp/variant_rows" ] || barrier_table "$id" "$seen" "x" | head -n 2 >"$tmp/variant_head"
            echo "$rows" >>"$tmp/variant_rows"
        else
            echo "$flags" >>"$tmp/variant_same"
        fi
        seen="$seen $id"
    done
    if [ -s "$tmp/variant_rows" ]; then
        cat "$tmp/variant_head"
        awk -F'|' 'BEGIN { OFS = "|" } { $2 = " " ++n " "; print }' "$tmp/variant_rows"
    fi
    if [ -s "$tmp/variant_same" ]; then
        echo
        echo "Configurations that record no barrier beyond those above: $(sed 's/.*/`&`/' "$tmp/variant_same" | paste -sd, - | sed 's/,/, /g')."
    fi
    echo "<!-- END GENERATED: variant table -->"
} >"$tmp/gen.variant"

{
    echo "<!-- BEGIN GENERATED: mutation table -->"
    echo "<!-- tools/sync_doc.sh, from tests/barrier_mutations.txt (made by tools/mutation_matrix.sh) -->"
    awk '
        function cell(r) { if (r == "") return "?"; if (r == "same") return "·"; if (r == "none") return "**silent**"; gsub(/\+/, " + ", r); return r }
        /^#/ || NF < 3 { next }
        { name = $1; sub(/:.*/, "", name); field = $1; sub(/^[^:]*:/, "", field)
          if (field ~ /=/) { extra[++ne] = "| `" $1 "` | " $2 " | " cell($3) " |"; next }
          key = name " " $2; if (!(key in seen)) { seen[key] = 1; order[++n] = key }
          res[key, field] = $3; if ($3 == "none") silent++; else if ($3 != "same") caught++ }
        END {
            print "| barrier | config | srcstage → NONE | srcaccess → NONE | dststage → NONE | dstaccess → NONE |"
            print "|---|---|---|---|---|---|"
            for (i = 1; i <= n; ++i) { split(order[i], k, " ")
                printf "| `%s` | %s | %s | %s | %s | %s |\n", k[1], k[2], cell(res[order[i], "srcstage"]), cell(res[order[i], "srcaccess"]), cell(res[order[i], "dststage"]), cell(res[order[i], "dstaccess"]) }
            print ""
            printf "%d weakened fields reported, %d silent (· : the field is already NONE).\n", caught, silent
            if (ne) { print ""; print "| mutation (explicit mask) | config | reported |"; print "|---|---|---|"; for (i = 1; i <= ne; ++i) print extra[i] }
        }' "$root/tests/barrier_mutations.txt"
    echo "<!-- END GENERATED: mutation table -->"
} >"$tmp/gen.mutation"

# The resource graph (Mermaid, in the guide itself): an edge from the pass that wrote a resource to the pass after
# the barrier that hands it on (every barrier whose source side writes), labelled resource and barrier.
{
    echo "<!-- BEGIN GENERATED: resource graph -->"
    echo '```mermaid'
    echo "flowchart TD"
    awk "$AWK_LIB"'
        /^pass / { ++np; node[np] = "p" np; printf "  p%d[\"%s\"]\n", np, $2
                   for (i = 1; i <= npend; ++i) printf "  %s -->|\"%s\"| p%d\n", pend_from[i], pend_label[i], np
                   npend = 0; next }
        /^barrier / { parse($0); if (b_sa !~ /WRITE/ || np == 0) next
                      lab = b_res (b_mips ~ /^[0-9]+$/ && b_res == "bloom" ? " mip " b_mips : "") ": " b_name
                      if (b_da ~ /HOST/) { host = 1; printf "  p%d -->|\"%s\"| host\n", np, lab; next }
                      pend_from[++npend] = "p" np; pend_label[npend] = lab }
        END { if (host) print "  host([\"host, after the fence\"])" }' "$tmp/trace.render"
    echo '```'
    echo "<!-- END GENERATED: resource graph -->"
} >"$tmp/gen.resource"

# --- 4. The diagram: passes in order, each edge labelled with the barriers recorded between two passes. -----
# The window's semaphore stages, as window.c's submit() sets them (wait, then signal).
sem_wait="" sem_signal=""
read -r sem_wait sem_signal < <(awk '/^static void submit\(/ { f = 1 } f && /stageMask = / { s = $0; sub(/.*stageMask = VK_PIPELINE_STAGE_2_/, "", s); sub(/_BIT.*/, "", s); out = out " " s } f && /^}/ { f = 0 } END { print out }' "$root/src/app/window/window.c" 2>/dev/null || true) || true
window_id=$(head -n 1 <<<"$window_configs")
awk -v sem_wait="${sem_wait:-?}" -v sem_signal="${sem_signal:-?}" "$AWK_LIB"'
    function esc(s) { gsub(/"/, "\\\"", s); return s }
    function label_of(i) { return names[i] "  " hz[i] "\\l" (old[i] == "UNDEFINED" && new[i] == "UNDEFINED" ? "buffer (no layout)" : short_layout(old[i]) " → " short_layout(new[i])) "\\l" }
    FNR == 1 { f++ }
    f == 1 && /^barrier / { l = $0; sub(/ DROPPED$/, "", l); in_render[l] = 1 }
    f == 1 && /^pass / { np++; pname[np] = $2; edge[np] = lab; lab = ""; next }
    f == 1 && /^barrier / { parse($0); ++nb; names[nb] = b_name; hz[nb] = b_hazard; old[nb] = b_old; new[nb] = b_new
                            lab = lab label_of(nb)
                            # What the pass just recorded wrote: the resources whose next barrier has a write source.
                            if (np && b_sa ~ /WRITE/) writes[np] = writes[np] (writes[np] == "" ? "" : ", ") b_res (b_mips ~ /^[0-9]+$/ && b_res == "bloom" ? " mip " b_mips : "") }
    f == 2 && /^pass / { wpass = $2; next }
    f == 2 && /^barrier / { l = $0; sub(/ DROPPED$/, "", l); if (l in in_render) next
                            parse($0); ++nb; names[nb] = b_name; hz[nb] = b_hazard; old[nb] = b_old; new[nb] = b_new
                            if (b_new ~ /PRESENT/) wpost = wpost label_of(nb); else wpre = wpre label_of(nb) }
    END {
        print "// Generated by tools/sync_doc.sh from vksky --trace-barriers; render with: dot -Tpng -o frame_graph.png frame_graph.dot"
        print "digraph vksky_frame {"
        print "  graph [fontname=\"Helvetica\", fontsize=12, rankdir=TB, nodesep=0.3, ranksep=0.22, labelloc=t,"
        print "         label=\"One vksky frame: the passes (boxes) in recording order and every barrier between them (edge labels: name, hazard, layout)\\n\"];"
        print "  node [fontname=\"Helvetica\", fontsize=11, shape=box, style=\"rounded,filled\", fillcolor=\"#e6eef8\", color=\"#4a6fa5\", height=0.3];"
        print "  edge [fontname=\"Helvetica\", fontsize=9, color=\"#555555\", arrowsize=0.6];"
        print "  start [shape=plaintext, style=\"\", label=\"frame start\\n(the previous frame read and wrote the same images)\"];"
        prev = "start"
        for (i = 1; i <= np; ++i) {
            count[pname[i]]++
            printf "  p%d [label=<%s%s>];\n", i, pname[i], writes[i] == "" ? "" : "<BR/><FONT POINT-SIZE=\"9\">writes " writes[i] "</FONT>"
            printf "  %s -> p%d [label=\"%s\"];\n", prev, i, edge[i] == "" ? "(no barrier)\\l" : edge[i]
            prev = "p" i
            if (pname[i] == "tonemap") tonemap_prev = (i > 1 ? "p" (i - 1) : "start")
        }
        if (lab != "") {
            print "  host [shape=plaintext, style=\"\", label=\"host reads the readback buffers\\n(after the fence)\"];"
            printf "  %s -> host [label=\"%s\"];\n", prev, lab
        }
        if (wpre != "" || wpost != "") {
            print "  subgraph cluster_window {"
            print "    label=\"the window: same passes up to the tone map, which renders into the swapchain image\"; fontsize=10; style=dashed; color=\"#999999\";"
            printf "    acquire [shape=note, fillcolor=\"#fff4d6\", color=\"#b08a2e\", label=\"vkAcquireNextImageKHR signals acquire semaphore;\\nsubmit waits on it at %s\"];\n", sem_wait
            print "    wtonemap [label=\"tonemap → swapchain image\"];"
            printf "    present [shape=note, fillcolor=\"#fff4d6\", color=\"#b08a2e\", label=\"submit signals render-finished semaphore at %s;\\nvkQueuePresentKHR waits on it\"];\n", sem_signal
            printf "    acquire -> wtonemap [label=\"%s\"];\n", wpre
            printf "    wtonemap -> present [label=\"%s\"];\n", wpost
            print "  }"
            if (tonemap_prev != "") printf "  %s -> wtonemap [style=dashed, label=\"window frame\\l\"];\n", tonemap_prev
        }
        print "}"
    }' "$tmp/trace.render" ${window_id:+"$tmp/trace.$window_id"} >"$tmp/frame_graph.dot"
dot_sum=$(cksum <"$tmp/frame_graph.dot" | awk '{ print $1 "-" $2 }')
echo "<!-- GENERATED: frame_graph.png is rendered from the frame_graph.dot with cksum $dot_sum -->" >"$tmp/gen.png"
# Without graphviz the PNG cannot be rendered: keep the guide's record of the .dot it was rendered from, so
# --check keeps failing until someone renders it.
if [ "$mode" = write ] && ! command -v dot >/dev/null; then
    grep "^<!-- GENERATED: frame_graph.png " "$doc" >"$tmp/gen.png" || true
fi

# --- 5. Splice the generated blocks into the guide. ---------------------------------------------------------
splice() {   # in out
    awk -v gdir="$tmp" '
        function emit(file,   l) { while ((getline l < file) > 0) print l; close(file) }
        /^<!-- BEGIN GENERATED: frame table -->$/ { emit(gdir "/gen.frame"); skip = 1; next }
        /^<!-- BEGIN GENERATED: present table -->$/ { emit(gdir "/gen.present"); skip = 1; next }
        /^<!-- BEGIN GENERATED: variant table -->$/ { emit(gdir "/gen.variant"); skip = 1; next }
        /^<!-- BEGIN GENERATED: mutation table -->$/ { emit(gdir "/gen.mutation"); skip = 1; next }
        /^<!-- BEGIN GENERATED: resource graph -->$/ { emit(gdir "/gen.resource"); skip = 1; next }
        /^<!-- GENERATED: frame_graph.png / { emit(gdir "/gen.png"); next }
        skip && /^<!-- END GENERATED: / { skip = 0; next }
        !skip { print }' "$1" >"$2"
    for marker in "frame table" "present table" "variant table" "mutation table" "resource graph"; do
        grep -q "^<!-- BEGIN GENERATED: $marker -->$" "$1" || { echo "sync_doc: $1 lacks <!-- BEGIN GENERATED: $marker -->" >&2; return 1; }
    done
    grep -q "^<!-- GENERATED: frame_graph.png " "$1" || { echo "sync_doc: $1 lacks the <!-- GENERATED: frame_graph.png ... --> line" >&2; return 1; }
}
splice "$doc" "$tmp/synchronization.md"

if [ "$mode" = check ]; then
    stale=0
    if ! diff -u "$doc" "$tmp/synchronization.md" >"$tmp/doc.diff"; then
        echo "sync_doc: docs/synchronization.md is stale (the frame's barriers changed); run tools/sync_doc.sh:"
        head -n 40 "$tmp/doc.diff"
        stale=1
    fi
    if ! diff -u "$dotfile" "$tmp/frame_graph.dot" >"$tmp/dot.diff"; then
        echo "sync_doc: docs/frame_graph.dot is stale; run tools/sync_doc.sh:"
        head -n 20 "$tmp/dot.diff"
        stale=1
    fi
    [ -f "$pngfile" ] || { echo "sync_doc: docs/frame_graph.png is missing; run tools/sync_doc.sh (needs graphviz)"; stale=1; }
    [ $stale -eq 0 ] && echo "sync_doc: ok: docs/synchronization.md and docs/frame_graph.dot match the traced frames"
    exit $stale
fi

cp "$tmp/synchronization.md" "$doc"
cp "$tmp/frame_graph.dot" "$dotfile"
if command -v dot >/dev/null; then
    dot -Tpng -Gdpi=96 -o "$pngfile" "$dotfile"
    echo "sync_doc: wrote docs/synchronization.md, docs/frame_graph.dot, docs/frame_graph.png"
else
    # The guide now records the new .dot's checksum: --check fails until the PNG is rendered from it.
    echo "sync_doc: wrote docs/synchronization.md and docs/frame_graph.dot; install graphviz (apt-get install graphviz)" >&2
    echo "sync_doc: and run: dot -Tpng -Gdpi=96 -o docs/frame_graph.png docs/frame_graph.dot" >&2
    exit 1
fi
