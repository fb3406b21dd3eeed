#!/usr/bin/env bash
# Size edges (issue 15 item 1, the part tiny_sizes does not run): every size from 1 to 16384 in each dimension
# renders at every preset and render scale, headless under --validate (validation + synchronization validation: any
# message makes vksky exit non-zero), with bloom on and off. tiny_sizes runs the small-size matrix at low, medium and
# the default; this adds
#  - the other presets (high, ultra, lesson, cpu) at one-pixel, odd and thin sizes;
#  - the smallest render scale the flag accepts (0.1: a 15x15 image's sky is 2x2, a 9x1 one's 1x1) and an odd one
#    (0.33), with both post chains (fragment and compute) and the longest and shortest bloom chains asked for;
#  - the largest width and height (16384) as one-pixel-thin images, and 16385 refused (exit 2, one line, no file).
# Each render must exit 0 with nothing on stderr and write an EXR of exactly the asked size (exr_probe reads the
# last pixel and is refused the one past it) whose last pixel is a finite positive radiance (the camera looks up).
# Usage: size_edges_test.sh path/to/vksky path/to/exr_probe
set -u
VKSKY=${1:?usage: size_edges_test.sh path/to/vksky path/to/exr_probe}
PROBE=${2:?usage: size_edges_test.sh path/to/vksky path/to/exr_probe}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The LUT cache on in the test's own directory: the checks are about sizes, not LUTs (tests/lib/own_lut_cache.sh).
# shellcheck source=lib/own_lut_cache.sh
source "$(dirname "$0")/lib/own_lut_cache.sh"
own_lut_cache "$work"
fails=0 count=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }

# render W H WHAT FLAGS...: one render and its checks.
render() {
    local w=$1 h=$2 what=$3
    shift 3
    local out="$work/t.exr"
    rm -f "$out"
    "$VKSKY" --validate --render "$out" --width "$w" --height "$h" "$@" >"$work/stdout" 2>"$work/stderr"
    local rc=$?
    count=$((count + 1))
    if [ $rc -ne 0 ]; then fail "$what: exit $rc: $(head -c 600 "$work/stderr")"; return; fi
    [ -s "$work/stderr" ] && fail "$what: stderr not empty: $(head -c 600 "$work/stderr")"
    [ -f "$out" ] || { fail "$what: no EXR written"; return; }
    local last
    last=$("$PROBE" "$out" $((w - 1)) $((h - 1)) 2>"$work/probe.err") || {
        fail "$what: last pixel unreadable: $(cat "$work/probe.err")"; return; }
    "$PROBE" "$out" "$w" 0 >/dev/null 2>"$work/probe.err" && fail "$what: pixel ($w, 0) exists"
    grep -qF "is not in the ${w}x${h} image" "$work/probe.err" || fail "$what: EXR is not ${w}x${h}: $(cat "$work/probe.err")"
    awk -v p="$last" 'BEGIN { n = split(p, c, " "); ok = n == 3;
        for (i = 1; i <= n; ++i) if (!(c[i] + 0 > 0 && c[i] + 0 < 1e4 * 133177 / 20)) ok = 0; exit !ok }' ||   # cd/m2 (docs/units.md)
        fail "$what: last pixel not a finite positive radiance: '$last'"
}

# The presets tiny_sizes leaves out.
for preset in high ultra lesson cpu; do
    for size in "1 1" "7 3" "1 9"; do
        read -r w h <<<"$size"
        render "$w" "$h" "${w}x${h} --quality $preset" --quality "$preset"
    done
done
render 3 1 "3x1 --quality high --no-bloom" --quality high --no-bloom

# Render scales down to the smallest accepted, both post chains, the longest and the shortest bloom chains.
for scale in 0.1 0.33; do
    for size in "1 1" "9 1" "15 15"; do
        read -r w h <<<"$size"
        for post in fragment compute; do
            render "$w" "$h" "${w}x${h} --render-scale $scale --post-pass $post --bloom-mips 8" \
                --render-scale "$scale" --post-pass "$post" --bloom-mips 8
        done
    done
    render 15 15 "15x15 --render-scale $scale --bloom-mips 1 --no-bloom" --render-scale "$scale" --bloom-mips 1 --no-bloom
done

# The largest width and height, one pixel thin the other way (bloom on: the chain is one pixel across).
render 16384 1 "16384x1" --quality low
render 1 16384 "1x16384" --quality low --post-pass compute

# One past the limit: refused before any work (one line naming the accepted range, exit 2, no file).
for flag in --width --height; do
    rm -f "$work/t.exr"
    "$VKSKY" --render "$work/t.exr" --width 4 --height 4 "$flag" 16385 >/dev/null 2>"$work/stderr"
    rc=$?
    count=$((count + 1))
    [ $rc -eq 2 ] || fail "$flag 16385: exit $rc (expected 2)"
    [ "$(wc -l <"$work/stderr")" -eq 1 ] && grep -qF '[1, 16384]' "$work/stderr" ||
        fail "$flag 16385: expected one line naming [1, 16384]: $(cat "$work/stderr")"
    [ -e "$work/t.exr" ] && fail "$flag 16385: wrote a file"
done

if [ $fails -ne 0 ]; then echo "size_edges: $fails failures in $count runs" >&2; exit 1; fi
echo "size_edges: $count runs: every preset, render scales 0.1 and 0.33, 16384-pixel edges validation-clean and exact"
