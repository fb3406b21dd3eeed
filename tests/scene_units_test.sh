#!/usr/bin/env bash
# --scene OUT.exr restores the units the EXR was rendered in (issue 32 item 5's follow-up: its "vksky:units"):
#  - a --units relative render, read back with --scene alone, renders the same pixels (before, it came back
#    photometric: ~10^4 times brighter); a photometric one likewise;
#  - a --units flag after --scene still overrides: --scene REL.exr --units photometric is the photometric render;
#  - a vksky:units value vksky does not write: exit 2, one line naming the attribute, no file.
# Every render under --validate; 32x18 images (~5 s of CPU on lavapipe).
set -u
VKSKY=${1:?usage: scene_units_test.sh VKSKY COMPARE}
COMPARE=${2:?usage: scene_units_test.sh VKSKY COMPARE}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
view=(--width 32 --height 18 --no-bloom --sun-elevation 5 --pitch 10 --validate)
render() { "$VKSKY" "$@" >/dev/null 2>"$work/err" && [ ! -s "$work/err" ] || fail "vksky $*: $(cat "$work/err")"; }
# same A B: every pixel of B equals A's (spectral_compare: luminance and CIEDE2000 max exactly 0).
same() { "$COMPARE" "$1" "$2" >"$work/cmp" 2>&1 && grep -q "max 0.000 %;.*max 0.000 (" "$work/cmp"; }

render "${view[@]}" --units relative --render "$work/rel.exr"
render "${view[@]}" --render "$work/pho.exr"
same "$work/pho.exr" "$work/rel.exr" && fail "the relative and photometric renders are the same: nothing is tested"
render --scene "$work/rel.exr" --validate --render "$work/rel2.exr"
same "$work/rel.exr" "$work/rel2.exr" || fail "--scene REL.exr: not the relative render: $(cat "$work/cmp")"
render --scene "$work/pho.exr" --validate --render "$work/pho2.exr"
same "$work/pho.exr" "$work/pho2.exr" || fail "--scene PHO.exr: not the photometric render: $(cat "$work/cmp")"
render --scene "$work/rel.exr" --units photometric --validate --render "$work/over.exr"
same "$work/pho.exr" "$work/over.exr" || fail "--scene REL.exr --units photometric: not the photometric render: $(cat "$work/cmp")"

if command -v oiiotool >/dev/null; then
    oiiotool "$work/rel.exr" --attrib "vksky:units" "furlongs" -o "$work/bad.exr" || fail "oiiotool"
    mkdir "$work/out"
    "$VKSKY" --scene "$work/bad.exr" --validate --render "$work/out/x.exr" >/dev/null 2>"$work/err"
    rc=$?
    [ $rc -eq 2 ] || fail "unknown units: exit $rc, expected 2"
    [ "$(wc -l <"$work/err")" -eq 1 ] && grep -q "vksky:units" "$work/err" ||
        fail "unknown units: expected one line naming vksky:units: $(cat "$work/err")"
    [ -z "$(ls -A "$work/out")" ] || fail "unknown units: left a file"
fi
[ $fails -eq 0 ] && echo "scene_units: all checks passed"
exit $((fails > 0))
