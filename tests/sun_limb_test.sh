#!/usr/bin/env bash
# tests/sun_limb_test.sh VKSKY: the sun's disc against the limb-darkening law and its closed-form integral (issue 31;
# tests/sun_limb_check.py says how). A 2-degree view centred on the sun (the disc ~50 pixels across), photometric
# units, --exr-type float, bloom off, render scale 1, the march; validated, exit statuses checked. The default limb
# darkening (u = 0.6) and none (u = 0), and a sun 30 and 8 degrees up. Exit 77 without python3-openimageio/numpy.
set -u
VKSKY=${1:?usage: sun_limb_test.sh VKSKY}
HERE=$(cd "$(dirname "$0")" && pwd)
/usr/bin/python3 -c 'import OpenImageIO, numpy' 2>/dev/null || { echo "sun_limb: SKIP: needs python3-openimageio, python3-numpy"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
FOV=${SUN_LIMB_FOV:-1} SIZE=${SUN_LIMB_SIZE:-400}
for c in "30 0.6" "8 0.6" "30 0"; do
    read -r el u <<<"$c"
    for disc in on off; do
        flag=""; [ $disc = off ] && flag=--no-sun-disc
        "$VKSKY" --validate --quiet --no-bloom --render-scale 1 --sky-mode march --exr-type float --width "$SIZE" --height "$SIZE" \
            --fov "$FOV" --yaw 0 --pitch "$el" --sun-azimuth 0 --sun-elevation "$el" --limb-darkening "$u" $flag \
            --render "$work/$disc.exr" >"$work/log" 2>&1 || { echo "FAIL: render sun $el u $u $flag: $(cat "$work/log")"; fails=$((fails + 1)); continue 2; }
    done
    echo -n "sun $el deg, u $u: "
    /usr/bin/python3 "$HERE/sun_limb_check.py" "$work/on.exr" "$work/off.exr" "$FOV" 0.265 "$u" ||
        { echo "FAIL: sun $el u $u: the disc is not the limb-darkening law at E T"; fails=$((fails + 1)); }
done
[ $fails -eq 0 ] || { echo "sun_limb: $fails failure(s)"; exit 1; }
echo "sun_limb: ok"
