#!/usr/bin/env bash
# Environment maps through the command line (issue 13). Every render runs with --validate (validation +
# synchronization validation; any message makes vksky exit non-zero).
#  - OpenImageIO reads each map and reports its environment format; the maps against each other through OIIO's
#    latlong lookup and OpenEXR's cube axes (envmap_check.py); the header carries the sun.
#  - Tiled == untiled: the same map rendered in many bands (a small VKSKY_TILE_PIXELS) and in one holds the same
#    pixels, for equirect, cube and perspective: the EXR bit for bit, the auto-exposed PNG within one 8-bit level
#    (the exposure meter's float sums, grouped by band; envmap_check.py same says why).
#  - Peak memory: a 4096x2048 map under a band budget that forces 64-row bands stays far below the same map in one
#    band (/usr/bin/time -v's maximum resident set size).
#  - Ctrl-C stops a banded render between bands and leaves no file.
#  - Bad input: one line, exit 2, no file; yaw/pitch/fov and --height get a note.
# Exit 77 (skipped) without python3-openimageio + numpy or GNU time.
set -u
VKSKY=${1:?usage: envmap_test.sh path/to/vksky}
here=$(cd "$(dirname "$0")" && pwd)
PY=/usr/bin/python3
if ! $PY -c 'import OpenImageIO, numpy' 2>/dev/null || [ ! -x /usr/bin/time ] || ! command -v oiiotool >/dev/null; then
    echo "envmap_test: skipped (needs python3-openimageio, python3-numpy, openimageio-tools and GNU time)"; exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
run() { "$VKSKY" --validate --quiet "$@" 2>"$work/stderr" || fail "vksky $*: exit $? ($(cat "$work/stderr"))"; }

S=(--sun-azimuth 40 --sun-elevation 30 --ground-albedo 0.3,0.3,0.3 --steps 16)

# --- OpenImageIO reads the maps ---
run --render "$work/eq.exr" --render "$work/eq.png" --projection equirect --width 256 "${S[@]}"
run --render "$work/cube.exr" --projection cubemap --width 64 "${S[@]}"
run --render "$work/fish.exr" --render "$work/fish.png" --projection fisheye --width 128 "${S[@]}"
oiiotool --info -v "$work/eq.exr" >"$work/info" 2>&1
grep -q '256 x  128' "$work/info" || fail "equirect is not 256 x 128: $(head -2 "$work/info")"
grep -q 'textureformat: "LatLong Environment"' "$work/info" || fail "oiiotool: equirect not a LatLong Environment: $(cat "$work/info")"
# The sun in photometric units (the default, issue 32): the solar spectrum's lux-weighted RGB, its unit named.
grep -qE 'vksky:sunIlluminance: 1[0-9]{5}(\.[0-9]*)?, 1[0-9]{5}' "$work/info" || fail "oiiotool: no sun illuminance: $(cat "$work/info")"
grep -q 'vksky:sunIlluminanceUnits: "lx' "$work/info" || fail "oiiotool: the sun's unit is not named lx: $(cat "$work/info")"
oiiotool --info -v "$work/cube.exr" >"$work/info" 2>&1
grep -q '64 x  384' "$work/info" || fail "cube is not 64 x 384: $(head -2 "$work/info")"
grep -q 'textureformat: "CubeFace Environment"' "$work/info" || fail "oiiotool: cube not a CubeFace Environment: $(cat "$work/info")"
oiiotool --info -v "$work/fish.exr" >"$work/info" 2>&1
grep -q 'vksky:projection: "fisheye"' "$work/info" || fail "fisheye: no projection attribute"
grep -q 'textureformat' "$work/info" && fail "fisheye claims an environment format: $(cat "$work/info")"
oiiotool --info "$work/eq.png" | grep -q '256 x  128' || fail "equirect PNG size"
$PY "$here/envmap_check.py" info "$work/eq.exr" "$work/cube.exr" || fail "envmap_check.py info"

# --- tiled == untiled (the EXR bit for bit; the PNG's auto exposure within one level) ---
# Half channels in both (--exr-type half): "within one step of the stored type" is a half's step, and auto picks the
# type by different rules for a streamed map (the sun above the horizon) and an image in memory (a value over half).
for p in "equirect --width 256" "cubemap --width 48" "perspective --width 200 --height 150 --no-bloom --render-scale 1"; do
    # shellcheck disable=SC2086
    set -- --projection $p "${S[@]}" --exr-type half
    run --render "$work/one.exr" --render "$work/one.png" "$@"
    VKSKY_TILE_PIXELS=3000 run --render "$work/bands.exr" --render "$work/bands.png" "$@"
    $PY "$here/envmap_check.py" same "$work/one.exr" "$work/bands.exr" 0 || fail "tiled EXR differs: $p"
    $PY "$here/envmap_check.py" same "$work/one.png" "$work/bands.png" 1 || fail "tiled PNG differs: $p"
done
# A perspective render over the budget warns that bloom is off (bands would show its seams).
VKSKY_TILE_PIXELS=3000 "$VKSKY" --validate --render "$work/p.exr" --width 100 --height 80 "${S[@]}" 2>"$work/stderr" ||
    fail "banded perspective: $(cat "$work/stderr")"
