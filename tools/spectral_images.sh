#!/usr/bin/env bash
# tools/spectral_images.sh VKSKY SPECTRAL_COMPARE [WIDTH HEIGHT [QUALITY]]: the colour axis of the trade on whole
# images (issue 32 item 5): the GPU's RGB renderer and --spectral 4/8/16 against the spectral reference at 48
# wavelengths (vksky --reference --spectral 48), on sunset, twilight, noon and space views; luminance error and
# CIEDE2000 per pixel (tests/spectral_compare). The sun is the top-of-atmosphere spectrum's own Rec.709 colour at
# luminance 20 (the relative units' sun), so the RGB renderer is not charged for a white sun; no bloom, no disc.
# The reference dominates the time: 16 groups of three wavelengths, ~2 min of CPU per view at 24x14.
set -u
VKSKY=${1:?usage: spectral_images.sh VKSKY SPECTRAL_COMPARE [WIDTH HEIGHT [QUALITY]]}
COMPARE=${2:?usage: spectral_images.sh VKSKY SPECTRAL_COMPARE [WIDTH HEIGHT [QUALITY]]}
W=${3:-24} H=${4:-14} Q=${5:-high}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sun=(--sun-illuminance 21.949807,19.542809,18.787458)   # spectrum_solar_rec709_toa scaled to Y = 20
views=(
  "sunset|--sun-elevation 2 --sun-azimuth 0 --yaw 0 --pitch 8 --fov 60"
  "twilight|--sun-elevation -4 --sun-azimuth 0 --yaw 0 --pitch 6 --fov 60"
  "noon|--sun-elevation 60 --sun-azimuth 0 --yaw 180 --pitch 30 --fov 70"
  "space|--altitude 400 --sun-elevation 10 --sun-azimuth 0 --yaw 0 --pitch -60 --fov 60"
)
echo "| view | GPU setting | luminance error mean / p95 | CIEDE2000 mean / p95 / max |"
echo "|---|---|---|---|"
for v in "${views[@]}"; do
    name=${v%%|*} args=${v#*|}
    common=(--width "$W" --height "$H" --no-bloom --no-sun-disc "${sun[@]}" $args)
    "$VKSKY" "${common[@]}" --reference --spectral 48 --render "$work/ref.exr" || exit 1
    for n in 0 4 8 16; do
        "$VKSKY" "${common[@]}" --quality "$Q" --spectral "$n" --render "$work/gpu.exr" || exit 1
        line=$("$COMPARE" "$work/gpu.exr" "$work/ref.exr")
        # "luminance error mean A % p95 B % max C %; CIEDE2000 mean D p95 E max F (...)"
        set -- $line
        label=$([ "$n" = 0 ] && echo "RGB" || echo "--spectral $n")
        echo "| $name | $label | $4 % / $7 % | ${14} / ${16} / ${18} |"
    done
done
