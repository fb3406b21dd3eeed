#!/usr/bin/env bash
# tests/meter_test.sh VKSKY: auto exposure's GPU meter (issue 32 item 2; sky/meter.h, shaders/glsl/meter.comp), every
# render under --validate.
#  1. The meter's log-average equals one computed here, in numpy, from the EXR of the same frame (its pixels are the
#     HDR image's at render scale 1 without bloom): L = exp(mean ln max(Y, 1e-4 cd/m2)), Y = Rec.709 luminance, over
#     the pixels whose ray misses the planet (black ground; the ray's elevation from the view's geometry, computed
#     here: sin e = (sin p + y tan(fov/2) cos p) / |d|, below the horizon sin = -sqrt(h (2R + h)) / (R + h)), or over
#     every pixel with a lit ground. At noon (60 deg), sunset (2 deg) and twilight (-4 deg); an all-sky view and one
#     with the horizon. Tolerance: 0.002 EV all-sky (float sums vs double), 0.05 EV with the horizon (pixels the
#     horizon crosses are the tone map's anti-aliased mix of sky and ground in the EXR, single texels in the meter).
#  2. The metered EV100 (the run's line) equals log2(L 100 / 12.5) of that L (the reflected-light meter's key, ISO
#     2720, K = 12.5), and the auto-exposed PNG is the PNG of the same frame at --exposure of the metered EV100 (the
#     tone map used the meter's value in the same frame): at most 1 of 255 apart, on average < 0.01 (the line's
#     EV100 is rounded to 1e-4).
#  3. One render per frame: the pass trace of an auto-exposed PNG has one sky pass, one meter and one meter_average.
#  4. A sequence with auto exposure through the readback ring (VKSKY_READBACK_SLOTS=2) writes the serial loop's files
#     byte for byte (VKSKY_READBACK_SLOTS=1).
set -u
VKSKY=$(realpath "${1:?usage: meter_test.sh VKSKY values|sequence}")
PART=${2:-values}   # two ctests, each under 30 s: values (1-3), sequence (4)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
# RGB (--spectral 0): the GPU meter is the subject. At sunset and twilight --quality auto picks a spectral setting,
# whose PNG is metered on the host from the groups' sum (that meter: ctest spectral_png part 4), not by meter.comp.
base=(--validate --width 64 --height 36 --fov 60 --no-bloom --render-scale 1 --altitude 0.001 --spectral 0)
run() {   # run NAME ARGS...: the run's stderr in $work/NAME.log
    local name=$1; shift
    "$VKSKY" "${base[@]}" "$@" >"$work/$name.log" 2>&1 || { fail "vksky $*: $(tail -2 "$work/$name.log")"; return 1; }
}
views() { case $1 in 60) echo sky:50 horizon:5 lit:5 ;; *) echo sky:50 horizon:5 ;; esac; }
[ "$PART" = values ] && for sun in 60 2 -4; do
    for view in $(views "$sun"); do
        name=${view%%:*}_$sun; pitch=${view##*:}
        extra=(); [ "${view%%:*}" = lit ] && extra=(--ground-albedo 0.3,0.3,0.3)
        run "$name" --sun-elevation "$sun" --pitch "$pitch" "${extra[@]}" --render "$work/$name.exr" \
            --render "$work/$name.png" || continue
        # The test's own EV100 from the EXR, then the PNG at that fixed exposure.
        ev=$(/usr/bin/python3 - "$work/$name.exr" "$pitch" "${view%%:*}" <<'PY'
import math, sys
import numpy as np
import OpenImageIO as oiio
b = oiio.ImageBuf(sys.argv[1])
p = np.asarray(b.get_pixels(oiio.FLOAT), dtype=np.float64)
h, w = p.shape[:2]
y = 0.2126 * p[..., 0] + 0.7152 * p[..., 1] + 0.0722 * p[..., 2]
pitch, fov, alt, R = math.radians(float(sys.argv[2])), math.radians(60.0), 0.001, 6360.0
ty = math.tan(fov / 2); tx = ty * w / h
nx = 2.0 * (np.arange(w) + 0.5) / w - 1.0
ny = 1.0 - 2.0 * (np.arange(h) + 0.5) / h
NX, NY = np.meshgrid(nx * tx, ny * ty)
sin_e = (math.sin(pitch) + NY * math.cos(pitch)) / np.sqrt(1.0 + NX ** 2 + NY ** 2)
horizon = -math.sqrt(alt * (2 * R + alt)) / (R + alt)
sky = np.ones_like(y, dtype=bool) if sys.argv[3] == "lit" else sin_e >= horizon
L = math.exp(np.mean(np.log(np.maximum(y[sky], 1e-4))))
print("%.6f %.6g %d" % (math.log2(L * 100.0 / 12.5), L, int(sky.sum())))
PY
)
        read -r ev_test l_test n_test <<<"$ev"
        line=$(grep -m1 'auto exposure: EV100' "$work/$name.log")
        ev_gpu=$(sed -E 's/.*EV100 ([-0-9.]+) .*/\1/' <<<"$line")
        l_gpu=$(sed -E 's/.*luminance ([-0-9.e+]+) .*/\1/' <<<"$line")
        n_gpu=$(sed -E 's/.* over ([0-9]+) pixels.*/\1/' <<<"$line")
        tol=0.05; [ "${view%%:*}" = sky ] && tol=0.002
        echo "$name: GPU EV100 $ev_gpu (L $l_gpu cd/m2, $n_gpu px); test $ev_test (L $l_test, $n_test px)"
        [ -n "$ev_gpu" ] || { fail "$name: no metered EV100 line"; continue; }
        /usr/bin/python3 -c "import sys, math; g, t, lg, tol = map(float, sys.argv[1:5]); \
sys.exit(0 if abs(g - t) <= tol and abs(g - math.log2(lg * 100 / 12.5)) < 1e-3 else 1)" "$ev_gpu" "$ev_test" "$l_gpu" \
            "$tol" || fail "$name: GPU EV100 $ev_gpu vs log2(L 100 / 12.5) = $ev_test from the EXR (tolerance $tol EV)"
        [ "${view%%:*}" = horizon ] || continue   # the PNG check once per sun
        run "${name}_fixed" --sun-elevation "$sun" --pitch "$pitch" "${extra[@]}" --exposure "$ev_gpu" \
            --render "$work/${name}_fixed.png" || continue
        /usr/bin/python3 - "$work/$name.png" "$work/${name}_fixed.png" <<'PY' || fail "$name: the auto-exposed PNG is not the PNG at the metered EV100"
import sys
import numpy as np
import OpenImageIO as oiio
a, b = (np.asarray(oiio.ImageBuf(f).get_pixels(oiio.UINT8), dtype=np.int32) for f in sys.argv[1:3])
d = np.abs(a - b)
print("  auto PNG vs --exposure PNG: max %d, mean %.4f (of 255)" % (d.max(), d.mean()))
sys.exit(0 if d.max() <= 1 and d.mean() < 0.01 else 1)
PY
    done
done
# 3. One render: one sky pass, the meter's two dispatches.
[ "$PART" = values ] && { "$VKSKY" "${base[@]}" --render "$work/t.png" --trace-passes >"$work/passes" 2>"$work/passes.err" || fail "trace run: $(cat "$work/passes.err")"
for p in sky meter meter_average; do
    n=$(grep -c "^pass $p\$" "$work/passes")
    [ "$n" = 1 ] || fail "pass $p ran $n times in an auto-exposed frame (want 1)"
done; }
[ "$PART" = sequence ] || exit $((fails > 0))
# 4. A sequence with auto exposure: the ring writes the serial loop's files.
SEQ=(--width 64 --height 36 --validate --quiet --animate sun-elevation=-4:40 --frame-count 4)
for slots in 1 2; do
    mkdir -p "$work/seq$slots"
    (cd "$work/seq$slots" && VKSKY_READBACK_SLOTS=$slots "$VKSKY" "${SEQ[@]}" --render f%02d.png >log 2>&1) ||
        fail "sequence with $slots slot(s): $(tail -2 "$work/seq$slots/log")"
done
a=$(cd "$work/seq1" && md5sum -- *.png); b=$(cd "$work/seq2" && md5sum -- *.png)
[ -n "$a" ] && [ "$a" = "$b" ] || fail "auto-exposed sequence: the ring's files differ from the serial loop's"
echo "sequence (4 frames, auto exposure): ring and serial files $([ "$a" = "$b" ] && echo identical || echo DIFFER)"
# Auto exposure is what makes these frames differ: the four levels must not all be the same exposure.
[ "$(cd "$work/seq1" && md5sum -- *.png | awk '{print $1}' | sort -u | wc -l)" = 4 ] || fail "sequence frames not distinct"
exit $((fails > 0))
