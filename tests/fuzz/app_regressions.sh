#!/usr/bin/env bash
# ctest app_fuzz_regressions: the fuzzers' regression inputs (tests/fuzz/regressions/{scene,cli}) against the vksky
# binary, with any compiler (the libFuzzer harnesses replay them too, but only where clang is installed). The
# properties are the harnesses': exit 0 or 2; on 2 one "vksky: " line on stderr; on 0 the --dump-scene output loads
# back to the same dump. A cli input is one argument per line (--dump-scene is appended).
# Usage: app_regressions.sh VKSKY REGRESSIONS_DIR
set -u
VKSKY=${1:?usage: app_regressions.sh VKSKY REGRESSIONS_DIR}
DIR=${2:?}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0 n=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
check() {   # check WHAT ARGS...
    local what=$1; shift
    n=$((n + 1))
    "$VKSKY" "$@" --dump-scene >"$work/d1.json" 2>"$work/err"
    local rc=$?
    if [ $rc -eq 2 ]; then
        [ "$(wc -l <"$work/err")" -eq 1 ] && grep -q '^vksky: ' "$work/err" ||
            fail "$what: exit 2 without exactly one 'vksky: ' line: $(head -c 300 "$work/err")"
    elif [ $rc -eq 0 ]; then
        [ ! -s "$work/err" ] || fail "$what: exit 0 with stderr: $(head -c 300 "$work/err")"
        "$VKSKY" --scene "$work/d1.json" --dump-scene >"$work/d2.json" 2>"$work/err" ||
            fail "$what: the dump does not load: $(head -c 300 "$work/err")"
        cmp -s "$work/d1.json" "$work/d2.json" || fail "$what: the dump does not round-trip"
    else
        fail "$what: exit status $rc: $(head -c 300 "$work/err")"
    fi
}
for f in "$DIR"/scene/*; do
    [ -e "$f" ] && check "scene $(basename "$f")" --scene "$f"
done
for f in "$DIR"/cli/*; do
    [ -e "$f" ] || continue
    mapfile -t args <"$f"
    check "cli $(basename "$f")" "${args[@]}"
done
echo "app_fuzz_regressions: $n inputs"
[ $n -gt 0 ] || fail "no regression inputs in $DIR"
if [ $fails -ne 0 ]; then echo "app_fuzz_regressions: $fails failure(s)"; exit 1; fi
echo "app_fuzz_regressions: ok"
