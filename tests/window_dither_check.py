#!/usr/bin/python3
"""The window's dithered swapchain image against the same frame without the dither (tests/window_dither_test.sh).

usage: window_dither_check.py ON.png AGAIN.png OFF.png [srgb UNORM_ON.png UNORM_OFF.png]
       window_dither_check.py same A.png B.png ...   (RGB byte-identical: the X server's window against screenshots)
  ON, AGAIN: two runs with the dither (the screenshot: the swapchain image the last frame presented); OFF: --no-dither.
  The region: the sky's smooth gradient above the horizon (rows 5 .. 54 of a 160x100 frame at pitch 20 and fov 75:
  the horizon is near row 74), every channel; the issue's properties (26 item 4):
    mean preserved: |mean(ON) - mean(OFF)| <= 0.1 LSB (the triangular noise has zero mean; the rounding of OFF's
      smooth gradient averages out over the region's many levels);
    amplitude: every value of ON within 1 LSB of OFF's (noise of +-1 LSB before the quantisation), where the
      quantiser is exact: the UNORM swapchain, whose value the tone map encodes and the format rounds to nearest;
    on an sRGB swapchain the format encodes, and Vulkan does not make that encode exact: lavapipe's disagrees with
      exact rounding of the same values in ~4 % of them (measured: the UNORM and sRGB frames without the dither,
      1418 of 24000 values 1 LSB apart, on an AVX-512 host). Two such inexact roundings, ON's and OFF's, can land a
      value 2 LSB from OFF's (1 of 24000 values there; none on the hosts before). So with an sRGB swapchain
      (`srgb UNORM_ON UNORM_OFF` after the three paths) the noise is checked against the exact quantiser: every
      value of ON within 1 LSB of UNORM_ON's (the same noise, the same pixels; only the encoder differs), OFF within
      1 LSB of UNORM_OFF's, and ON within 2 LSB of OFF's in fewer than 0.1 % of the values beyond 1;
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


def main(on_path, again_path, off_path, exact_on_path=None, exact_off_path=None):
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
    diff = np.abs(r_on - r_off)
    amplitude = int(diff.max())
    if exact_on_path is None:
        check(amplitude <= 1, f"amplitude: {amplitude} LSB (bound 1)")
    else:
        exact_on, exact_off = pixels(exact_on_path)[5:55], pixels(exact_off_path)[5:55]
        to_exact_on = int(np.abs(r_on - exact_on).max())
        to_exact_off = int(np.abs(r_off - exact_off).max())
        check(to_exact_on <= 1, f"the format's encode of the dithered values within 1 LSB of the exact quantiser's: "
                                f"{to_exact_on} LSB")
        check(to_exact_off <= 1, f"the format's encode without the dither within 1 LSB of the exact quantiser's: "
                                 f"{to_exact_off} LSB ({int((r_off != exact_off).sum())} of {r_off.size} values differ)")
        beyond = int((diff > 1).sum())
        check(amplitude <= 2 and beyond * 1000 < diff.size,
              f"amplitude: {amplitude} LSB, {beyond} of {diff.size} values beyond 1 (bound 2, fewer than 0.1 %)")
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
    if len(sys.argv) == 7 and sys.argv[4] == "srgb":
        sys.exit(main(*sys.argv[1:4], *sys.argv[5:7]))
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    sys.exit(main(*sys.argv[1:]))
