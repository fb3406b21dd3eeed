#!/usr/bin/python3
"""The sun's disc carries the sun's power (issue 32 item 3): tests/sun_disc_power_test.sh runs it.

usage: sun_disc_power.py PROJECTION WITH.exr WITHOUT.exr [FOV_DEG]
  Integrates the disc, sum over pixels of (Y_with - Y_without) x the pixel's solid angle, Y = 0.2126 R + 0.7152 G +
  0.0722 B in cd/m2, and compares it with the header's vksky:sunIlluminanceAtCamera (its Y, lux), which vksky
  computes apart from the image (the CPU reference's transmittance times the sun's spectrum). Solid angles are
  exact per pixel (closed forms below, no small-angle step): equirect by latitude band, a plane's rectangle
  (perspective, cube faces) by the atan formula, the equidistant fisheye by its Jacobian at the pixel centre.
  Prints "disc LX header LX ratio R"; exit 1 when |R - 1| > 1 %.
"""
import math
import sys

import numpy as np
import OpenImageIO as oiio


def luminance(path):
    inp = oiio.ImageInput.open(path)
    if inp is None:
        sys.exit("cannot read %s: %s" % (path, oiio.geterror()))
    spec = inp.spec()
    px = inp.read_image(oiio.FLOAT)
    inp.close()
    px = np.asarray(px, dtype=np.float64).reshape(spec.height, spec.width, spec.nchannels)
    return spec, 0.2126 * px[..., 0] + 0.7152 * px[..., 1] + 0.0722 * px[..., 2]


def plane_rect(u0, u1, v0, v1):
    """Solid angle of the rectangle [u0,u1] x [v0,v1] on the plane at distance 1."""
    f = lambda u, v: np.arctan(u * v / np.sqrt(1.0 + u * u + v * v))
    return f(u1, v1) - f(u0, v1) - f(u1, v0) + f(u0, v0)


def solid_angles(kind, w, h, fov):
    if kind == "equirect":
        y = np.arange(h + 1)
        lat = math.pi * (0.5 - y / h)
        band = 2.0 * math.pi / w * (np.sin(lat[:-1]) - np.sin(lat[1:]))
        return np.repeat(band[:, None], w, axis=1)
    if kind in ("cubemap", "perspective"):
        if kind == "cubemap":
            face = w
            e = np.linspace(-1.0, 1.0, face + 1)
            a = plane_rect(e[None, :-1], e[None, 1:], e[:-1, None], e[1:, None])
            return np.tile(a, (6, 1))
        ty = math.tan(math.radians(fov) / 2.0)
        tx = ty * w / h
        eu = np.linspace(-tx, tx, w + 1)
        ev = np.linspace(-ty, ty, h + 1)
        return plane_rect(eu[None, :-1], eu[None, 1:], ev[:-1, None], ev[1:, None])
    if kind == "fisheye":
        x = (np.arange(w) + 0.5) * 2.0 / w - 1.0
        y = (np.arange(h) + 0.5) * 2.0 / h - 1.0
        r = np.sqrt(x[None, :] ** 2 + y[:, None] ** 2)
        theta = 0.5 * math.pi * np.minimum(r, 1.0)
        area = (2.0 / w) * (2.0 / h)
        with np.errstate(divide="ignore", invalid="ignore"):
            jac = np.where(r > 0, np.sin(theta) * 0.5 * math.pi / r, (0.5 * math.pi) ** 2)
        return np.where(r <= 1.0, jac * area, 0.0)
    sys.exit("unknown projection " + kind)


def main():
    kind, with_path, without_path = sys.argv[1:4]
    fov = float(sys.argv[4]) if len(sys.argv) > 4 else 75.0
    spec, y_with = luminance(with_path)
    _, y_without = luminance(without_path)
    d_omega = solid_angles(kind, spec.width, spec.height, fov)
    disc = float(np.sum((y_with - y_without) * d_omega))
    e = spec.getattribute("vksky:sunIlluminanceAtCamera")
    if e is None:
        sys.exit("%s has no vksky:sunIlluminanceAtCamera" % with_path)
    header = 0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2]
    ratio = disc / header
    print("%s %dx%d: disc %.6g lx header %.6g lx ratio %.5f" % (kind, spec.width, spec.height, disc, header, ratio))
    return 0 if abs(ratio - 1.0) <= 0.01 else 1


sys.exit(main())
