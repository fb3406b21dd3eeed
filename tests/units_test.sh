#!/usr/bin/env bash
# tests/units_test.sh VKSKY: photometric units and EV100 exposure (issue 32 items 1 and 2), every render under --validate.
#  1. Scale: a photometric EXR is the relative render times the sun's spectrum over the lesson's 20, channel by
#     channel (the model is linear in the sun), and the header's vksky:sunIlluminance has Y among the published
#     luminous solar constants (1.27-1.34e5 lx); whiteLuminance is 1 and vksky:units names cd/m2.
#  2. Absolute level: a clear noon sky (sun 60 deg, an all-sky view) has the log-average luminance of EV100 14-16 (the
#     photographers' "sunny 16" scene is EV100 15; published clear-sky zenith luminances at 60 deg are 3-6 kcd/m2).
#  3. Auto exposure (the default of photometric PNGs): noon and a -4 deg twilight, 5 stops of light apart, both come
#     out well exposed with no flag: the PNG's mean sRGB level of the sky in 0.3-0.6.
#  4. --exposure is EV100: a fixed EV100 gives the PNG of a scene of luminance L the level of L / (1.2 2^EV) -- one
#     stop more EV100 halves the linear light (checked on the EXR-predicted clamp tone map of a uniform patch).
set -u
VKSKY=${1:?usage: units_test.sh VKSKY}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
view=(--validate --quiet --width 64 --height 36 --pitch 50 --fov 60 --no-bloom)
render() { "$VKSKY" "${view[@]}" "$@" >"$work/log" 2>&1 || { echo "FAIL: vksky $*: $(cat "$work/log")"; exit 1; }; }
render --sun-elevation 60 --render "$work/noon.exr" --render "$work/noon.png"
render --sun-elevation 60 --units relative --render "$work/noon_rel.exr"
render --sun-elevation -4 --render "$work/dusk.exr" --render "$work/dusk.png"
render --sun-elevation 60 --tonemap clamp --exposure 15 --render "$work/ev15.png"
render --sun-elevation 60 --tonemap clamp --exposure 16 --render "$work/ev16.png"
/usr/bin/python3 - "$work" <<'PY'
import math
import sys

import numpy as np
import OpenImageIO as oiio

w = sys.argv[1]
fails = 0


def check(ok, msg):
    global fails
    if not ok:
        fails += 1
        print("FAIL:", msg)


def img(name):
    b = oiio.ImageBuf(w + "/" + name)
    return b.spec(), np.asarray(b.get_pixels(oiio.FLOAT), dtype=np.float64)


def lum(p):
    return 0.2126 * p[..., 0] + 0.7152 * p[..., 1] + 0.0722 * p[..., 2]


spec, noon = img("noon.exr")
_, rel = img("noon_rel.exr")
e = spec.getattribute("vksky:sunIlluminance")
ey = 0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2]
print("sun at the top of the atmosphere: %.0f %.0f %.0f lx-weighted, Y %.0f lx" % (e[0], e[1], e[2], ey))
check(1.27e5 <= ey <= 1.34e5, "the sun's illuminance %.0f lx is outside the published 1.27-1.34e5 lx" % ey)
check(spec.getattribute("whiteLuminance") == 1.0, "whiteLuminance is not 1")
check("cd/m2" in (spec.getattribute("vksky:units") or ""), "vksky:units does not name cd/m2")
for c in range(3):
    ratio = np.median(noon[..., c] / rel[..., c])
    check(abs(ratio / (e[c] / 20.0) - 1.0) < 2e-3, "channel %d: photometric / relative = %.2f, the sun's ratio %.2f"
          % (c, ratio, e[c] / 20.0))
la = math.exp(np.mean(np.log(np.maximum(lum(noon), 1e-4))))
ev = math.log2(la * 100.0 / 12.5)
print("noon sky: log-average %.0f cd/m2, EV100 %.2f" % (la, ev))
check(14.0 <= ev <= 16.0, "noon sky EV100 %.2f outside 14-16" % ev)
_, dusk = img("dusk.exr")
ld = math.exp(np.mean(np.log(np.maximum(lum(dusk), 1e-4))))
print("-4 deg twilight: log-average %.3g cd/m2 (EV100 %.2f)" % (ld, math.log2(ld * 8.0)))
check(la / ld > 2 ** 5, "twilight is not 5 stops below noon")
for name in ("noon.png", "dusk.png"):
    _, p = img(name)
    m = float(p[..., :3].mean())
    print("%s: mean sRGB level %.3f" % (name, m))
    check(0.3 <= m <= 0.6, "%s mean level %.3f outside 0.3-0.6 (auto exposure)" % (name, m))
# EV100: linear = L / (1.2 2^EV) under the clamp tone map; decode sRGB and compare with the EXR's prediction where
# neither clips.
for name, evx in (("ev15.png", 15.0), ("ev16.png", 16.0)):
    _, p = img(name)
    lin = np.where(p <= 0.04045, p / 12.92, ((p + 0.055) / 1.055) ** 2.4)[..., :3]
    pred = noon[..., :3] / (1.2 * 2.0 ** evx)
    ok = (pred > 0.05) & (pred < 0.9)
    err = np.median(np.abs(lin[ok] / pred[ok] - 1.0)) if ok.any() else 1.0
    print("%s: median |PNG / (L / (1.2 2^EV)) - 1| = %.4f over %d values" % (name, err, int(ok.sum())))
    check(ok.sum() > 100 and err < 0.02, "%s does not show L / (1.2 2^%g)" % (name, evx))
sys.exit(1 if fails else 0)
PY
