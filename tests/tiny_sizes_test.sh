#!/usr/bin/env bash
# Tiny images (issue 15, item 1): every size from 1x1 up renders, with bloom on and off, at every preset, headless
# under --validate (validation + synchronization validation: any message makes vksky exit non-zero). The bloom
# chain shrinks to what the image can hold (down to one level) and never hands a null or zero-sized view to a
# descriptor or an attachment.
#
# Each render must: exit 0, print nothing on stderr, write an EXR of exactly the asked size (exr_probe reads the
# last pixel and is refused the one past it), with finite positive pixels. For odd sizes the centre pixel looks
# along the view axis: it must match the CPU reference (double precision, no LUTs: `vksky --reference`, an
# independent computation) within TOL: the presets' measured mean error is <= 3.2 % at this kind of scene
# (quality_table.h, "low", afternoon class: 5 % mean, the sky-view LUT's worst case; the lesson's march: 2 %),
# bloom adds strength 0.04 x (luminance above the threshold 1) ~ 2 %: 8 % holds them all with margin and still
# catches a black, doubled or misplaced pixel.
# Photometric units (the default, issue 32): the sun's disc carries the sun's power, spread at these sizes over a
# few texels each wider than the 10 degrees between the view axis and the sun, and the reference has no disc: the
# renders leave it out (--no-sun-disc; the disc is tested at these sizes by sun_disc_power_test.sh), and the bound
# on a pixel is the lesson's 1e4 in cd/m2 (x 133177 / 20: docs/units.md).
set -u
VKSKY=${1:?usage: tiny_sizes_test.sh path/to/vksky path/to/exr_probe}
PROBE=${2:?usage: tiny_sizes_test.sh path/to/vksky path/to/exr_probe}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The LUT cache on in the test's own directory: the checks are about sizes, not LUTs (tests/lib/own_lut_cache.sh).
# shellcheck source=lib/own_lut_cache.sh
source "$(dirname "$0")/lib/own_lut_cache.sh"
own_lut_cache "$work"
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
TOL=0.08

# The camera looks 30 degrees up: a 3-row image's pixel spans 25 degrees, and since issue 26 a pixel the horizon
# crosses is its footprint's mix of sky and ground (anti-aliased), no longer the point sample along the axis that the
# reference computes; at 30 degrees the centre pixel's footprint stays clear of the horizon.
ref=$("$VKSKY" --reference --pitch 30 2>"$work/ref.err") || { echo "FAIL: --reference: $(cat "$work/ref.err")" >&2; exit 1; }
read -r ref_r ref_g ref_b <<<"$ref"

