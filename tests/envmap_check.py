#!/usr/bin/python3
"""Environment-map files through OpenImageIO (tests/envmap_test.sh runs it).

usage: envmap_check.py info EQUIRECT.exr CUBE.exr
         OpenImageIO reports each file's environment format; OIIO's own latlong lookup (its TextureSystem, not vksky's
         maths) agrees with vksky's cube map sampled by OpenEXR's cube axes (Imf::CubeMap, written out below); a cube
         map built from OIIO's latlong lookups (equirect -> cube) matches vksky's cube, and an equirect map built from
         vksky's cube (cube -> equirect) matches vksky's equirect; the header's sun direction is where the map's
         brightest pixel is, by OIIO's lookup.
       envmap_check.py same A B
         the two images hold the same pixels, bit for bit or within one step of the stored type (see same()).
OpenImageIO 2.4's oiiotool has no latlong <-> cube conversion and its TextureSystem does not read OpenEXR's
vertical-strip cube layout correctly, so the conversions go through OIIO's latlong lookup and OpenEXR's cube axes.
"""
import math
import sys

import numpy as np
import OpenImageIO as oiio

fails = 0


def fail(msg):
    global fails
    fails += 1
    print("FAIL:", msg, file=sys.stderr)


def pixels(path, fmt=oiio.FLOAT):
    """The spec and the pixels (fmt None: as stored)."""
    buf = oiio.ImageBuf(path)
    spec = buf.spec()
    data = buf.get_pixels(fmt if fmt is not None else spec.format)
    if buf.has_error or data is None:
        fail(f"{path}: cannot read: {buf.geterror()}")
        sys.exit(1)
    return spec, data


# OpenEXR's cube faces, +X -X +Y -Y +Z -Z top to bottom: top-left corner direction and the axes of pixel x and y.
CORNER = np.array([[1, 1, -1], [-1, 1, 1], [-1, 1, 1], [-1, -1, -1], [1, 1, 1], [-1, 1, -1]], float)
RIGHT = np.array([[0, 0, 1], [0, 0, -1], [1, 0, 0], [1, 0, 0], [-1, 0, 0], [1, 0, 0]], float)
DOWN = np.array([[0, -1, 0], [0, -1, 0], [0, 0, -1], [0, 0, 1], [0, -1, 0], [0, -1, 0]], float)


