#!/usr/bin/python3
"""The horizon-band error of a frame against the per-pixel march of the same view, computed here (issue 26 item 5;
tests/horizon_band_test.sh runs it).

usage: horizon_band_check.py band FRAME.exr REFERENCE.exr ALTITUDE_KM PITCH_DEG FOV_DEG YAW_DEG SUN_ELEV_DEG SUN_AZ_DEG
         prints "max mean count" of the relative luminance error over the band.
       horizon_band_check.py photometric WORK
         the sunset view in photometric units (tools/horizon_band_photometric.sh renders WORK's frames): for each
         configuration (cpu; high at render scale 0.5) the band max of the frame with the sun's disc is within
         1.01 x that of the same configuration with --no-sun-disc (each against the reference of its own kind) plus
         0.5 %: the disc adds nothing to the band beyond the sky's own error. Also prints the band max of the disc-free
         frame plus the reference's own disc (the frame's disc drawn at the output's scale): what a fix can reach.
       horizon_band_check.py suite WORK QUALITY_HORIZON_TABLE.h TRADEOFF_TABLE.h
         the frames horizon_band_test.sh rendered in WORK: for every configuration and view,
         (a) the band max is within the bound the shipped table (src/app/quality/quality_horizon_table.h) states for
             it: its max against ultra plus the reference's own (high's row: this test's reference is high, ultra's
             128x128 multi-scattering LUT costs minutes on lavapipe; by the triangle inequality the error against
             high is at most the error against ultra plus high's against ultra), 1 % for the floors' denominators;
         (b) max and mean equal tools/tradeoff's for the same configuration, view and reference (TRADEOFF_TABLE.h,
             written by tradeoff --emit-horizon-table --horizon-reference high) within 1e-4 + 0.1 %;
         (c) the frames --max-error E rendered (pick_<view>.exr, E in WORK/pick_<view>.budget): band max within E
             plus high's row, and the cpu configuration (what the frame mean alone accepts there) over E, so a pick
             that ignored the horizon would fail.

The band is defined as tools/tradeoff_horizon.h states it in words, but computed from scratch: the horizon's
elevation for a camera at altitude h above a sphere of radius R = 6360 km (Earth in Bruneton's and Hillaire's
parameters, vksky's default planet) is -atan(sqrt(h (2R + h)) / R); a pinhole camera's pixel (x, y) of a W x H frame
with vertical field of view F and pitch p looks along f + nx tan(F/2) W/H r + ny tan(F/2) u (nx, ny the pixel
centre's normalised coordinates, f, r, u the camera's forward, right and up), whose elevation is
asin((sin p + ny t cos p) / |d|). A pixel is in the band when its elevation is within 2 pixel heights (the elevation
step to the next row in its column) of the horizon's, unless it lies within 4 sun radii + 3 pixel heights of the sun
(the sun's error, not the horizon's). The error of a pixel is |Y - Y_ref| / max(Y_ref, 5 % of the band's brightest
Y_ref), Y Rec. 709's luminance. Nothing here comes from vksky's code: only the frames.
"""
import math
import sys

import numpy as np
import OpenImageIO as oiio

R_EARTH_KM = 6360.0
SUN_RADIUS = math.radians(0.53) / 2


def luminance(path):
    buf = oiio.ImageBuf(path)
    px = buf.get_pixels(oiio.FLOAT)
    if buf.has_error or px is None:
        sys.exit(f"horizon_band_check: cannot read {path}: {buf.geterror()}")
    return 0.2126 * px[:, :, 0] + 0.7152 * px[:, :, 1] + 0.0722 * px[:, :, 2]


def directions(w, h, yaw, pitch, fov):
    """Unit view directions of the pixel centres, (h, w, 3), in x east, y up, z north (yaw clockwise from north)."""
    f = np.array([math.sin(yaw) * math.cos(pitch), math.sin(pitch), math.cos(yaw) * math.cos(pitch)])
    r = np.array([math.cos(yaw), 0.0, -math.sin(yaw)])      # to the right of the view, horizontal
    u = np.cross(f, r)                                        # up in the image (x east, y up, z north: left-handed)
    t = math.tan(fov / 2)
    nx = 2 * (np.arange(w) + 0.5) / w - 1
    ny = 1 - 2 * (np.arange(h) + 0.5) / h
    d = f + (nx[None, :, None] * t * w / h) * r + (ny[:, None, None] * t) * u
    return d / np.linalg.norm(d, axis=2, keepdims=True)


def band_error(frame, ref, alt_km, pitch_deg, fov_deg, yaw_deg, sun_el_deg, sun_az_deg):
    y_frame, y_ref = luminance(frame), luminance(ref)
    h, w = y_ref.shape
    if y_frame.shape != y_ref.shape:
        sys.exit(f"horizon_band_check: {frame} is {y_frame.shape}, {ref} {y_ref.shape}")
    d = directions(w, h, math.radians(yaw_deg), math.radians(pitch_deg), math.radians(fov_deg))
    el = np.arcsin(np.clip(d[:, :, 1], -1, 1))
    step = np.abs(el[1:, :] - el[:-1, :])                   # rows 0 .. h-2: the step to the next row
    el = el[:-1, :]
    e_h = -math.atan(math.sqrt(alt_km * (2 * R_EARTH_KM + alt_km)) / R_EARTH_KM)
    se, sa = math.radians(sun_el_deg), math.radians(sun_az_deg)
    sun = np.array([math.sin(sa) * math.cos(se), math.sin(se), math.cos(sa) * math.cos(se)])
    near_sun = d[:-1, :, :] @ sun > np.cos(4 * SUN_RADIUS + 3 * step)
    band = (np.abs(el - e_h) < 2 * step) & ~near_sun
    if band.sum() < w:
        sys.exit(f"horizon_band_check: only {band.sum()} band pixels: is the horizon in the frame?")
    ref_band, frame_band = y_ref[:-1, :][band], y_frame[:-1, :][band]
    err = np.abs(frame_band - ref_band) / np.maximum(ref_band, 0.05 * ref_band.max())
    return float(err.max()), float(err.mean()), int(band.sum())


