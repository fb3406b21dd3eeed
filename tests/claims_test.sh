#!/usr/bin/env bash
# The claims index (issue 31 item 4): every figure the README quotes is listed in docs/claims.md with what backs it.
# A figure: a number followed by %, ms, fps, x (a factor, not an image size WxH), kB, MB, MiB, GB or GiB; compared with
# the space before the unit removed. Fails on a README figure the index lacks, and on a ctest the index names
# (`name` after "ctest") that tests/CMakeLists.txt does not define; and the README's H100 preset table must equal
# src/app/quality/quality_table.h's rows (a figure copied from a table must stay the table's). Text only (grep, sed, awk).
# Usage: claims_test.sh SOURCE_DIR
set -u
root=${1:?usage: claims_test.sh path/to/source}
readme=$root/README.md index=$root/docs/claims.md
[ -f "$readme" ] && [ -f "$index" ] || { echo "FAIL: no $readme or $index"; exit 1; }
figures() {   # the figures of a file, one a line, normalised
    sed -E 's/([0-9])×([0-9])/\1x\2/g' "$1" | grep -oE '[0-9]+(\.[0-9]+)? ?(%|ms|fps|×|MiB|GiB|MB|kB|GB)' |
        sed 's/ //' | sort -u
}
fails=0
figures "$readme" >"${TMPDIR:-/tmp}/claims.$$.readme"
figures "$index" >"${TMPDIR:-/tmp}/claims.$$.index"
trap 'rm -f "${TMPDIR:-/tmp}"/claims.$$.*' EXIT
missing=$(comm -23 "${TMPDIR:-/tmp}/claims.$$.readme" "${TMPDIR:-/tmp}/claims.$$.index")
if [ -n "$missing" ]; then
    echo "FAIL: the README quotes figures docs/claims.md does not list (add each to its row, with what backs it):"
    echo "$missing" | tr '\n' ' '; echo
    fails=$((fails + 1))
fi
# Every ctest the index names exists (a row cannot point at a test that is gone).
for t in $(grep -oE 'ctest `[a-z_0-9]+`(, `[a-z_0-9]+`)*' "$index" | grep -oE '`[a-z_0-9]+`' | tr -d '`' | sort -u); do
    cat "$root/tests/CMakeLists.txt" "$root"/tests/*/CMakeLists.txt 2>/dev/null | grep -qE "NAME $t( |\))|foreach\(t .*\b$t\b" ||
        { echo "FAIL: docs/claims.md names ctest '$t', which tests/CMakeLists.txt (or a folder's) does not define"; fails=$((fails + 1)); }
done
# The README's "Presets on the new model" table quotes src/app/quality/quality_table.h (the GPU table): each cell must be its
# row's mean error, as a percentage to two decimals (columns: noon, sunset +2, sun 0, twilight -2, -4, the limb).
awk -F'|' '
    FILENAME ~ /quality_table\.h$/ && /^ *\{"/ { gsub(/[{}" ]/, ""); split($0, f, ","); err[f[1] "," f[2]] = f[4]; next }
    /^\| preset \| noon \| sunset \+2° \| sun 0° \| twilight −2° \| twilight −4° \| 400 km limb \|/ { t = 1; next }
    t && /^\|---/ { next }
    t && /^\| (low|medium|high|ultra) \|/ {
        split("0 2 6 7 3 5", cls, " "); name = $2; gsub(/ /, "", name)
        for (i = 1; i <= 6; ++i) {
            cell = $(i + 2); gsub(/[ %]/, "", cell); key = name "," cls[i]
            if (!(key in err)) { printf "FAIL: README preset table: no row %s in quality_table.h\n", key; bad++; continue }
            want = sprintf("%.2f", 100 * err[key])
            if (cell != want) { printf "FAIL: README preset table %s class %s: %s %%, quality_table.h says %s %%\n", name, cls[i], cell, want; bad++ }
            cells++
        }
        next
    }
    t { t = 0 }
    END { if (cells != 24) { printf "FAIL: README preset table: %d cells checked, expected 24\n", cells; bad++ }; exit bad != 0 }' \
    "$root/src/app/quality/quality_table.h" "$readme" || fails=$((fails + 1))
n=$(wc -l <"${TMPDIR:-/tmp}/claims.$$.readme")
[ "$n" -gt 50 ] || { echo "FAIL: only $n figures found in the README: the pattern is broken"; fails=$((fails + 1)); }
[ $fails -eq 0 ] || exit 1
echo "claims_test: ok ($n distinct README figures indexed)"