# Presets: low (render scale 0.5, 4 bloom levels), medium, and the default (no --quality flag).
presets=("low" "medium" "")
# Sizes: 1x1, 1xN and Nx1 (a one-pixel column/row: bloom mip 0 is 1 pixel across), 2x2 and 4x4 (the chain
# shrinks to one level), 7x3 (odd, non-square: half sizes round down), 15x15 (just under the 16-pixel
# threshold the window used to trip on), 2x600 (tall: mips halve to 1 pixel across while the height still allows 5).
sizes=("1 1" "1 9" "9 1" "2 2" "4 4" "7 3" "15 15" "2 600")
count=0
for preset in "${presets[@]}"; do
    qflag=()
    [ -n "$preset" ] && qflag=(--quality "$preset")
    for size in "${sizes[@]}"; do
        read -r w h <<<"$size"
        for bloom in on off; do
            bflag=()
            [ $bloom = off ] && bflag=(--no-bloom)
            what="${w}x${h} quality=${preset:-default} bloom=$bloom"
            out="$work/t.exr"
            rm -f "$out"
            "$VKSKY" --validate --no-sun-disc --render "$out" --width "$w" --height "$h" --pitch 30 "${qflag[@]}" "${bflag[@]}" \
                >"$work/stdout" 2>"$work/stderr"
            rc=$?
            count=$((count + 1))
            if [ $rc -ne 0 ]; then fail "$what: exit $rc: $(head -c 600 "$work/stderr")"; continue; fi
            [ -s "$work/stderr" ] && fail "$what: stderr not empty: $(head -c 600 "$work/stderr")"
            [ -f "$out" ] || { fail "$what: no EXR written"; continue; }
            # The size: the last pixel exists, the ones just past it do not (exr_probe names the image's size).
            last=$("$PROBE" "$out" $((w - 1)) $((h - 1)) 2>"$work/probe.err") || {
                fail "$what: last pixel unreadable: $(cat "$work/probe.err")"; continue; }
            "$PROBE" "$out" "$w" 0 >/dev/null 2>"$work/probe.err" && fail "$what: pixel ($w, 0) exists"
            grep -qF "is not in the ${w}x${h} image" "$work/probe.err" ||
                fail "$what: EXR is not ${w}x${h}: $(cat "$work/probe.err")"
            # Finite, positive: a sky pixel (the camera looks 30 degrees up).
            awk -v p="$last" 'BEGIN { n = split(p, c, " "); ok = n == 3;
                for (i = 1; i <= n; ++i) if (!(c[i] + 0 > 0 && c[i] + 0 < 1e4 * 133177 / 20)) ok = 0; exit !ok }' ||
                fail "$what: last pixel not a finite positive radiance: '$last'"
            # The sky is rendered at the preset's render scale (low: 0.5; the default on a CPU device picks 0.5 too:
            # --dump-scene says), rounded to nearest, and the tone map samples it at the output's pixel centres:
            # only where that image has a pixel on the view axis too (both sizes odd) is the centre pixel the
            # axis's radiance (7x3 at 0.5 renders 4x2: its centre blends the ground).
            scale=$("$VKSKY" --dump-scene --width "$w" --height "$h" "${qflag[@]}") || fail "$what: --dump-scene: exit $?"
            scale=$(echo "$scale" |
                awk -F: '/"render_scale"/ { gsub(/[ \t,]/, "", $2); print $2 }')
            [ -n "$scale" ] || fail "$what: --dump-scene names no render_scale"
            read -r hw hh < <(awk -v w="$w" -v h="$h" -v s="${scale:-1}" 'BEGIN {
                a = int(w * s + 0.5); b = int(h * s + 0.5); print (a ? a : 1), (b ? b : 1) }')
            if [ $((w % 2)) -eq 1 ] && [ $((h % 2)) -eq 1 ] && [ $((hw % 2)) -eq 1 ] && [ $((hh % 2)) -eq 1 ]; then
                centre=$("$PROBE" "$out" $((w / 2)) $((h / 2)))
                awk -v p="$centre" -v r="$ref_r $ref_g $ref_b" -v tol=$TOL 'BEGIN {
                    split(p, c, " "); split(r, e, " ");
                    for (i = 1; i <= 3; ++i) { d = (c[i] - e[i]) / e[i]; if (d < 0) d = -d; if (!(d <= tol)) exit 1 }
                    exit 0 }' || fail "$what: centre pixel '$centre' differs from the CPU reference '$ref' by more than $TOL"
            fi
        done
    done
done
[ $count -eq $((${#presets[@]} * ${#sizes[@]} * 2)) ] || fail "ran $count renders"

# The compute post chain (issue 16) at the sizes where its chain is shortest: one-level chains, single-tile
# levels, thin images; both of its downsamples.
for size in "1 1" "2 2" "7 3" "15 15" "2 600" "1 9"; do
    read -r w h <<<"$size"
    for down in levels single-pass; do
        what="${w}x${h} --post-pass compute --bloom-downsample $down"
        out="$work/t.exr"
        rm -f "$out"
        "$VKSKY" --validate --render "$out" --width "$w" --height "$h" --quality low --post-pass compute \
            --bloom-downsample "$down" >"$work/stdout" 2>"$work/stderr"
        rc=$?
        count=$((count + 1))
        if [ $rc -ne 0 ] || [ -s "$work/stderr" ]; then fail "$what: exit $rc: $(head -c 600 "$work/stderr")"; continue; fi
        "$PROBE" "$out" "$w" 0 >/dev/null 2>"$work/probe.err"
        grep -qF "is not in the ${w}x${h} image" "$work/probe.err" || fail "$what: EXR is not ${w}x${h}: $(cat "$work/probe.err")"
    done
done
if [ $fails -ne 0 ]; then echo "tiny_sizes: $fails failures in $count renders" >&2; exit 1; fi
echo "tiny_sizes: $count renders validation-clean, sizes exact, centre pixels within $TOL of the CPU reference"
