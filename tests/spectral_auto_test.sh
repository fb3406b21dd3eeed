#!/usr/bin/env bash
# tests/spectral_auto_test.sh VKSKY SPECTRAL_COMPARE: --quality auto's spectral choice beyond still EXR frames (issue 32,
# 32g): PNG stills, environment maps with the sun's disc, sequences; where it cannot, it says why. Every GPU render runs
# with --validate (a validation message fails the run) and must leave stderr with nothing but its own progress lines.
# About 40 s of CPU on lavapipe.
#   1. A PNG at twilight (sun -4, 12x7, single scattering): auto picks a spectral setting (its stdout line), the sum is
#      tone-mapped on the host and auto-exposed there: its EV100 within 0.02 EV of the log-average of the 48-wavelength
#      spectral reference's pixels (numpy here: ISO 2720's key, docs/units.md), and every pixel within CIEDE2000 1 (auto's
#      colour budget) of that reference tone-mapped at that EV100 (spectral_compare --png).
#   2. An equirect map with the sun's disc at 10 km (auto picks 24 wavelengths): the disc's integral (sun_disc_power.py:
#      each pixel's exact solid angle) within 1 % of vksky:sunIlluminanceAtCamera, which for a spectral render is the
#      CPU reference's transmittance per wavelength times the solar spectrum (computed apart from the image).
#   3. A sequence from sun 30 to -4 stays RGB under auto and says why; with --spectral 24
#      its twilight frame within CIEDE2000 1 of the reference of part 1.
#   4. A PNG environment map at sunset renders spectral too (issue 32 item 5: the sum tone-mapped and metered on the
#      host, as the PNG still's; ctest spectral_png checks its pixels).
#   5. Auto by the device's kind (docs/spectral.md): at noon (12x7, single scattering, looking toward the sun) the GPU
#      table (VKSKY_QUALITY_TABLE=gpu) picks 8 wavelengths, within CIEDE2000 1 at p95 of the 48-wavelength reference
#      (spectral_compare; the max is the GPU numerics' share, docs/spectral.md), where RGB of the same numerics is not
#      (p95 1.67: the view shows what the pick is for); the CPU table keeps RGB and prints no pick.
set -u
VKSKY=${1:?usage: spectral_auto_test.sh VKSKY SPECTRAL_COMPARE}
COMPARE=${2:?usage: spectral_auto_test.sh VKSKY SPECTRAL_COMPARE}
HERE=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
picked() { sed -n 's/^vksky: --quality auto: .*picked --spectral \([0-9]*\) .*/\1/p' "$1"; }

# 1. The twilight PNG. Undithered: the promise is the render's colour, and the dither's +-1 LSB of noise (the GPU's law,
# on the spectral PNG too since the sixteenth session; ctest spectral_png checks it) moves a dark twilight pixel's
# CIEDE2000 by design (max 1.24 against 0.90 undithered at this 12x7 view).
tw=(--width 12 --height 7 --no-bloom --no-dither --no-sun-disc --no-multiscatter --sun-elevation -4 --sun-azimuth 0
    --yaw 0 --pitch 35 --fov 60)
"$VKSKY" "${tw[@]}" --validate --render "$work/tw.png" >"$work/out" 2>"$work/err" || fail "twilight PNG: $(cat "$work/err")"
n=$(picked "$work/out")
[ -n "$n" ] && [ "$n" -gt 0 ] || fail "twilight PNG: no spectral pick printed: $(cat "$work/out")"
grep -v '^vksky: auto exposure: ' "$work/err" | grep -q . && fail "twilight PNG: stderr: $(cat "$work/err")"
ev=$(sed -n 's/^vksky: auto exposure: EV100 \([-0-9.]*\) .*metered on the host.*/\1/p' "$work/err")
[ -n "$ev" ] || fail "twilight PNG: no host auto exposure line: $(cat "$work/err")"
"$VKSKY" "${tw[@]}" --reference --spectral 48 --render "$work/ref.exr" 2>"$work/err" || fail "reference: $(cat "$work/err")"
ref_ev=$(/usr/bin/python3 - "$work/ref.exr" <<'PY'
import math, sys
import numpy as np
import OpenImageIO as oiio
px = np.asarray(oiio.ImageBuf(sys.argv[1]).get_pixels(oiio.FLOAT), dtype=np.float64)[..., :3]
y = 0.2126 * px[..., 0] + 0.7152 * px[..., 1] + 0.0722 * px[..., 2]   # every pixel is sky (pitch 35, fov 60)
print("%.6f" % math.log2(math.exp(np.mean(np.log(np.maximum(y, 1e-4)))) * 100.0 / 12.5))
PY
)
echo "twilight PNG: picked --spectral ${n:-?}, EV100 ${ev:-?} (the reference's ${ref_ev:-?})"
[ -n "$ev" ] && [ -n "$ref_ev" ] && awk "BEGIN { d = $ev - $ref_ev; exit !(d <= 0.02 && d >= -0.02) }" ||
    fail "twilight PNG: EV100 $ev against the reference's $ref_ev: over 0.02 EV"
line=$("$COMPARE" --png "$work/tw.png" "$work/ref.exr" "${ref_ev:-0}" 1) || fail "twilight PNG: $line (bound 1)"
echo "twilight PNG against the 48-wavelength reference: $line"

