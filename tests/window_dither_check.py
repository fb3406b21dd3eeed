#!/usr/bin/python3
"""The window's dithered swapchain image against the same frame without the dither (tests/window_dither_test.sh).

usage: window_dither_check.py ON.png AGAIN.png OFF.png
       window_dither_check.py same A.png B.png ...   (RGB byte-identical: the X server's window against screenshots)
  ON, AGAIN: two runs with the dither (the screenshot: the swapchain image the last frame presented); OFF: --no-dither.
  The region: the sky's smooth gradient above the horizon (rows 5 .. 54 of a 160x100 frame at pitch 20 and fov 75:
  the horizon is near row 74), every channel; the issue's properties (26 item 4):
    mean preserved: |mean(ON) - mean(OFF)| <= 0.1 LSB (the triangular noise has zero mean; the rounding of OFF's
      smooth gradient averages out over the region's many levels);
    amplitude: every value of ON within 1 LSB of OFF's (noise of +-1 LSB before the quantisation);
    identical horizontal neighbours (all three channels) < 60 % with the dither and >= 60 % without (so the test
      can fail: the undithered gradient is banded);
    ON and AGAIN byte-identical (the noise is seeded by the pixel, not by time).
  The region must span at least 8 levels of some channel away from 0 and 255, so that it is a gradient.
"""
import sys

import numpy as np
import OpenImageIO as oiio


def pixels(path):
    buf = oiio.ImageBuf(path)
    px = buf.get_pixels(oiio.UINT8)
    if buf.has_error or px is None:
        sys.exit(f"window_dither_check: cannot read {path}: {buf.geterror()}")
    return px[:, :, :3].astype(np.int32)


def main(on_path, again_path, off_path):
    on, again, off = pixels(on_path), pixels(again_path), pixels(off_path)
    fails = 0

    def check(ok, msg):
        nonlocal fails
        print(("ok   " if ok else "FAIL ") + msg)
        fails += not ok

    check(on.shape == (100, 160, 3) and on.shape == off.shape == again.shape, f"sizes {on.shape} {off.shape}")
    if fails:
        return 1
    r_on, r_off = on[5:55], off[5:55]
    levels = max(len(np.unique(r_off[:, :, c])) for c in range(3))
    check(levels >= 8 and r_off.min() > 0 and r_off.max() < 255,
          f"the region is a gradient: {levels} levels, values {r_off.min()} .. {r_off.max()}")
    mean_diff = float(r_on.mean() - r_off.mean())
    check(abs(mean_diff) <= 0.1, f"mean preserved: {mean_diff:+.4f} LSB (bound 0.1)")
    amplitude = int(np.abs(r_on - r_off).max())
    check(amplitude <= 1, f"amplitude: {amplitude} LSB (bound 1)")
    same_on = float(np.all(r_on[:, 1:] == r_on[:, :-1], axis=2).mean())
    same_off = float(np.all(r_off[:, 1:] == r_off[:, :-1], axis=2).mean())
    check(same_on < 0.6, f"identical neighbours with the dither: {100 * same_on:.1f} % (< 60 %)")
    check(same_off >= 0.6, f"identical neighbours without: {100 * same_off:.1f} % (>= 60 %: the test can fail)")
    check(np.array_equal(on, again), "two runs byte-identical")
    return 1 if fails else 0


if __name__ == "__main__":
    if len(sys.argv) >= 4 and sys.argv[1] == "same":
        images = [pixels(p) for p in sys.argv[2:]]
        same = all(i.shape == images[0].shape and np.array_equal(i, images[0]) for i in images[1:])
        print(("ok   " if same else "FAIL ") + "the same pixels: " + ", ".join(sys.argv[2:]))
        sys.exit(0 if same else 1)
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    sys.exit(main(*sys.argv[1:]))
