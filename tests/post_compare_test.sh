#!/usr/bin/env bash
# The compute post chain against the fragment chain (issue 16): the same frame rendered with --post-pass compute
# and --post-pass fragment, each also without bloom, all under --validate (validation + synchronization
# validation; any message fails the render). post_compare then requires, of the bloom (composite minus the same
# path's no-bloom composite): energy within E_TOL and shape within SHAPE_TOL of the fragment bloom's peak; of the
# tone-mapped 8-bit pixels: at most LEVELS apart, MEAN on average.
#
# The bounds, and why they are not zero: the compute chain computes levels >= 1 with its own bilinear weights
# (exact, where the sampler quantizes them to 8 bits), fuses the last upsample into the tone map (mip 1's tent
# evaluated at the output pixel instead of interpolated between mip 0 texels), rounds to half floats on
# imageStore where a fragment output may round differently, and encodes sRGB in the shader where the fragment
# path's sRGB attachment does it in fixed function. Measured on lavapipe: energy 0.02-0.6 % (2.6 % for a faint
# bloom, all of it rounding: lavapipe's fragment outputs truncate to half floats, imageStore rounds to nearest; so
# the energy bound adds the rounding difference measured on the no-bloom frames), shape 0.2-1.2 % of the peak,
# 2 levels at most, 0.05 on average.
set -u
VKSKY=${1:?usage: post_compare_test.sh VKSKY POST_COMPARE}
COMPARE=${2:?usage: post_compare_test.sh VKSKY POST_COMPARE}
E_TOL=0.02 SHAPE_TOL=0.02 LEVELS=2 MEAN=0.25
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The LUT cache on in the test's own directory: 28 renders of three LUT settings, and the checks are about the post
# chains, which run after the LUT passes (tests/lib/own_lut_cache.sh).
# shellcheck source=lib/own_lut_cache.sh
source "$(dirname "$0")/lib/own_lut_cache.sh"
own_lut_cache "$work"
fails=0
# Frames: the sun in view at sunset (the bloom's peak), odd sizes (every level's halving rounds down, the single
# pass's tiles are partial), a size with many tiles per level (levels 0-2 of 25x16, 13x8, 7x4 tiles: counters
# complete in every order), the low preset (render scale 0.5: the tone map upsamples the sky); the compute chain
# with its default per-level downsample, and with the single-pass one (--bloom-downsample single-pass, ignored
# by the fragment path) on an odd and a many-tile frame; and the bloom chain from a quarter-size mip 0
# (--bloom-res quarter).
cases=(
  "sunset   --width 320 --height 180 --sun-elevation 3 --quality lesson"
  "odd      --width 97 --height 61 --sun-elevation 5 --pitch 2 --quality lesson"
  "tiles    --width 800 --height 512 --sun-elevation 8 --pitch 5 --quality medium"
  "low      --width 200 --height 120 --sun-elevation 4 --quality low"
  "spd      --width 97 --height 61 --sun-elevation 5 --pitch 2 --quality lesson --bloom-downsample single-pass"
  "spdtiles --width 800 --height 512 --sun-elevation 8 --pitch 5 --quality medium --bloom-downsample single-pass"
  "quarter  --width 320 --height 180 --sun-elevation 3 --quality medium --bloom-res quarter"
)
# In the lesson's units: a photometric PNG is auto-exposed from its own frame (app/scene/light.c), so two chains whose
# blooms differ by rounding would also differ by their exposures; this test compares the chains at one exposure.
for c in "${cases[@]}"; do
    read -r name args <<<"$c"
    args="$args --units relative"
    for pp in fragment compute; do
        # shellcheck disable=SC2086  # args are words
        "$VKSKY" --validate --post-pass $pp $args --render "$work/$pp.exr" --render "$work/$pp.png" \
            >/dev/null 2>"$work/err" || { echo "FAIL $name: --post-pass $pp: $(head -c 600 "$work/err")"; fails=$((fails + 1)); continue 2; }
        # shellcheck disable=SC2086
        "$VKSKY" --validate --post-pass $pp $args --no-bloom --render "$work/$pp-nb.exr" \
            >/dev/null 2>"$work/err" || { echo "FAIL $name: --post-pass $pp --no-bloom: $(head -c 600 "$work/err")"; fails=$((fails + 1)); continue 2; }
    done
    echo "== $name: $args"
    "$COMPARE" "$work/fragment.exr" "$work/compute.exr" "$work/fragment-nb.exr" "$work/compute-nb.exr" \
        "$work/fragment.png" "$work/compute.png" $E_TOL $SHAPE_TOL $LEVELS $MEAN || { echo "FAIL $name"; fails=$((fails + 1)); }
done
[ $fails -eq 0 ] || { echo "post_compare: $fails failures"; exit 1; }
echo "post_compare: compute and fragment chains agree within the bounds on ${#cases[@]} frames"