# 2. The disc in an equirect map at 10 km under auto spectral.
map=(--projection equirect --width 96 --sun-elevation 33.3 --sun-azimuth 71 --altitude 10 --exr-type float)
for disc in on off; do
    flag=""; [ $disc = off ] && flag=--no-sun-disc
    # shellcheck disable=SC2086 # an empty flag is no word
    "$VKSKY" "${map[@]}" $flag --validate --render "$work/$disc.exr" >"$work/out" 2>"$work/err" && [ ! -s "$work/err" ] ||
        fail "map ($disc): $(cat "$work/err")"
    n=$(picked "$work/out")
    [ -n "$n" ] && [ "$n" -gt 0 ] || fail "map ($disc): no spectral pick printed: $(cat "$work/out")"
done
/usr/bin/python3 "$HERE/sun_disc_power.py" equirect "$work/on.exr" "$work/off.exr" ||
    fail "map: the spectral disc's integral is more than 1 % from vksky:sunIlluminanceAtCamera"

# 3. A sequence keeps RGB under auto and says why (a spectral frame is a pass per wavelength group, summed on the GPU:
#    a sequence's throughput is the default's, issue 27); --spectral 24 asked for: its twilight frame is spectral.
"$VKSKY" "${tw[@]}" --animate sun-elevation=30:-4 --frame-count 2 --validate --quiet --render "$work/r_%d.exr" \
    >"$work/out" 2>"$work/err" && [ ! -s "$work/err" ] || fail "sequence: $(cat "$work/err")"
grep -q "^vksky: --quality auto: .*'afternoon+twilight' scene.*this run stays RGB: .*a sequence" "$work/out" ||
    fail "sequence: no line saying why it stays RGB: $(cat "$work/out")"
grep -q "picked --spectral" "$work/out" && fail "sequence: picked spectral under auto: $(cat "$work/out")"
"$VKSKY" "${tw[@]}" --animate sun-elevation=30:-4 --frame-count 2 --spectral 24 --validate --quiet \
    --render "$work/s_%d.exr" >"$work/out" 2>"$work/err" && [ ! -s "$work/err" ] || fail "sequence: $(cat "$work/err")"
line=$("$COMPARE" "$work/s_1.exr" "$work/ref.exr")
de=$(echo "$line" | sed -n 's/.*CIEDE2000 mean [0-9.]* p95 [0-9.]* max \([0-9.infa]*\) .*/\1/p')
echo "sequence --spectral 24, twilight frame against the 48-wavelength reference: $line"
[ -n "$de" ] && awk "BEGIN { exit !($de <= 1) }" || fail "sequence: twilight frame CIEDE2000 max '$de' over 1"

# 4. A PNG map at sunset: spectral, its exposure metered on the host.
"$VKSKY" --projection equirect --width 32 --sun-elevation 3 --validate --render "$work/m.png" >"$work/out" 2>"$work/err" ||
    fail "PNG map: $(cat "$work/err")"
n=$(picked "$work/out")
[ -n "$n" ] && [ "$n" -gt 0 ] || fail "PNG map: no spectral pick printed: $(cat "$work/out")"
grep -q "stays RGB" "$work/out" && fail "PNG map: stays RGB: $(cat "$work/out")"
grep -v '^vksky: auto exposure: .*metered on the host: the spectral sum' "$work/err" | grep -q . &&
    fail "PNG map: stderr: $(cat "$work/err")"

# 5. Noon by the device's kind.
noon=(--width 12 --height 7 --no-bloom --no-dither --no-sun-disc --no-multiscatter --sun-elevation 60 --sun-azimuth 0
      --yaw 0 --pitch 35 --fov 60)
"$VKSKY" "${noon[@]}" --reference --spectral 48 --render "$work/noon_ref.exr" 2>"$work/err" ||
    fail "noon reference: $(cat "$work/err")"
VKSKY_QUALITY_TABLE=gpu "$VKSKY" "${noon[@]}" --validate --render "$work/noon_gpu.exr" >"$work/out" 2>"$work/err" &&
    [ ! -s "$work/err" ] || fail "noon, GPU table: $(cat "$work/err")"
[ "$(picked "$work/out")" = 8 ] || fail "noon, GPU table: auto did not pick --spectral 8: $(cat "$work/out")"
line=$("$COMPARE" "$work/noon_gpu.exr" "$work/noon_ref.exr" 100 1) || fail "noon, GPU table's pick: $line (p95 bound 1)"
echo "noon, GPU table, --spectral $(picked "$work/out") against the 48-wavelength reference: $line"
VKSKY_QUALITY_TABLE=gpu "$VKSKY" "${noon[@]}" --spectral 0 --validate --render "$work/noon_rgb.exr" >/dev/null \
    2>"$work/err" && [ ! -s "$work/err" ] || fail "noon RGB: $(cat "$work/err")"
line=$("$COMPARE" "$work/noon_rgb.exr" "$work/noon_ref.exr" 100 1 2>&1) &&
    fail "noon: RGB is within CIEDE2000 1 at p95 too ($line): the view shows nothing the pick is for"
echo "noon, RGB: $line"
VKSKY_QUALITY_TABLE=cpu "$VKSKY" "${noon[@]}" --validate --render "$work/noon_cpu.exr" >"$work/out" 2>"$work/err" &&
    [ ! -s "$work/err" ] || fail "noon, CPU table: $(cat "$work/err")"
grep -q "picked --spectral" "$work/out" && fail "noon, CPU table: picked spectral: $(cat "$work/out")"

[ $fails -eq 0 ] && echo "spectral_auto: all checks passed"
exit $((fails > 0))
