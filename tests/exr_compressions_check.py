#!/usr/bin/python3
"""OpenImageIO reads an EXR written with some compression and finds the pixels of the same image written
uncompressed (tests/exr_compressions_test.sh; issue 27).
  exr_compressions_check.py REFERENCE.exr FILE.exr EXPECT
EXPECT: exact (lossless: every value's bits equal), or MAX[,MEAN]: bounds on the largest (and the mean) relative
difference (lossy: pxr24 on float channels, b44 on half). Also checks that the header names the compression FILE was meant to have when given as
COMPRESSION=NAME in the environment (OpenImageIO's own name: zip, zips, piz, rle, pxr24, b44, b44a, none).
Exit 0 when they match, 1 (with one line) when not."""
import os
import sys

import numpy as np
import OpenImageIO as oiio


def read(path):
    inp = oiio.ImageInput.open(path)
    if inp is None:
        sys.exit(f"FAIL: OpenImageIO cannot open {path}: {oiio.geterror()}")
    spec = inp.spec()
    px = inp.read_image(oiio.FLOAT)
    inp.close()
    if px is None:
        sys.exit(f"FAIL: OpenImageIO cannot read the pixels of {path}")
    return spec, np.asarray(px, dtype=np.float32)


ref_spec, ref = read(sys.argv[1])
spec, px = read(sys.argv[2])
expect = sys.argv[3]
want = os.environ.get("COMPRESSION")
got = spec.get_string_attribute("compression")
if want and got.split(":")[0] != want:
    sys.exit(f"FAIL: {sys.argv[2]}: compression {got!r}, expected {want!r}")
if px.shape != ref.shape:
    sys.exit(f"FAIL: {sys.argv[2]}: shape {px.shape}, the uncompressed file {ref.shape}")
if not np.isfinite(px).all():
    sys.exit(f"FAIL: {sys.argv[2]}: non-finite values")
if expect == "exact":
    diff = np.count_nonzero(px.view(np.uint32) != ref.view(np.uint32))
    if diff:
        sys.exit(f"FAIL: {sys.argv[2]} ({got}): {diff} values differ from the uncompressed file")
else:
    bounds = [float(b) for b in expect.split(",")]
    rel = np.abs(px - ref) / np.maximum(np.abs(ref), 1e-30)
    rel[(ref == 0) & (px == 0)] = 0
    if rel.max() > bounds[0]:
        sys.exit(f"FAIL: {sys.argv[2]} ({got}): largest relative difference {rel.max():.3g} > {bounds[0]}")
    if len(bounds) > 1 and rel.mean() > bounds[1]:
        sys.exit(f"FAIL: {sys.argv[2]} ({got}): mean relative difference {rel.mean():.3g} > {bounds[1]}")
print(f"ok {os.path.basename(sys.argv[2])} ({got})")
