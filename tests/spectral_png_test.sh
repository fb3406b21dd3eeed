#!/usr/bin/env bash
# tests/spectral_png_test.sh VKSKY SPECTRAL_COMPARE TONEMAP_CHECK: spectral .png environment maps and banded .png
# images (issue 32 item 5): the sum tone-mapped on the host as the .png still's is, dithered as the GPU dithers. Every render runs with --validate
# (a validation message fails the run); stderr holds nothing but the host meter's line. Small sizes, single scattering.
#   1. A twilight equirect .png under --quality auto picks a spectral setting (its stdout line); at six sky directions
#      (pixel centres at 5.6-50.6 degrees up, three azimuths) the PNG's pixel is within CIEDE2000 1 (auto's colour
#      budget) of the 48-wavelength CPU reference along the same ray (3x3 perspective views, centre pixel), tone-mapped
#      at the map's metered EV100 (spectral_compare --png).
#   2. The same run's .exr and .png (equirect, cube, fisheye; --spectral 8 at sunset): the PNG within one 8-bit level
#      of the tone-map formula applied to the EXR at the printed EV100 (tonemap_check, written from the published
#      formulas; tonemap_png's bound without dither), and that EV100 within 0.005 of the log-average of the EXR's own
#      pixels computed here in numpy over the sky's pixels (the default ground is black: docs/units.md's meter), each
#      pixel's direction from the projection's published convention (docs/readme/envmap.md).
#      2b. The dither of the host's tone map: the dithered PNG within the formula's dithered bound, within one level of
#      the undithered PNG, the noise there (at least 20 % of the mid-range channels one level off), and its law the
#      GPU's: where the RGB PNG of the same view and the spectral one both moved off their undithered selves, they moved
#      the same way (the noise's sign at that pixel: the same hash of the same position), on at least 99 %.
#   3. In bands (VKSKY_TILE_ROWS, a map and a perspective frame with the horizon in it): the banded PNG byte for byte the
#      one-band PNG, auto-exposed (the meter's first pass over the bands) and at a given exposure, dithered.
#   4. Bloom, as an RGB frame has it: a perspective still with the sun in view, with and without the horizon. (a) The
#      auto-exposed PNG is metered without bloom, as the GPU's meter reads the HDR image before bloom: its EV100 within
#      0.002 EV (all sky) / 0.05 EV (the horizon's pixels: meter_test.sh's bounds) of the log-average over the sky's
#      pixels of the same view's --no-bloom EXR, computed here in numpy (the pixel's elevation from the view's geometry,
#      as meter_test.sh). Until this part, the host metered the groups' composites, bloom included: 0.4 EV darker than
#      the RGB PNG at the default view. (b) The EXR carries bloom (as an RGB frame's: its total luminance over the
#      --no-bloom EXR's within 10 % of the RGB pair's ratio, and at least 1 % over): an all-sky frame used to take four
#      wavelengths a pass, whose build has no bloom.
set -u
VKSKY=${1:?usage: spectral_png_test.sh VKSKY SPECTRAL_COMPARE TONEMAP_CHECK}
COMPARE=${2:?usage: spectral_png_test.sh VKSKY SPECTRAL_COMPARE TONEMAP_CHECK}
CHECK=${3:?usage: spectral_png_test.sh VKSKY SPECTRAL_COMPARE TONEMAP_CHECK}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
picked() { sed -n 's/^vksky: --quality auto: .*picked --spectral \([0-9]*\) .*/\1/p' "$1"; }
metered() { sed -n 's/^vksky: auto exposure: EV100 \([-0-9.]*\) .*metered on the host: the spectral sum.*/\1/p' "$1"; }
# clean NAME: stderr holds the host meter's line only
clean() { grep -v '^vksky: auto exposure: .*metered on the host' "$work/err" | grep -q . && fail "$1: stderr: $(cat "$work/err")"; }

