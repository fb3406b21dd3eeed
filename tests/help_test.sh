#!/usr/bin/env bash
# tests/help_test.sh VKSKY MAN_PAGE: --help is grouped (output, camera, sun, atmosphere, quality, diagnostics, then
# the compositing mode's own flags; every flag in one of them), no line is over 100 columns, every flag's
# description starts in the same column; and
# the man page lists every flag that --help lists (and no flag --help does not).
set -u
VKSKY=${1:?usage: help_test.sh VKSKY MAN_PAGE}
MAN=${2:?}
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
help=$("$VKSKY" --help) || fail "--help exited non-zero"
groups=$(echo "$help" | grep -E '^[a-z]+:$' | tr -d ':' | tr '\n' ' ')
[ "$groups" = "output camera sun atmosphere quality diagnostics compositing " ] || fail "groups are '$groups'"
long=$(echo "$help" | awk 'length($0) > 100')
[ -z "$long" ] || fail "lines over 100 columns: $long"
# The description column: where the text after "  --flag [METAVAR]" starts on each flag line (or on the next line
# when the flag and its metavar are too wide), and where each continuation line starts.
cols=$(echo "$help" | awk '
    /^  --/ { head = $0; sub(/^  --[^ ]+( [^ ]+)?/, "", head)
              if (head == "") { pending = 1; next }
              match(head, /^ +/); print length($0) - length(head) + RLENGTH + 1; next }
    pending || /^          +[^ ]/ { match($0, /^ +/); print RLENGTH + 1; pending = 0 }' | sort -u)
[ "$(echo "$cols" | wc -l)" -eq 1 ] || fail "descriptions start in columns: $(echo $cols)"
flags=$(echo "$help" | grep -oE '^  --[a-z0-9-]+' | tr -d ' ' | sort -u)
[ "$(echo "$flags" | wc -l)" -ge 60 ] || fail "--help lists only $(echo "$flags" | wc -l) flags"
man_flags=$(sed -n 's/^\.BI\{0,1\} \(\\-\\-[a-z0-9\\-]*\).*/\1/p' "$MAN" | sed 's/\\-/-/g' | sort -u)
missing=$(comm -23 <(echo "$flags") <(echo "$man_flags"))
extra=$(comm -13 <(echo "$flags") <(echo "$man_flags"))
[ -z "$missing" ] || fail "the man page lacks: $(echo $missing) (regenerate: tools/man_page.sh build/vksky > docs/vksky.1)"
[ -z "$extra" ] || fail "the man page lists flags --help does not: $(echo $extra)"
[ $fails -eq 0 ] && echo "help: all checks pass ($(echo "$flags" | wc -l) flags, descriptions at column $cols)"
exit $((fails > 0))
