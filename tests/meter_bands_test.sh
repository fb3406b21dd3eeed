#!/usr/bin/env bash
# tests/meter_bands_test.sh VKSKY: auto exposure of a banded render, metered on the GPU (issue 25; sky/meter.h,
# vksky_frame_band's meter rows), every render under --validate.
#  1. An auto-exposed equirect map (PNG + EXR) rendered in one band (the one-frame meter) and in 4 bands of 16 rows
#     (VKSKY_TILE_PIXELS: each band meters only its own rows, the host adds the bands' sums of logs): the two metered
#     EV100s agree within 1e-3 EV and count the same pixels.
#  2. Both equal an EV100 computed here, in numpy, from the EXR of the same map: L = exp(mean ln max(Y, 1e-4 cd/m2)),
#     Y = Rec.709 luminance, over the pixels whose direction is above the horizon seen from the camera's altitude
#     (black ground; a row's elevation from the latlong mapping, 90 - 180 (j + 0.5) / H degrees). Within 2e-3 EV
#     (float sums on the GPU against double here; no row lies within 0.5 degree of the horizon at this size).
#  3. The same one-band / banded agreement for a fisheye (pixels outside its circle are no sky) and a cube map.
#  4. The banded map's PNG is the banded PNG at --exposure of its metered EV100 (equirect): the bands were exposed
#     with the metered value (within 1 of 255, on average < 0.01: the printed EV100 is rounded to 1e-4).
set -u
VKSKY=$(realpath "${1:?usage: meter_bands_test.sh VKSKY}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
# --no-bloom: a fisheye in one band would have bloom (the EXR then holds the sky plus its glare, the meter reads the
# sky alone), in several not.
base=(--validate --altitude 0.001 --sun-elevation 12 --sun-azimuth 40 --no-bloom)
# run NAME PIXELS ARGS...: the map in bands of at most PIXELS pixels; its metered "EV100 L count" on stdout
run() {
    local name=$1 pixels=$2; shift 2
    VKSKY_TILE_PIXELS=$pixels "$VKSKY" "${base[@]}" "$@" --render "$work/$name.exr" --render "$work/$name.png" \
        >"$work/$name.log" 2>&1 || { fail "vksky $*: $(tail -2 "$work/$name.log")"; return 1; }
    local line
    line=$(grep -m1 'auto exposure: EV100' "$work/$name.log") || { fail "$name: no metered EV100 line"; return 1; }
    sed -E 's/.*EV100 ([-0-9.]+) \(log-average luminance ([-0-9.e+]+) .* over ([0-9]+) pixels.*/\1 \2 \3/' <<<"$line"
}
# agree NAME A B: two "EV100 L count" lines within 1e-3 EV (the printed EV100 is rounded to 1e-4), the same count
agree() {
    /usr/bin/python3 -c "import sys; a, b = sys.argv[1].split(), sys.argv[2].split(); \
sys.exit(0 if abs(float(a[0]) - float(b[0])) <= 1e-3 and a[2] == b[2] else 1)" "$2" "$3" ||
        fail "$1: banded EV100/L/count ($3) vs one band ($2): more than 1e-3 EV apart, or other pixels counted"
}
for p in equirect:128 fisheye:64 cubemap:16; do
    proj=${p%%:*} w=${p##*:}
    one=$(run "${proj}_one" 100000000 --projection "$proj" --width "$w") || continue
    banded=$(run "${proj}_bands" $((w * 16)) --projection "$proj" --width "$w") || continue
    grep -qE 'in ([2-9]|[1-9][0-9]+) bands' "$work/${proj}_bands.log" || fail "$proj: the banded run metered no bands"
    echo "$proj: one band: EV100 L count = $one; in bands of 16 rows: $banded"
    agree "$proj" "$one" "$banded"
    [ "$proj" = equirect ] || continue
    # 2. The test's own EV100 from the EXR's pixels and the latlong geometry.
    mine=$(/usr/bin/python3 - "$work/${proj}_one.exr" <<'PY'
import math, sys
import numpy as np
import OpenImageIO as oiio
p = np.asarray(oiio.ImageBuf(sys.argv[1]).get_pixels(oiio.FLOAT), dtype=np.float64)
h, w = p.shape[:2]
y = 0.2126 * p[..., 0] + 0.7152 * p[..., 1] + 0.0722 * p[..., 2]
alt, R = 0.001, 6360.0
elev = np.radians(90.0 - 180.0 * (np.arange(h) + 0.5) / h)
horizon = -math.sqrt(alt * (2 * R + alt)) / (R + alt)
sky = np.repeat((np.sin(elev) >= horizon)[:, None], w, axis=1)
L = math.exp(np.mean(np.log(np.maximum(y[sky], 1e-4))))
print("%.6f %.6g %d" % (math.log2(L * 100.0 / 12.5), L, int(sky.sum())))
PY
)
    echo "$proj: numpy over the EXR: EV100 L count = $mine"
    for got in "$one" "$banded"; do
        /usr/bin/python3 -c "import sys; g, t = sys.argv[1].split(), sys.argv[2].split(); \
sys.exit(0 if abs(float(g[0]) - float(t[0])) <= 2e-3 and g[2] == t[2] else 1)" "$got" "$mine" ||
            fail "$proj: the GPU's EV100/L/count ($got) vs numpy over the EXR ($mine): more than 2e-3 EV apart"
    done
    # 4. The bands were exposed with the metered EV100.
    VKSKY_TILE_PIXELS=$((w * 16)) "$VKSKY" "${base[@]}" --quiet --projection "$proj" --width "$w" \
        --exposure "${banded%% *}" --render "$work/fixed.png" 2>"$work/fixed.log" || fail "fixed exposure: $(cat "$work/fixed.log")"
    /usr/bin/python3 - "$work/${proj}_bands.png" "$work/fixed.png" <<'PY' || fail "$proj: the auto-exposed bands are not the bands at the metered EV100"
import sys
import numpy as np
import OpenImageIO as oiio
a, b = (np.asarray(oiio.ImageBuf(f).get_pixels(oiio.UINT8), dtype=np.int32) for f in sys.argv[1:3])
d = np.abs(a - b)
print("  auto-exposed bands vs --exposure of the metered EV100: max %d, mean %.4f (of 255)" % (d.max(), d.mean()))
sys.exit(0 if d.max() <= 1 and d.mean() < 0.01 else 1)
PY
done
exit $((fails > 0))
