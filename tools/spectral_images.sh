#!/usr/bin/env bash
# tools/spectral_images.sh VKSKY SPECTRAL_COMPARE [WIDTH HEIGHT [QUALITY]]: the colour axis of the trade on whole
# images (issue 32 item 5): the GPU's RGB renderer at every preset and --spectral 4..32 against the spectral reference at 48
# wavelengths (vksky --reference --spectral 48), on sunset, twilight, noon and space views; luminance error and
# CIEDE2000 per pixel (tests/spectral_compare). The sun is the top-of-atmosphere spectrum's own Rec.709 colour at
# luminance 20 (the relative units' sun), so the RGB renderer is not charged for a white sun; no bloom, no disc.
# The ground views keep the horizon out of the image (as ctest spectral_gpu does): the GPU draws a lit ground and
# anti-aliases the horizon where the reference samples each pixel's centre, so those pixels are not the same
# quantity (with pitch 8 the sunset's ground pixels read as errors of thousands of %).
# The reference dominates the time: 16 groups of three wavelengths, ~2 min of CPU per view at 24x14.
# PRESETS (default "low medium high ultra": RGB at each) and COUNTS (default "4 8 16 24 32": at QUALITY) choose the
# rows; VIEWS (default all four) the views, e.g. VIEWS="sunset twilight".
set -u
VKSKY=${1:?usage: spectral_images.sh VKSKY SPECTRAL_COMPARE [WIDTH HEIGHT [QUALITY]]}
COMPARE=${2:?usage: spectral_images.sh VKSKY SPECTRAL_COMPARE [WIDTH HEIGHT [QUALITY]]}
W=${3:-24} H=${4:-14} Q=${5:-high}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sun=(--sun-illuminance 21.949807,19.542809,18.787458)   # spectrum_solar_rec709_toa scaled to Y = 20
views=(
  "sunset|--sun-elevation 2 --sun-azimuth 0 --yaw 0 --pitch 35 --fov 60"
  "twilight|--sun-elevation -4 --sun-azimuth 0 --yaw 0 --pitch 35 --fov 60"
  "noon|--sun-elevation 60 --sun-azimuth 0 --yaw 180 --pitch 40 --fov 70"
  "space|--altitude 400 --sun-elevation 10 --sun-azimuth 0 --yaw 0 --pitch -60 --fov 60"
)
echo "| view | GPU setting | luminance error mean / p95 | CIEDE2000 mean / p95 / max | sRGB PSNR |"
echo "|---|---|---|---|---|"
for v in "${views[@]}"; do
    name=${v%%|*} args=${v#*|}
    [[ " ${VIEWS:-sunset twilight noon space} " == *" $name "* ]] || continue
    common=(--width "$W" --height "$H" --no-bloom --no-sun-disc "${sun[@]}" $args)
    "$VKSKY" "${common[@]}" --reference --spectral 48 --render "$work/ref.exr" || exit 1
    # Every preset renders RGB (PRESETS, default the four); the spectral settings (COUNTS) at QUALITY.
    settings=()
    for p in ${PRESETS:-low medium high ultra}; do settings+=("$p:0"); done
    for n in ${COUNTS:-4 8 16 24 32}; do settings+=("$Q:$n"); done
    for s in "${settings[@]}"; do
        q=${s%%:*} n=${s#*:}
        "$VKSKY" "${common[@]}" --quality "$q" --spectral "$n" --render "$work/gpu.exr" || exit 1
        line=$("$COMPARE" "$work/gpu.exr" "$work/ref.exr")
        # "luminance error mean A % p95 B % max C %; CIEDE2000 mean D p95 E max F (N pixels); sRGB PSNR P dB"
        set -- $line
        label=$([ "$n" = 0 ] && echo "RGB, --quality $q" || echo "--spectral $n, --quality $q")
        echo "| $name | $label | $4 % / $7 % | ${14} / ${16} / ${18} | ${23} dB |"
    done
done
