#!/usr/bin/env bash
# The Mie phase functions (Henyey-Greenstein and Cornette-Shanks) against their published formulas, through the
# renderer (issue 31 item 2): an atmosphere of aerosols alone, single scattering, rendered twice per asymmetry g with
# only --mie-phase changed; tests/phase_ratio_check.py holds each pixel's ratio to the formulas' ratio at its
# scattering angle. Validation + synchronization validation on; any message fails. Usage: phase_ratio_test.sh VKSKY
set -u
VKSKY=${1:?usage: phase_ratio_test.sh path/to/vksky}
HERE=$(cd "$(dirname "$0")" && pwd)
/usr/bin/python3 -c 'import numpy, OpenImageIO' 2>/dev/null || { echo "SKIP: python3-numpy / python3-openimageio missing"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fov=60 yaw=20 pitch=45 sun_az=0 sun_el=15
view=(--width 64 --height 48 --fov $fov --yaw $yaw --pitch $pitch --sun-azimuth $sun_az --sun-elevation $sun_el
      --rayleigh-scale 0 --ozone-scale 0 --no-multiscatter --no-sun-disc --no-bloom --sky-mode march
      --render-scale 1 --units relative --exposure 0 --exr-type float --validate --quiet)
fail=0
for g in 0.8 0.5; do
  for phase in hg cornette-shanks; do
    if ! "$VKSKY" "${view[@]}" --mie-g $g --mie-phase $phase --render "$work/$phase-$g.exr" 2>"$work/err"; then
      echo "FAIL: the render with --mie-phase $phase --mie-g $g failed:"; cat "$work/err"; fail=1; continue
    fi
    [ -s "$work/err" ] && { echo "FAIL: messages on stderr (--mie-phase $phase --mie-g $g):"; cat "$work/err"; fail=1; }
  done
  /usr/bin/python3 "$HERE/phase_ratio_check.py" "$work/hg-$g.exr" "$work/cornette-shanks-$g.exr" $g $fov $yaw $pitch \
    $sun_az $sun_el || fail=1
done
[ $fail -eq 0 ] && echo "phase_ratio: ok"
exit $fail