grep -q 'bloom is off' "$work/stderr" || fail "banded perspective: no note on bloom: $(cat "$work/stderr")"
grep -q '100 %' "$work/stderr" || fail "no progress lines on a banded render: $(cat "$work/stderr")"
VKSKY_TILE_PIXELS=3000 "$VKSKY" --validate --quiet --render "$work/p.exr" --width 100 --height 80 --no-bloom "${S[@]}" \
    2>"$work/stderr" || fail "--quiet banded render: exit $?"
[ -s "$work/stderr" ] && fail "--quiet still printed: $(cat "$work/stderr")"

# --- peak memory: 4096 x 2048 in 64-row bands vs in one band ---
# Not validated (issue 31, on purpose): the layer's own memory would be measured with the renderer's; the same
# banded and one-band paths ran validated above.
rss() { # prints the maximum resident set size in kB of vksky "$@"
    /usr/bin/time -v "$VKSKY" --quiet "$@" 2>"$work/time" >/dev/null || { fail "vksky $*: $(tail -3 "$work/time")"; echo 0; return; }
    sed -n 's/.*Maximum resident set size (kbytes): //p' "$work/time"
}
BIG=(--projection equirect --width 4096 --steps 4 --sky-mode skyview --render "$work/big.exr")
one=$(VKSKY_TILE_PIXELS=100000000 rss "${BIG[@]}")
banded=$(VKSKY_TILE_PIXELS=262144 rss "${BIG[@]}")
echo "peak RSS 4096x2048 equirect: one band ${one} kB, 64-row bands ${banded} kB"
# One band holds ~8.4 Mpixel of images and readback buffers (~290 MB); 64-row bands ~9 MB of them.
[ "$banded" -gt 0 ] && [ "$banded" -lt $((one - 200000)) ] || fail "banded peak RSS ${banded} kB not 200 MB below one band's ${one} kB"
[ "$banded" -lt 400000 ] || fail "banded peak RSS ${banded} kB over 400 MB"
oiiotool --info "$work/big.exr" | grep -q '4096 x 2048' || fail "big map size"

# --- Ctrl-C in a long render: stops between bands, exit 130, nothing left (neither the file nor its temporary) ---
mkdir "$work/sig"
VKSKY_TILE_PIXELS=16384 "$VKSKY" --validate --render "$work/sig/s.exr" --render "$work/sig/s.png" --projection equirect \
    --width 4096 2>"$work/stderr" &
pid=$!
for _ in $(seq 1 300); do ls -A "$work/sig" | grep -q tmp && break; sleep 0.1; done
kill -INT $pid
wait $pid
rc=$?
[ $rc -eq 130 ] || fail "interrupted render: exit $rc, expected 130 ($(cat "$work/stderr"))"
grep -q 'stopped by SIGINT' "$work/stderr" || fail "interrupted render: no message: $(cat "$work/stderr")"
[ -z "$(ls -A "$work/sig")" ] || fail "interrupted render left files: $(ls -A "$work/sig")"

# --- bad input and notes ---
"$VKSKY" --render "$work/bad.exr" --projection globe 2>"$work/stderr"
rc=$?
[ $rc -eq 2 ] && [ "$(wc -l <"$work/stderr")" -eq 1 ] && grep -q 'equirect, cubemap or fisheye' "$work/stderr" ||
    fail "--projection globe: exit $rc, stderr: $(cat "$work/stderr")"
[ -e "$work/bad.exr" ] && fail "--projection globe wrote a file"
"$VKSKY" --validate --render "$work/n.exr" --projection equirect --width 64 --yaw 30 --height 99 --steps 4 2>"$work/stderr" ||
    fail "equirect with --yaw: $(cat "$work/stderr")"
grep -q 'ignores --yaw, --pitch and --fov' "$work/stderr" || fail "no note about --yaw: $(cat "$work/stderr")"
grep -q -- '--height ignored' "$work/stderr" || fail "no note about --height: $(cat "$work/stderr")"
"$VKSKY" --projection equirect --width 64 --sun-azimuth 90 --sun-elevation 0 --dump-scene >"$work/scene.json" 2>"$work/stderr" ||
    fail "--dump-scene with equirect"
grep -q 'sun direction 0.000000 0.000000 1.000000' "$work/stderr" ||
    fail "--dump-scene: sun at azimuth 90 on the horizon is not +Z: $(cat "$work/stderr")"
# The sun reaching the camera: all of it above the atmosphere, none where the planet hides it (1 degree below the
# horizontal from 1 m: the horizon dips 0.03 degrees).
"$VKSKY" --projection equirect --width 64 --altitude 200 --sun-elevation 5 --dump-scene 2>"$work/space.err" >/dev/null ||
    fail "--dump-scene from space: exit $?"
sed -n 's/.*illuminance \(.*\) at the top of the atmosphere, \(.*\) at the camera.*/\1|\2/p' "$work/space.err" |
    awk -F'|' '{ ok = $1 == $2 && $1 != "" } END { exit !ok }' ||
    fail "--dump-scene from space: sun at the camera is not the full illuminance"
"$VKSKY" --projection equirect --width 64 --sun-elevation -1 --dump-scene 2>"$work/below.err" >/dev/null ||
    fail "--dump-scene, sun below the horizon: exit $?"
grep -q ' 0 0 0 at the camera' "$work/below.err" ||
    fail "--dump-scene: a sun below the horizon reaches the camera"

[ $fails -eq 0 ] && echo "envmap_test: ok" || echo "envmap_test: $fails failure(s)"
[ $fails -eq 0 ]
