#!/usr/bin/python3
"""The Mie phase functions against their formulas (issue 31 item 2): tests/phase_ratio_test.sh runs it.

usage: phase_ratio_check.py HG.exr CS.exr G FOV_DEG YAW_DEG PITCH_DEG SUN_AZIMUTH_DEG SUN_ELEVATION_DEG
  Two renders of the same view of an atmosphere of aerosols alone (no Rayleigh, no ozone, single scattering, black
  ground, no disc), one with Henyey-Greenstein, one with Cornette-Shanks. The phase function is the only thing that
  differs, and along a ray toward a sun at infinity the scattering angle is fixed, so each pixel's ratio CS / HG is
  the phase functions' ratio at that pixel's angle: 3 (1 + nu^2) / (2 (2 + g^2)), written here from the published
  forms (Henyey & Greenstein 1941; Cornette & Shanks 1992) and the camera's pixel -> ray rule (sky/view_params.h),
  sharing no code with the shaders. Each sky pixel within 1e-3 relative: the sky pass writes a half-float image, so
  each value is rounded by up to 2^-11 relative and a ratio of two by up to 2^-10 = 9.8e-4 (the rest is float math).
  The expected ratio must vary by more than 30 % over the frame (else the check could not tell the two functions
  apart). Exit 1 otherwise.
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
    return px[..., :3]


def direction(az_deg, el_deg):
    """vksky's angles -> a unit vector (+Y up; azimuth 0 along +X, 90 along +Z)."""
    az, el = math.radians(az_deg), math.radians(el_deg)
    return np.array([math.cos(el) * math.cos(az), math.sin(el), math.cos(el) * math.sin(az)])


def main():
    if len(sys.argv) != 9:
        sys.exit(__doc__)
    hg, cs = read(sys.argv[1]), read(sys.argv[2])
    g, fov, yaw, pitch, sun_az, sun_el = (float(a) for a in sys.argv[3:9])
    h, w = hg.shape[:2]
    f = direction(yaw, pitch)
    right = np.array([-f[2], 0.0, f[0]])
    right /= np.linalg.norm(right)
    up = np.cross(right, f)
    t = math.tan(math.radians(fov) / 2.0)
    x = (2.0 * (np.arange(w) + 0.5) / w - 1.0) * t * w / h
    y = (1.0 - 2.0 * (np.arange(h) + 0.5) / h) * t
    rays = f[None, None, :] + x[None, :, None] * right[None, None, :] + y[:, None, None] * up[None, None, :]
    rays /= np.linalg.norm(rays, axis=2, keepdims=True)
    nu = rays @ direction(sun_az, sun_el)
    expected = 3.0 * (1.0 + nu * nu) / (2.0 * (2.0 + g * g))
    sky = np.all(hg > 1e-6, axis=2)
    if sky.sum() < 0.9 * w * h:
        sys.exit("FAIL: only %d of %d pixels hold sky: the view must be all sky" % (sky.sum(), w * h))
    ratio = cs[sky] / hg[sky]
    err = np.abs(ratio / expected[sky][:, None] - 1.0)
    spread = expected[sky].max() / expected[sky].min()
    print("phase_ratio: g %.2f, %d sky pixels, CS/HG expected %.4f .. %.4f, worst relative error %.2e (mean %.2e)"
          % (g, sky.sum(), expected[sky].min(), expected[sky].max(), err.max(), err.mean()))
    fails = 0
    if spread < 1.3:
        print("FAIL: the expected ratio varies only %.3fx over the frame: the check cannot tell HG from CS" % spread)
        fails += 1
    if err.max() > 1e-3:
        j, i = np.argwhere(sky)[np.argmax(err.max(axis=1))]
        print("FAIL: pixel (%d, %d): CS/HG %s, expected %.6f" % (i, j, cs[j, i] / hg[j, i], expected[j, i]))
        fails += 1
    sys.exit(1 if fails else 0)


if __name__ == "__main__":
    main()