def cube_dirs(n):
    """Unit direction of every pixel centre of an n-face cube (6n x n x 3)."""
    y, x = np.mgrid[0:6 * n, 0:n] + 0.5
    face = (y // n).astype(int)
    a, b = 2 * x / n, 2 * (y / n - face)
    d = CORNER[face] + a[..., None] * RIGHT[face] + b[..., None] * DOWN[face]
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


def cube_sample(cube, d):
    """Nearest pixel of a cube map along unit directions d (... x 3)."""
    n = cube.shape[1]
    axis = np.argmax(np.abs(d), axis=-1)
    comp = np.take_along_axis(d, axis[..., None], -1)[..., 0]
    face = 2 * axis + (comp < 0)
    s = d / np.abs(comp)[..., None]
    rel = s - CORNER[face]
    x = np.clip((0.5 * np.sum(rel * RIGHT[face], -1) * n).astype(int), 0, n - 1)
    y = np.clip((0.5 * np.sum(rel * DOWN[face], -1) * n).astype(int), 0, n - 1) + face * n
    return cube[y, x]


def latlong_dirs(w, h):
    """OpenEXR's LatLongMap: longitude +pi at the left edge to -pi at the right, latitude +pi/2 at the top;
    direction (sin lon cos lat, sin lat, cos lon cos lat)."""
    y, x = np.mgrid[0:h, 0:w] + 0.5
    lon, lat = math.pi * (1 - 2 * x / w), math.pi * (0.5 - y / h)
    return np.stack([np.sin(lon) * np.cos(lat), np.sin(lat), np.cos(lon) * np.cos(lat)], -1)


def oiio_lookup(path, dirs):
    ts = oiio.TextureSystem(False)
    opt = oiio.TextureOpt()
    opt.interpmode = oiio.InterpMode.Bilinear
    opt.mipmode = oiio.MipMode.NoMIP
    out = np.empty(dirs.shape[:-1] + (3,))
    flat = dirs.reshape(-1, 3)
    res = out.reshape(-1, 3)
    for i, d in enumerate(flat):
        res[i] = ts.environment(path, opt, tuple(map(float, d)), (0, 0, 0), (0, 0, 0), 3)
    return out


def lum(rgb):
    return rgb[..., 0] * 0.2126 + rgb[..., 1] * 0.7152 + rgb[..., 2] * 0.0722


def compare(name, got, want, sun, mask_deg, dirs, med_max, p98_max):
    """Relative luminance error away from the sun's disc (a step no resampling keeps)."""
    keep = dirs @ sun < math.cos(math.radians(mask_deg))
    err = np.abs(lum(got) - lum(want))[keep] / np.maximum(lum(want)[keep], 1e-3)
    med, p98 = float(np.median(err)), float(np.percentile(err, 98))
    print(f"{name}: median relative error {med:.4f}, 98th percentile {p98:.4f} over {err.size} pixels")
    if not (med < med_max and p98 < p98_max):
        fail(f"{name}: median {med:.4f} (< {med_max}), 98th percentile {p98:.4f} (< {p98_max})")


def info(eq_path, cube_path):
    eq_spec, eq = pixels(eq_path)
    cube_spec, cube = pixels(cube_path)
    if eq_spec.get_string_attribute("textureformat") != "LatLong Environment":
        fail(f"{eq_path}: OpenImageIO reports textureformat '{eq_spec.get_string_attribute('textureformat')}'")
    if cube_spec.get_string_attribute("textureformat") != "CubeFace Environment":
        fail(f"{cube_path}: OpenImageIO reports textureformat '{cube_spec.get_string_attribute('textureformat')}'")
    sun = np.array(eq_spec.getattribute("vksky:sunDirection"), float)
    if cube_spec.getattribute("vksky:sunDirection") is None or sun.shape != (3,):
        fail("no vksky:sunDirection attribute")
        return
    eq, cube = eq[..., :3], cube[..., :3]
    n = cube.shape[1]
    # OIIO's latlong lookup along every cube pixel's direction: equirect -> cube.
    dirs = cube_dirs(n)
    from_eq = oiio_lookup(eq_path, dirs)
    compare("equirect -> cube (OIIO latlong lookup) vs vksky's cube", from_eq, cube, sun, 3.0, dirs, 0.02, 0.1)
    # vksky's cube along every equirect pixel's direction (OpenEXR's latlong axes): cube -> equirect.
    ldirs = latlong_dirs(eq.shape[1], eq.shape[0])
    from_cube = cube_sample(cube, ldirs)
    compare("cube -> equirect (OpenEXR axes) vs vksky's equirect", from_cube, eq, sun, 3.0, ldirs, 0.02, 0.1)
    # The header's sun: OIIO finds the map's brightest value along it, brighter than 5 degrees away on every side
    # (the drawn disc, at most the sun's radius or a texel, 1.4 degrees at 256 wide, lies within that). The disc
    # keeps the sun's power, not its radiance, when a texel is wider than the sun (sky_common.glsl, sun_disc): at
    # 256 wide its peak is ~(0.265 / 1.4)^2 of the true radiance, so a comparison with the sky opposite the sun
    # would measure the map's resolution, not where the sun is.
    at_sun = lum(oiio_lookup(eq_path, sun[None, :]))[0]
    side = np.cross(sun, np.array([0.0, 1.0, 0.0]))
    side = side / np.linalg.norm(side) if np.linalg.norm(side) > 1e-6 else np.array([1.0, 0.0, 0.0])
    up = np.cross(side, sun)
    c5, s5 = math.cos(math.radians(5.0)), math.sin(math.radians(5.0))
    around = np.array([c5 * sun + s5 * side, c5 * sun - s5 * side, c5 * sun + s5 * up, c5 * sun - s5 * up])
    far = float(np.max(lum(oiio_lookup(eq_path, around))))
    peak_dir = ldirs.reshape(-1, 3)[np.argmax(lum(eq).reshape(-1))]
    angle = math.degrees(math.acos(min(1.0, float(peak_dir @ sun))))
    print(f"header sun direction {sun}: brightest pixel {angle:.2f} deg away; OIIO lookup there {at_sun:.3g}, "
          f"5 deg around it at most {far:.3g}")
    if angle > 1.0 or not at_sun > 2 * far:
        fail(f"the header's sun direction is {angle:.2f} deg from the brightest pixel (lookup {at_sun} vs {far})")


def same(a, b, steps=0.0):
    """Bit-identical, or within `steps` steps of the stored type (fp16 ulps or 8-bit levels). The pixels of a band are
    the whole image's bit for bit (issue 26: at render scale 1 the tone map fetches a pixel's texel and starts its
    horizon taps there, whatever the band's height), so an EXR must be identical. An auto-exposed PNG may differ by
    one level: its exposure multiplier comes from the meter's float sums, grouped by band (ctest meter_bands)."""
    sa, pa = pixels(a, None)
    sb, pb = pixels(b, None)
    if pa.shape != pb.shape:
        fail(f"{a} {pa.shape} vs {b} {pb.shape}")
        return
    differ = int(np.sum(pa != pb))
    if pa.dtype == np.float16:
        x, y = pa.astype(np.float64), pb.astype(np.float64)
        ulp = np.spacing(np.maximum(np.abs(x), 2.0 ** -14).astype(np.float16)).astype(np.float64)
        worst = float(np.max(np.abs(x - y) / ulp))
    else:
        worst = float(np.max(np.abs(pa.astype(np.int64) - pb.astype(np.int64))))
    print(f"{a} vs {b}: {differ} of {pa.size} values differ, by at most {worst:g} "
          f"{'fp16 ulp' if pa.dtype == np.float16 else 'levels'}")
    if steps == 0 and differ:
        fail(f"{a} and {b}: {differ} values differ (bit-identical required)")
    elif worst > steps:
        fail(f"{a} and {b} differ by {worst} steps (more than the {steps:g} allowed)")


if __name__ == "__main__":
    if sys.argv[1] == "info":
        info(sys.argv[2], sys.argv[3])
    elif sys.argv[1] == "same":
        same(sys.argv[2], sys.argv[3], float(sys.argv[4]) if len(sys.argv) > 4 else 0.0)
    sys.exit(1 if fails else 0)