# 1. The twilight equirect map against the 48-wavelength reference.
map=(--projection equirect --width 32 --no-sun-disc --no-multiscatter --sun-elevation -4 --sun-azimuth 0)
"$VKSKY" "${map[@]}" --validate --render "$work/tw.png" >"$work/out" 2>"$work/err" || fail "twilight map: $(cat "$work/err")"
clean "twilight map"
n=$(picked "$work/out")
ev=$(metered "$work/err")
[ -n "$n" ] && [ "$n" -gt 0 ] || fail "twilight map: no spectral pick printed: $(cat "$work/out")"
echo "twilight map: picked --spectral ${n:-?}, EV100 ${ev:-?}"
# Pixels (i, j) of the 32x16 map: row j's centre is at latitude 90 - 11.25 (j + 0.5); column i's longitude
# pi (1 - (2 i + 1) / 32), direction (sin lon cos lat, sin lat, cos lon cos lat) = dir(azimuth, elevation).
pixels="4,3 4,7 12,5 12,7 22,3 22,6"
i=0
for p in $pixels; do
    read -r az el < <(/usr/bin/python3 -c "
import math; i, j = $p
lon = math.pi * (1 - (2 * i + 1) / 32); lat = math.pi * (0.5 - (j + 0.5) / 16)
d = (math.sin(lon) * math.cos(lat), math.sin(lat), math.cos(lon) * math.cos(lat))
print('%.9f %.9f' % (math.degrees(math.atan2(d[2], d[0])), math.degrees(lat)))")
    "$VKSKY" --width 3 --height 3 --fov 1 --yaw "$az" --pitch "$el" --no-sun-disc --no-multiscatter --sun-elevation -4 \
        --sun-azimuth 0 --reference --spectral 48 --render "$work/ref$i.exr" 2>"$work/err" ||
        fail "reference at ($az, $el): $(cat "$work/err")"
    i=$((i + 1))
done
# The map's pixels and the references' centre pixels, side by side: a 6x1 PNG against a 6x1 EXR.
/usr/bin/python3 - "$work" "$pixels" <<'PY' || fail "twilight map: gathering the pixels"
import sys
import numpy as np
import OpenImageIO as oiio
work, pixels = sys.argv[1], sys.argv[2].split()
png = oiio.ImageBuf(work + "/tw.png").get_pixels(oiio.UINT8)
got = np.zeros((1, len(pixels), 4), np.uint8)
ref = np.zeros((1, len(pixels), 4), np.float32)
for k, p in enumerate(pixels):
    i, j = map(int, p.split(","))
    got[0, k] = png[j, i, :4] if png.shape[2] == 4 else list(png[j, i, :3]) + [255]
    ref[0, k] = oiio.ImageBuf("%s/ref%d.exr" % (work, k)).get_pixels(oiio.FLOAT)[1, 1, :4]
for name, px, fmt in (("got.png", got, oiio.UINT8), ("ref.exr", ref, oiio.FLOAT)):
    out = oiio.ImageBuf(oiio.ImageSpec(len(pixels), 1, 4, fmt))
    out.set_pixels(oiio.ROI(), px)
    out.write(work + "/" + name)
PY
line=$("$COMPARE" --png "$work/got.png" "$work/ref.exr" "${ev:-0}" 1) || fail "twilight map: $line (bound 1)"
echo "twilight map against the 48-wavelength reference at 6 directions: $line"

# --max-color-error with a .png map: the pick (the fewest wavelengths within 1 at noon) renders it.
"$VKSKY" --projection equirect --width 16 --sun-elevation 60 --max-color-error 1 --validate --render "$work/pick.png" \
    >"$work/out" 2>"$work/err" || fail "--max-color-error 1, .png map: $(cat "$work/err")"
clean "--max-color-error 1, .png map"
[ -n "$(sed -n 's/.*picked --spectral \([1-9][0-9]*\) .*/\1/p' "$work/out")" ] && [ -s "$work/pick.png" ] ||
    fail "--max-color-error 1, .png map: no pick or no file: $(cat "$work/out")"

# 2. The PNG against the tone-map formula on the same run's EXR, and the meter against the EXR's log-average.
formula() {
    local name=$1; shift
    "$VKSKY" --spectral 8 --sun-elevation 3 --sun-azimuth 40 --no-sun-disc --no-dither --validate "$@" \
        --render "$work/$name.exr" --render "$work/$name.png" >"$work/out" 2>"$work/err" || { fail "$name: $(cat "$work/err")"; return; }
    clean "$name"
    local e
    e=$(metered "$work/err")
    [ -n "$e" ] || { fail "$name: no host meter line: $(cat "$work/err")"; return; }
    "$CHECK" "$work/$name.exr" "$work/$name.png" photometric "$e" aces || fail "$name: the PNG is not the formula's"
    /usr/bin/python3 - "$work/$name.exr" "$e" "$name" <<'PY' || fail "$name: the metered EV100 is not the EXR's"
import math, sys
import numpy as np
import OpenImageIO as oiio
px = np.asarray(oiio.ImageBuf(sys.argv[1]).get_pixels(oiio.FLOAT), dtype=np.float64)
y = 0.2126 * px[..., 0] + 0.7152 * px[..., 1] + 0.0722 * px[..., 2]
h, w = y.shape
jj, ii = np.mgrid[0:h, 0:w]
u, v = (ii + 0.5) / w, (jj + 0.5) / h
if sys.argv[3] == "equirect":   # latitude pi (0.5 - v): the sky is the upper half
    sky = np.pi * (0.5 - v) >= 0
elif sys.argv[3] == "cube":     # faces +X -X +Y -Y +Z -Z stacked, b top to bottom: up is -b on the side faces
    face, b = np.floor(v * 6), 2 * (v * 6 - np.floor(v * 6)) - 1
    up = np.choose(face.astype(int), [-b, -b, np.ones_like(b), -np.ones_like(b), -b, -b])
    sky = up >= 0
else:                            # the upper hemisphere inside the inscribed circle; outside it, nothing
    sky = np.hypot(2 * u - 1, 1 - 2 * v) <= 1
y = y[sky]
ev = math.log2(math.exp(np.mean(np.log(np.maximum(y, 1e-4)))) * 100 / 12.5)
print("%s: EV100 %s metered, %.4f from the EXR's pixels" % (sys.argv[3], sys.argv[2], ev))
sys.exit(abs(ev - float(sys.argv[2])) > 0.005)
PY
}
formula equirect --projection equirect --width 64
formula cube --projection cubemap --width 16
formula fisheye --projection fisheye --width 48

# 2b. The dither: the host's tone map adds the GPU's (docs/spectral.md "The PNG"), dithered as an RGB PNG is. The same
# sunset with and without --no-dither: the dithered PNG within two levels of the formula on the EXR (tonemap_check's
# dithered bound: the noise's one level more, its mean within 0.05), within one level of the undithered PNG on every
# channel (triangular noise of +-1 LSB moves a rounding by one level at most), and the noise there: at least 20 % of the
# mid-range channels one level off the undithered PNG (before the sixteenth session the host's tone map had none). And
# the law: a pixel's noise moves its rounding, when it does, in the noise's own direction; the RGB PNG (the GPU's
# shader) and the spectral one (the host's C) of the same view draw it from the same hash of the same position, so
# where both moved they moved alike (a wrong hash or seed: half the time).
dithered() {
    local args=(--width 96 --height 54 --pitch 6 --sun-elevation 3 --sun-azimuth 40 --no-sun-disc --validate)
    "$VKSKY" "${args[@]}" --spectral 0 --no-dither --render "$work/rgbflat.png" >/dev/null 2>&1 &&
        "$VKSKY" "${args[@]}" --spectral 0 --render "$work/rgbnoisy.png" >/dev/null 2>&1 || fail "dither: the RGB PNGs"
    args+=(--spectral 8)
    "$VKSKY" "${args[@]}" --no-dither --render "$work/flat.png" >/dev/null 2>"$work/err" || { fail "dither: $(cat "$work/err")"; return; }
    "$VKSKY" "${args[@]}" --render "$work/noisy.exr" --render "$work/noisy.png" >/dev/null 2>"$work/err" ||
        { fail "dither: $(cat "$work/err")"; return; }
    clean "dither"
    local e
    e=$(metered "$work/err")
    "$CHECK" "$work/noisy.exr" "$work/noisy.png" photometric "${e:-0}" aces dither || fail "dither: the PNG is not the formula's"
    /usr/bin/python3 - "$work" <<'PY' || fail "dither: no +-1 LSB noise on the spectral PNG, or not the GPU's"
import sys
import numpy as np
import OpenImageIO as oiio
png = lambda name: np.asarray(oiio.ImageBuf(sys.argv[1] + "/" + name).get_pixels(oiio.UINT8)[..., :3], dtype=int)
flat, noisy, rgb = png("flat.png"), png("noisy.png"), png("rgbnoisy.png") - png("rgbflat.png")
mid = (flat >= 16) & (flat <= 239)
d = noisy - flat
share = (np.abs(d[mid]) == 1).mean()
both = (d != 0) & (rgb != 0)
alike = (np.sign(d[both]) == np.sign(rgb[both])).mean() if both.any() else 0.0
print("dither: %.1f %% of %d mid-range channels one level off the undithered PNG, largest difference %d; moved as the "
      "RGB PNG's (the GPU's dither) on %.2f %% of %d channels both moved" % (100 * share, mid.sum(), np.abs(d).max(),
                                                                          100 * alike, both.sum()))
sys.exit(not (np.abs(d).max() <= 1 and share >= 0.2 and mid.mean() >= 0.25 and both.sum() >= 200 and alike >= 0.99))
PY
}
dithered

# 3. Banded against one band, byte for byte.
bands() {
    local name=$1 rows=$2; shift 2
    "$VKSKY" "$@" --no-bloom --validate --render "$work/$name.one.png" >/dev/null 2>"$work/err" ||
        { fail "$name: one band: $(cat "$work/err")"; return; }
    clean "$name: one band"
    local one
    one=$(metered "$work/err")
    VKSKY_TILE_ROWS=$rows "$VKSKY" "$@" --no-bloom --validate --render "$work/$name.bands.png" >/dev/null \
        2>"$work/all" || { fail "$name: in bands: $(cat "$work/all")"; return; }
    grep -v '^vksky: rendering .* bands)' "$work/all" >"$work/err"   # the progress lines
    clean "$name: in bands"
    [ "$(metered "$work/err")" = "$one" ] || fail "$name: EV100 '$(metered "$work/err")' in bands, '$one' in one"
    cmp -s "$work/$name.one.png" "$work/$name.bands.png" && echo "$name: bands of $rows rows = one band (EV100 $one)" ||
        fail "$name: the banded PNG differs from the one-band PNG"
}
bands equirect-auto 5 --projection equirect --width 48 --spectral 8 --sun-elevation 2
bands perspective-auto 7 --width 40 --height 24 --pitch 0 --fov 50 --spectral 4 --sun-elevation 1
bands fisheye-ev 9 --projection fisheye --width 40 --spectral 8 --sun-elevation 2 --exposure 9

# 4. Bloom: metered without it, drawn with it (the view: 64x36, fov 60, the sun 25 deg up straight ahead).
bloom_view() {
    local name=$1 pitch=$2
    local v=(--width 64 --height 36 --fov 60 --pitch "$pitch" --altitude 0.001 --sun-elevation 25 --sun-azimuth 0
             --render-scale 1 --validate)
    for s in 16 0; do
        "$VKSKY" "${v[@]}" --spectral $s --render "$work/$name.$s.exr" --render "$work/$name.$s.png" >"$work/out" \
            2>"$work/err" || { fail "$name: $(cat "$work/err")"; return; }
        [ $s = 16 ] && { clean "$name"; e=$(metered "$work/err"); }
        "$VKSKY" "${v[@]}" --spectral $s --no-bloom --render "$work/$name.$s.bare.exr" >/dev/null 2>"$work/err" ||
            { fail "$name --no-bloom: $(cat "$work/err")"; return; }
    done
    [ -n "$e" ] || { fail "$name: no host meter line"; return; }
    /usr/bin/python3 - "$work/$name" "$e" "$pitch" <<'PY' || fail "$name: bloom or its meter is not the RGB frame's"
import math, sys
import numpy as np
import OpenImageIO as oiio
base, ev, pitch = sys.argv[1], float(sys.argv[2]), math.radians(float(sys.argv[3]))
def lum(f):
    p = np.asarray(oiio.ImageBuf(f).get_pixels(oiio.FLOAT), dtype=np.float64)
    return 0.2126 * p[..., 0] + 0.7152 * p[..., 1] + 0.0722 * p[..., 2]
y = lum(base + ".16.bare.exr")
h, w = y.shape
ty = math.tan(math.radians(60.0) / 2); tx = ty * w / h
NX, NY = np.meshgrid((2.0 * (np.arange(w) + 0.5) / w - 1.0) * tx, (1.0 - 2.0 * (np.arange(h) + 0.5) / h) * ty)
sin_e = (math.sin(pitch) + NY * math.cos(pitch)) / np.sqrt(1.0 + NX ** 2 + NY ** 2)
R, alt = 6360.0, 0.001
sky = sin_e >= -math.sqrt(alt * (2 * R + alt)) / (R + alt)
ev_exr = math.log2(math.exp(np.mean(np.log(np.maximum(y[sky], 1e-4)))) * 100 / 12.5)
tol = 0.002 if sky.all() else 0.05
ratio = {s: lum(base + ".%d.exr" % s).sum() / lum(base + ".%d.bare.exr" % s).sum() for s in (16, 0)}
print("%s: EV100 %.4f metered, %.4f from the --no-bloom EXR (tolerance %g); bloom adds %.2f %% (RGB: %.2f %%)"
      % (base.rsplit("/", 1)[1], ev, ev_exr, tol, 100 * (ratio[16] - 1), 100 * (ratio[0] - 1)))
ok = abs(ev - ev_exr) <= tol and ratio[16] >= 1.01 and abs(ratio[16] - 1 - (ratio[0] - 1)) <= 0.1 * (ratio[0] - 1)
sys.exit(0 if ok else 1)
PY
}
bloom_view bloom_sky 35
bloom_view bloom_horizon 8

[ $fails -eq 0 ] && echo "spectral_png: all checks passed"
exit $((fails > 0))
