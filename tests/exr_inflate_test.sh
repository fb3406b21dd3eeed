#!/bin/sh
# Issue 28: EXR chunks inflated by libdeflate give pixels bit-identical to OpenEXRCore's own decode, for files written
# by OpenImageIO (oiiotool) in every lossless compression vksky reads (NONE, RLE, ZIPS, ZIP, PIZ), HALF and FLOAT,
# and for OpenEXR's own test image stripes.exr (PIZ) and its ZIP / ZIPS re-encodings. vksky-written ZIP files are
# read through the same path by the composite tests.
# Usage: exr_inflate_test.sh EXR_INFLATE_CHECK DATA_DIR
set -eu
check=$1 data=$2
command -v oiiotool >/dev/null 2>&1 || { echo "SKIP: oiiotool not installed"; exit 77; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
files=""
# Odd sizes: the last chunk is short, and ZIP's 16-line chunks and ZIPS's single lines both occur.
oiiotool --pattern noise:type=gaussian:mean=0.5:stddev=0.5 97x53 4 -o "$dir/noise.tif" >/dev/null
for fmt in half float; do
  for comp in none rle zips zip piz; do
    oiiotool "$dir/noise.tif" -d $fmt --compression $comp -o "$dir/noise_${fmt}_$comp.exr"
    files="$files $dir/noise_${fmt}_$comp.exr"
  done
done
# A smooth image (long runs: zlib's matches rather than literals).
oiiotool --pattern fill:topleft=0,0,0:topright=1,0.5,0:bottomleft=0,0.2,1:bottomright=4,4,4 300x40 3 \
  -d half --compression zip -o "$dir/ramp_zip.exr"
files="$files $dir/ramp_zip.exr"
for comp in zip zips; do
  oiiotool "$data/openexr-images/stripes.exr" --compression $comp -o "$dir/stripes_$comp.exr"
  files="$files $dir/stripes_$comp.exr"
done
"$check" "$data/openexr-images/stripes.exr" $files
