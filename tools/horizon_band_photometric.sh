#!/usr/bin/env bash
# tools/horizon_band_photometric.sh VKSKY: the sun's disc against the horizon band in photometric units (issue 26,
# docs/horizon.md "Found while writing it"). horizon_band_test.sh's sunset view (240x135, bloom off) in photometric
# units (the CLI's default): the per-pixel march (--quality high, the reference), --quality cpu and --quality high at
# --render-scale 0.5, each with and without the sun's disc; tests/horizon_band_check.py photometric then checks that
# the disc adds nothing to the band error beyond the sky's own (exit 1 when it does: main's build today, where the
# half-size sky spreads the disc's 1e7 cd/m2 texels over the horizon row beside it). The acceptance check of the fix
# (the disc drawn per output pixel by the tone map); ctest horizon_band runs it once that lands. Every render
# validated (any message fails). About 10 s of CPU on lavapipe. Exit 77 without python3-openimageio/numpy.
set -u
VKSKY=${1:?usage: horizon_band_photometric.sh VKSKY}
HERE=$(cd "$(dirname "$0")" && pwd)
/usr/bin/python3 -c 'import OpenImageIO, numpy' 2>/dev/null || { echo "horizon_band_photometric: SKIP: needs python3-openimageio, python3-numpy"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
view=(--validate --quiet --no-bloom --units photometric --width 240 --height 135 --exposure 1
      --altitude 0.001 --sun-elevation 2 --sun-azimuth 0 --yaw 0 --pitch 15 --fov 90)
fails=0
render() {   # render NAME FLAGS...: NAME.exr and NAME_nodisc.exr
    local name=$1; shift
    for disc in "" --no-sun-disc; do
        local out=$work/$name${disc:+_nodisc}.exr
        "$VKSKY" "${view[@]}" "$@" $disc --render "$out" >"$work/log" 2>&1 && [ ! -s "$work/log" ] ||
            { echo "FAIL: render $name $disc: $(head -c 2000 "$work/log")"; fails=$((fails + 1)); }
    done
}
render ref --quality high
render cpu --quality cpu
render high05 --quality high --render-scale 0.5
[ $fails -eq 0 ] || { echo "horizon_band_photometric: $fails failure(s)"; exit 1; }
/usr/bin/python3 "$HERE/../tests/horizon_band_check.py" photometric "$work" || { echo "horizon_band_photometric: FAIL"; exit 1; }
echo "horizon_band_photometric: ok"