# The views (tools/tradeoff's quality_scenes, its index there = the table's scene) and the configurations (the
# table's names; horizon_band_test.sh renders each under the same short name with the same knobs).
VIEWS = {"sunset": (2, 0.001, 15.0, 90.0, 0.0, 2.0, 0.0), "10km": (4, 10.0, 0.0, 60.0, 90.0, 30.0, 0.0)}
CONFIGS = {"cpu": "medium-skyview96-s24-scale0.5-bloomq", "low": "low", "medium": "medium",
           "skyview1": "medium-skyview96", "skyview05": "medium-skyview96-scale0.5"}
REFERENCE = "high"


def table_rows(path):
    """{(config, scene): (max, mean)} of a quality_horizon table (C source)."""
    import re
    rows = {}
    for m in re.finditer(r'\{"([^"]+)", (\d+), ([0-9.]+), ([0-9.]+)\}', open(path).read()):
        rows[(m.group(1), int(m.group(2)))] = (float(m.group(3)), float(m.group(4)))
    return rows


def suite(work, shipped_path, tradeoff_path):
    shipped, tradeoff = table_rows(shipped_path), table_rows(tradeoff_path)
    fails = 0

    def check(ok, msg):
        nonlocal fails
        print(("ok   " if ok else "FAIL ") + msg)
        fails += not ok

    measured = {}
    for v, (scene, alt, pitch, fov, yaw, sun_el, sun_az) in VIEWS.items():
        ref = f"{work}/ref_{v}.exr"
        slack = shipped[(REFERENCE, scene)][0]
        for c, name in CONFIGS.items():
            mx, mean, n = band_error(f"{work}/{c}_{v}.exr", ref, alt, pitch, fov, yaw, sun_el, sun_az)
            measured[(c, v)] = mx
            bound = shipped[(name, scene)][0]
            check(mx <= 1.01 * (bound + slack), f"(a) {c:9s} {v:6s}: band max {100 * mx:7.3f} % (mean {100 * mean:6.3f} %, "
                  f"{n} px) within the table's {100 * bound:.3f} % + high's {100 * slack:.3f} %")
            t = tradeoff.get((name, scene))
            agree = t is not None and all(abs(a - b) <= 1e-4 + 1e-3 * b for a, b in zip((mx, mean), t))
            check(agree, f"(b) {c:9s} {v:6s}: tradeoff's max / mean {t and 100 * t[0]:.3f} / {t and 100 * t[1]:.3f} %")
        budget = float(open(f"{work}/pick_{v}.budget").read())
        mx, mean, n = band_error(f"{work}/pick_{v}.exr", ref, alt, pitch, fov, yaw, sun_el, sun_az)
        check(mx <= 1.01 * (budget + slack), f"(c) --max-error {budget} {v}: the pick's band max {100 * mx:.3f} % "
              f"within {100 * budget:.1f} % + high's {100 * slack:.3f} %")
        check(measured[("cpu", v)] > budget, f"(c) {v}: cpu's band max {100 * measured[('cpu', v)]:.3f} % is over "
              f"{100 * budget:.1f} % (a pick by the frame mean alone would fail (c))")
    return fails


def photometric(work):
    """The photometric sunset: the sun's disc must not reach the band beyond the exclusion (issue 26, 26e)."""
    scene = VIEWS["sunset"][1:]
    fails = 0
    ref, ref_nodisc = oiio.ImageBuf(f"{work}/ref.exr"), oiio.ImageBuf(f"{work}/ref_nodisc.exr")
    disc = ref.get_pixels(oiio.FLOAT) - ref_nodisc.get_pixels(oiio.FLOAT)   # the reference's disc, per output pixel
    for c in ("cpu", "high05"):
        mx, mean, n = band_error(f"{work}/{c}.exr", f"{work}/ref.exr", *scene)
        sky, sky_mean, _ = band_error(f"{work}/{c}_nodisc.exr", f"{work}/ref_nodisc.exr", *scene)
        own = oiio.ImageBuf(f"{work}/{c}_nodisc.exr")
        fixed = oiio.ImageBuf(own.spec())
        fixed.set_pixels(oiio.ROI(), (own.get_pixels(oiio.FLOAT) + disc).astype(np.float32))
        fixed.write(f"{work}/{c}_disc_at_output.exr")
        reach, _, _ = band_error(f"{work}/{c}_disc_at_output.exr", f"{work}/ref.exr", *scene)
        ok = mx <= 1.01 * sky + 0.005
        print(("ok   " if ok else "FAIL ") + f"{c:6s} sunset photometric: band max {100 * mx:8.3f} % (mean "
              f"{100 * mean:6.3f} %, {n} px); without the disc {100 * sky:.3f} % (mean {100 * sky_mean:.3f} %); "
              f"its sky plus the disc at the output's scale {100 * reach:.3f} %")
        fails += not ok
    return fails


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "photometric":
        sys.exit(1 if photometric(sys.argv[2]) else 0)
    if len(sys.argv) == 5 and sys.argv[1] == "suite":
        sys.exit(1 if suite(*sys.argv[2:5]) else 0)
    if len(sys.argv) != 10 or sys.argv[1] != "band":
        sys.exit(__doc__)
    mx, mean, n = band_error(sys.argv[2], sys.argv[3], *map(float, sys.argv[4:10]))
    print(f"{mx:.6f} {mean:.6f} {n}")
