#!/usr/bin/python3
"""The sun's disc against its closed form (issue 31 item 2): tests/sun_limb_test.sh runs it.

usage: sun_limb_check.py WITH.exr WITHOUT.exr FOV_DEG RADIUS_DEG U
  A perspective frame centred on the sun, the disc many pixels across. The disc's radiance (with minus without the
  disc) at each pixel well inside it against the limb-darkening law L(mu) = L0 (1 - u (1 - mu)), mu the cosine at the
  sun's surface (mu = sqrt(1 - (sin t / sin r)^2), t the pixel's angle from the sun's centre), where L0 comes from
  the closed-form integral of that law over the disc, E = L0 pi sin^2 r (1 - u / 3), and E is the header's
  vksky:sunIlluminanceAtCamera (the sun's illuminance at the camera: E_sun T). So the test holds the disc's shape
  and level together: each interior pixel within 2 % (luminance; with u > 0 inside rho <= 0.8, see below). Exit 1
  otherwise.
"""
import math
import sys

import numpy as np
import OpenImageIO as oiio


def read(path):
    inp = oiio.ImageInput.open(path)
    if inp is None:
        sys.exit("cannot read %s: %s" % (path, oiio.geterror()))
    spec = inp.spec()
    px = np.asarray(inp.read_image(oiio.FLOAT), dtype=np.float64).reshape(spec.height, spec.width, spec.nchannels)
    inp.close()
    return spec, 0.2126 * px[..., 0] + 0.7152 * px[..., 1] + 0.0722 * px[..., 2]


def main():
    with_path, without_path = sys.argv[1:3]
    fov, radius, u = (float(a) for a in sys.argv[3:6])
    spec, y_with = read(with_path)
    _, y_without = read(without_path)
    e = spec.getattribute("vksky:sunIlluminanceAtCamera")
    if e is None:
        sys.exit("%s has no vksky:sunIlluminanceAtCamera" % with_path)
    E = 0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2]
    r = math.radians(radius)
    L0 = E / (math.pi * math.sin(r) ** 2 * (1.0 - u / 3.0))
    w, h = spec.width, spec.height
    ty = math.tan(math.radians(fov) / 2.0)
    tx = ty * w / h
    # The pixel centres' directions on the plane at distance 1 (the sun at the centre of the view, the optical axis).
    x = ((np.arange(w) + 0.5) / w * 2.0 - 1.0) * tx
    y = ((np.arange(h) + 0.5) / h * 2.0 - 1.0) * ty
    t = np.arctan(np.sqrt(x[None, :] ** 2 + y[:, None] ** 2))
    # The sun's centre may sit off the axis by a fraction of a pixel: find it as the disc's light-weighted centroid.
    disc = y_with - y_without
    wsum = np.sum(disc)
    cx = np.sum(disc * x[None, :]) / wsum
    cy = np.sum(disc * y[:, None]) / wsum
    t = np.arctan(np.sqrt((x[None, :] - cx) ** 2 + (y[:, None] - cy) ** 2))
    pixel = 2.0 * ty / h
    inside = t < r - 3.0 * pixel           # away from the edge, where the disc is filtered at the texel's size
    rho = np.sin(t[inside]) / math.sin(r)
    mu = np.sqrt(np.clip(1.0 - rho ** 2, 0.0, 1.0))
    want = L0 * (1.0 - u * (1.0 - mu))
    rel = disc[inside] / want - 1.0
    # The shader spreads the limb darkening over its support, R + 1.5 texels (sky_common.glsl, sun_power_shape: its
    # square-root edge must fall where the smooth edge is already zero), so the profile converges to the law as 1.5
    # texels / R: at 106 texels per radius the outer rim (rho > 0.8) is a few per cent bright; the law is held on
    # rho <= 0.8 (the rim is reported) and, with u = 0, on the whole interior.
    held = rho <= 0.8 if u > 0.0 else rho <= 1.0
    worst = float(np.max(np.abs(rel[held])))
    rim = float(np.max(np.abs(rel[~held]))) if np.any(~held) else 0.0
    centre = float(np.mean(rel[rho < 0.2]))
    limb = float(np.mean(rel[rho > 0.8])) if np.any(rho > 0.8) else float("nan")
    print("disc: %d interior pixels, worst %.2f %% (rho <= 0.8 when u > 0; the rim's worst %.2f %%), centre %+.2f %%, "
          "rim mean %+.2f %%; L0 %.4g cd/m2 (E %.4g lx)" % (rel.size, 100 * worst, 100 * rim, 100 * centre, 100 * limb, L0, E))
    # The rim is not the law by design (docs/claims.md, issue 31: it stays), but it is bounded: the stretch of 1.5 texels
    # over R brightens rho in (0.8, 1 - 3 px / R) by at most u (sqrt(1 - (rho R / (R + 1.5 px))^2) - sqrt(1 - rho^2)) /
    # (1 - u (1 - sqrt(1 - rho^2))), less the centre's deficit; at 106 texels per radius 5.5 % (less 1.1 %), measured 4.7 %.
    # Held at that closed form's value for this image's texels per radius + 1 point: a wider edge, a limb spread
    # further, or a lost normalisation fail it.
    if u > 0.0 and np.any(~held):
        R_px = r / (math.radians(fov) / h)
        rr = rho[~held]
        stretch = np.sqrt(np.clip(1.0 - (rr * R_px / (R_px + 1.5)) ** 2, 0.0, 1.0))
        law = 1.0 - u * (1.0 - np.sqrt(np.clip(1.0 - rr ** 2, 0.0, 1.0)))
        rim_bound = float(np.max(u * (stretch - np.sqrt(np.clip(1.0 - rr ** 2, 0.0, 1.0))) / law)) + 0.01
        print("  rim bound (the stretch over R + 1.5 texels, %.0f texels per radius, + 1 point): %.2f %%" % (R_px, 100 * rim_bound))
        ok_rim = rim <= rim_bound
    else:
        ok_rim = True
    ok = rel.size > 500 and worst <= 0.02 and not math.isnan(limb) and ok_rim
    return 0 if ok else 1


sys.exit(main())
