#!/usr/bin/env bash
# Scene files (--scene, --dump-scene; src/app/scene/scene*.c, scenes/README.md):
#  1. every shipped scene (scenes/*.json) renders validation-clean (--validate: any validation message exits 1),
#     writes its file and prints nothing on stderr; its --dump-scene loads back to the same dump, and the dump
#     renders the very same image; earth-clear.json is the defaults;
#  2. flags override scene fields wherever they stand (the dump shows the override); a --quality flag replaces
#     the scene's quality section; a dump with many overrides round-trips too; extra species and layer profiles
#     round-trip, an extra species copying ozone renders as doubled ozone, extreme profiles render finite pixels;
#  3. every malformed scene (tests/scenes_bad/*.json, and a few made here) and every bad value of the new flags
#     exits 2 with exactly one line on stderr naming the field (or file:line:column), and leaves no file behind;
#  4. the Mars sky (colour only): butterscotch by day (R > B), and bluer near the sun at sunset than at noon.
# Usage: scene_test.sh VKSKY EXR_PROBE [SCENES_DIR] [BAD_SCENES_DIR]
set -u
VKSKY=${1:?usage: scene_test.sh path/to/vksky path/to/exr_probe [scenes dir] [bad scenes dir]}
PROBE=${2:?usage: scene_test.sh path/to/vksky path/to/exr_probe [scenes dir] [bad scenes dir]}
PIXELS=$(dirname "$PROBE")/exr_pixels   # built beside exr_probe (tests/CMakeLists.txt): EXR pixels bit for bit
here=$(cd "$(dirname "$0")" && pwd)
SCENES=${3:-$here/../scenes}
BAD=${4:-$here/scenes_bad}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The LUT cache on in the test's own directory: a scene and its dump render the same LUT inputs twice, and the
# checks are about the scene files, not the LUT passes; a dump that lost a LUT input keys other LUTs and renders
# them afresh (tests/lib/own_lut_cache.sh).
# shellcheck source=lib/own_lut_cache.sh
source "$(dirname "$0")/lib/own_lut_cache.sh"
own_lut_cache "$work"
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
SMALL=(--width 64 --height 36 --validate)

# ---- 1. shipped scenes ------------------------------------------------------------------------------------
shipped=0
for scene in "$SCENES"/*.json; do
    name=$(basename "$scene" .json)
    shipped=$((shipped + 1))
    "$VKSKY" --scene "$scene" "${SMALL[@]}" --render "$work/$name.exr" --render "$work/$name.png" \
        >"$work/out" 2>"$work/err"
    rc=$?
    [ $rc -eq 0 ] || fail "$name: render exited $rc: $(head -c 600 "$work/err")"
    # Nothing on stderr but the auto-exposed PNG's one informational line (docs/units.md: the metered EV100).
    grep -v '^vksky: auto exposure: EV100 [-0-9.]* (log-average luminance .* metered on the GPU)$' "$work/err" \
        >"$work/err.rest"
    [ ! -s "$work/err.rest" ] || fail "$name: render printed on stderr: $(head -c 600 "$work/err.rest")"
    grep -q '^vksky: auto exposure: EV100' "$work/err" || fail "$name: the auto-exposed PNG did not say its EV100"
    [ -s "$work/$name.exr" ] && [ -s "$work/$name.png" ] || fail "$name: render wrote no image"
    if ! "$VKSKY" --scene "$scene" --dump-scene >"$work/$name.dump.json" 2>"$work/err" || [ -s "$work/err" ]; then
        fail "$name: --dump-scene failed: $(cat "$work/err")"
        continue
    fi
    "$VKSKY" --scene "$work/$name.dump.json" --dump-scene >"$work/$name.dump2.json" 2>"$work/err" ||
        fail "$name: its dump does not load: $(cat "$work/err")"
    cmp -s "$work/$name.dump.json" "$work/$name.dump2.json" ||
        fail "$name: dump -> load -> dump differs: $(diff "$work/$name.dump.json" "$work/$name.dump2.json" | head -5)"
    "$VKSKY" --scene "$work/$name.dump.json" "${SMALL[@]}" --render "$work/$name.again.exr" 2>"$work/err" ||
        fail "$name: the dump does not render: $(cat "$work/err")"
    # The pixels bit for bit (the files' headers differ by the command line they record), and the same effective
    # scene in both headers.
    "$PIXELS" same "$work/$name.exr" "$work/$name.again.exr" || fail "$name: the dump renders a different image"
    cmp -s <("$PIXELS" attr "$work/$name.exr" vksky:scene) <("$PIXELS" attr "$work/$name.again.exr" vksky:scene) ||
        fail "$name: the dump's render records another scene"
done
[ $shipped -ge 4 ] || fail "expected at least 4 shipped scenes in $SCENES, found $shipped"
# (the dump to a file first: a pipe would hide vksky's exit status)
"$VKSKY" --dump-scene >"$work/defaults.raw" || fail "--dump-scene: exit $?"
"$VKSKY" --scene "$SCENES/earth-clear.json" --dump-scene >"$work/clear.raw" || fail "--scene earth-clear --dump-scene: exit $?"
grep -v '"description"' "$work/defaults.raw" >"$work/defaults.json"
grep -v '"description"' "$work/clear.raw" >"$work/clear.json"
cmp -s "$work/defaults.json" "$work/clear.json" ||
    fail "earth-clear.json is not the defaults: $(diff "$work/defaults.json" "$work/clear.json" | head -6)"

# ---- 2. flags override the scene ---------------------------------------------------------------------------
# has DUMP_FILE "key" VALUE: the dump holds "key": VALUE (cJSON prints a tab after the colon).
has() { grep -qE "^[[:space:]]*\"$2\":[[:space:]]*$3,?\$" "$1"; }
dump() { "$VKSKY" "$@" --dump-scene >"$work/d.json" 2>"$work/err" || fail "dump of $* failed: $(cat "$work/err")"; }
MARS=$SCENES/mars.json
dump --scene "$MARS" --sun-elevation 33 --width 99 --pitch -5
has "$work/d.json" elevation_deg 33 && has "$work/d.json" width 99 && has "$work/d.json" pitch_deg -5 ||
    fail "flags after --scene do not override it: $(grep -E 'elevation_deg|width|pitch_deg' "$work/d.json")"
has "$work/d.json" ground_radius_km 3389.5 || fail "the Mars scene's planet did not load"
dump --sun-elevation 33 --width 99 --scene "$MARS"
has "$work/d.json" elevation_deg 33 && has "$work/d.json" width 99 ||
    fail "flags before --scene do not override it (the scene must load first)"
dump --scene "$MARS" --mie-scale 2 --sun-illuminance 1,2,3 --ground-albedo 0.1,0.2,0.3 --no-sun-disc --no-multiscatter \
     --mie-phase cornette-shanks --sun-angular-radius 0.5 --limb-darkening 0.25 --no-bloom --tonemap reinhard
has "$work/d.json" scattering "\[0\.09088, 0\.08378, 0\.06918\]" || fail "--mie-scale does not scale the scene's Mie"
has "$work/d.json" illuminance "\[1, 2, 3\]" || fail "--sun-illuminance"
has "$work/d.json" ground_albedo "\[0\.1, 0\.2, 0\.3\]" || fail "--ground-albedo"
has "$work/d.json" disc false && has "$work/d.json" multiple_scattering false && has "$work/d.json" bloom false ||
    fail "--no-sun-disc / --no-multiscatter / --no-bloom"
has "$work/d.json" model '"cornette-shanks"' && has "$work/d.json" angular_radius_deg 0.5 &&
    has "$work/d.json" limb_darkening 0.25 && has "$work/d.json" tonemap '"reinhard"' ||
    fail "--mie-phase / --sun-angular-radius / --limb-darkening / --tonemap"
cp "$work/d.json" "$work/many.json"
"$VKSKY" --scene "$work/many.json" --dump-scene >"$work/many2.json" 2>"$work/err" && cmp -s "$work/many.json" "$work/many2.json" ||
    fail "a dump with overrides does not round-trip: $(cat "$work/err"; diff "$work/many.json" "$work/many2.json" | head -5)"
# Extra species and general layer profiles: a scene with both round-trips through --dump-scene, renders
# validation-clean, and renders what the equivalent built-in species render (an extra species copying ozone's
# absorption and tent = ozone doubled, --ozone-scale 2; compared on the centre pixel).
cat >"$work/extra.json" <<'EOF'
{"species": {"ozone_copy": {"absorption": [0.650e-3, 1.881e-3, 0.085e-3],
                            "density": {"profile": "layers", "layers": [
                              {"width_km": 25, "linear_term_per_km": 0.06666666666666667, "constant_term": -0.6666666666666667},
                              {"linear_term_per_km": -0.06666666666666667, "constant_term": 2.6666666666666665}]}},
             "haze_layer": {"scattering": [1e-3, 1e-3, 1e-3],
                            "density": {"layers": [{"width_km": 1, "constant_term": 1}, {"constant_term": 0}]}}},
 "sun": {"elevation_deg": 10}, "camera": {"pitch_deg": 4, "yaw_deg": 180}}
EOF
"$VKSKY" --scene "$work/extra.json" --dump-scene >"$work/extra.d1.json" 2>"$work/err" || fail "extra species: $(cat "$work/err")"
"$VKSKY" --scene "$work/extra.d1.json" --dump-scene >"$work/extra.d2.json" 2>"$work/err" || fail "extra species dump: $(cat "$work/err")"
cmp -s "$work/extra.d1.json" "$work/extra.d2.json" || fail "extra species: dump -> load -> dump differs"
grep -q '"ozone_copy"' "$work/extra.d1.json" && grep -q '"haze_layer"' "$work/extra.d1.json" ||
    fail "extra species missing from the dump"
[ "$(grep -c '"profile":[[:space:]]*"tent"' "$work/extra.d1.json")" -eq 2 ] ||
    fail "the tent written as layers is not dumped as a tent"
"$VKSKY" --scene "$work/extra.json" "${SMALL[@]}" --render "$work/extra.exr" 2>"$work/err" ||
    fail "extra species render: $(cat "$work/err")"
[ ! -s "$work/err" ] || fail "extra species render printed: $(cat "$work/err")"
cat >"$work/ozone_copy.json" <<'EOF'
{"species": {"ozone_copy": {"absorption": [0.650e-3, 1.881e-3, 0.085e-3],
                            "density": {"profile": "tent", "center_km": 25, "half_width_km": 15}}}}
EOF
ODD=(--width 65 --height 37 --no-bloom --validate --sun-elevation 10 --pitch 4 --yaw 180)
"$VKSKY" --scene "$work/ozone_copy.json" "${ODD[@]}" --render "$work/copy.exr" 2>"$work/err" ||
    fail "ozone copy render: $(cat "$work/err")"
"$VKSKY" "${ODD[@]}" --ozone-scale 2 --render "$work/doubled.exr" 2>"$work/err" || fail "doubled ozone: $(cat "$work/err")"
"$VKSKY" "${ODD[@]}" --render "$work/single.exr" 2>"$work/err" || fail "single ozone: $(cat "$work/err")"
a=$("$PROBE" "$work/copy.exr" 32 18); b=$("$PROBE" "$work/doubled.exr" 32 18); c0=$("$PROBE" "$work/single.exr" 32 18)
awk -v a="$a" -v b="$b" -v c="$c0" 'BEGIN { split(a, x, " "); split(b, y, " "); split(c, z, " "); d = 0; e = 0
    for (i = 1; i <= 3; ++i) { r = (x[i] - y[i]) / y[i]; if (r < 0) r = -r; if (r > d) d = r
                               q = (y[i] - z[i]) / y[i]; if (q < 0) q = -q; if (q > e) e = q }
    exit !(d < 2e-3 && e > 0.01) }' ||
    fail "an extra species copying ozone does not render as doubled ozone: copy $a, doubled $b, single $c0"

# Extreme layer profiles (overflowing exponentials, steep linear terms, a zero-width layer 0, a profile that is 0
# everywhere) render finite, non-negative pixels everywhere, validation-clean, from the ground and from space.
extreme=0
for prof in '{"layers": [{"exp_term": 1000, "exp_scale_per_km": 1000}]}' \
            '{"layers": [{"exp_term": -1000, "exp_scale_per_km": 1000, "constant_term": 1000}]}' \
            '{"layers": [{"width_km": 0, "constant_term": 1}, {"linear_term_per_km": -1000, "constant_term": 1000}]}' \
            '{"layers": [{"width_km": 1000, "exp_term": 1, "exp_scale_per_km": -1000}, {"constant_term": 5}]}' \
            '{"layers": [{"constant_term": -1}]}'; do
    for alt in 0 500; do
        extreme=$((extreme + 1))
        printf '{"species": {"mie": {"density": %s}, "gas": {"absorption": [1e-3, 1e-3, 1e-3], "density": %s}},
                 "camera": {"altitude_km": %s, "pitch_deg": -20}}' "$prof" "$prof" "$alt" >"$work/extreme.json"
        "$VKSKY" --scene "$work/extreme.json" --width 16 --height 9 --validate --render "$work/extreme.exr" 2>"$work/err" ||
            { fail "extreme profile $prof at $alt km: $(head -c 300 "$work/err")"; continue; }
        "$PROBE" "$work/extreme.exr" $(for y in $(seq 0 8); do for x in $(seq 0 15); do echo "$x $y"; done; done) |
            awk '{ for (i = 1; i <= 3; ++i) if (!($i + 0 == $i && $i >= 0 && $i < 1e30)) bad = 1 } END { exit bad }' ||
            fail "extreme profile $prof at $alt km: a NaN, Inf or negative pixel"
    done
done
[ $extreme -eq 10 ] || fail "extreme profiles: $extreme renders"

# Quality: the scene's knobs override its preset; --quality replaces both; knob flags override everything.
# (Compared with the same choice made by flags alone, so that the test does not copy the preset table.)
cat >"$work/q.json" <<'EOF'
{"quality": {"preset": "low", "steps": 100, "lut_format": "f32"}}
EOF
same_dump() {   # same_dump "what" "args A" "args B": the two dumps are equal but for the description
    local what=$1 a b
    read -r -a a <<<"$2"; read -r -a b <<<"$3"
    "$VKSKY" "${a[@]}" --dump-scene >"$work/a.raw" 2>&1 || fail "$what: --dump-scene $2: exit $?"
    "$VKSKY" "${b[@]}" --dump-scene >"$work/b.raw" 2>&1 || fail "$what: --dump-scene $3: exit $?"
    grep -v '"description"' "$work/a.raw" >"$work/a.json"
    grep -v '"description"' "$work/b.raw" >"$work/b.json"
    cmp -s "$work/a.json" "$work/b.json" || fail "$what: $(diff "$work/a.json" "$work/b.json" | head -8)"
}
same_dump "a scene's knobs must override its preset" "--scene $work/q.json" "--quality low --steps 100 --lut-format f32"
same_dump "--quality must replace the scene's quality section" "--scene $work/q.json --quality high" "--quality high"
dump --steps 7 --scene "$work/q.json" --quality high
has "$work/d.json" steps 7 || fail "--steps must override --quality and the scene"
"$VKSKY" --scene "$work/q.json" --max-error 1 --dump-scene >"$work/d.json" 2>"$work/err" ||
    fail "--max-error with a scene that names a preset: $(cat "$work/err")"
grep -q "picked" "$work/err" && ! grep -q "picked" "$work/d.json" || fail "--max-error's note must go to stderr with --dump-scene"
"$VKSKY" --scene "$work/d.json" --dump-scene >/dev/null 2>&1 || fail "the dump after --max-error is not a scene"
"$VKSKY" --trace-passes --dump-scene >/dev/null 2>&1 || fail "--trace-passes is not accepted"

# ---- 3. errors: exit 2, one line naming the field, nothing written ---------------------------------------
# expect_bad "what" "expected text in stderr" args...
expect_bad() {
    local what=$1 needle=$2; shift 2
    rm -f "$work/bad.exr" "$work"/.bad.exr.* 2>/dev/null
    "$VKSKY" "$@" >"$work/stdout" 2>"$work/stderr"
    local rc=$?
    [ $rc -eq 2 ] || fail "$what: exit status $rc, expected 2 (stderr: $(head -c 400 "$work/stderr"))"
    [ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "$what: expected exactly one line on stderr, got: $(head -c 800 "$work/stderr")"
    grep -qF -- "$needle" "$work/stderr" || fail "$what: stderr does not mention '$needle': $(cat "$work/stderr")"
    [ ! -s "$work/stdout" ] || fail "$what: printed on stdout: $(head -c 200 "$work/stdout")"
    [ -z "$(ls -A "$work" | grep -e 'bad\.exr')" ] || fail "$what: left a file behind: $(ls -A "$work" | grep bad)"
}
R=(--render "$work/bad.exr" "${SMALL[@]}")
bad_scene() { expect_bad "$1" "$2" --scene "$BAD/$1.json" "${R[@]}"; }
bad_scene syntax-line5 "syntax-line5.json:5:13: syntax error near '\"disc\": tru'"
bad_scene trailing-comma "trailing-comma.json:4:"
bad_scene unterminated "unterminated.json:4:1: syntax error: unexpected end of the file"
bad_scene empty "empty.json: empty file"
bad_scene top-array "top-array.json: the top level is an array; expected a JSON object"
bad_scene unknown-field "unknown-field.json: sun.elevaton_deg: unknown field; accepted: elevation_deg, azimuth_deg, illuminance, angular_radius_deg, limb_darkening, disc"
bad_scene unknown-top-field "clouds: unknown field; accepted: description, planet, species"
bad_scene species-name "species.Water Vapour: not a species name; an extra species is named with a-z, 0-9 and _"
bad_scene too-many-species "species.water_vapour: one species too many; vksky takes 2 beyond rayleigh, mie and ozone"
bad_scene extra-phase "species.dust: an extra species scatters with the Rayleigh (molecular) phase and takes no phase"
bad_scene extra-no-density "species.no2.density: missing; an extra species needs a density profile"
bad_scene wrong-type "camera.fov_deg: expected a number, got a string"
bad_scene wrong-type-bool "sun.disc: expected true or false, got a string"
bad_scene wrong-type-section "output: expected an object, got an array"
bad_scene out-of-range "camera.fov_deg: 0 is out of range; expected a number in [1, 170] (as --fov)"
bad_scene negative-coefficient "species.mie.scattering[1]: -0.001 is out of range; expected a number in [0, 1000]"
bad_scene top-below-ground "planet.atmosphere_top_km: the atmosphere top (6300 km) is not above the ground (6360 km)"
bad_scene mie-g-one "species.mie.phase.g: 1 is out of range; expected a number in [-0.999, 0.999] (as --mie-g)"
bad_scene huge-number "sun.illuminance[1]: not a finite number; expected a number in [0, 1e+06] (as --sun-illuminance)"
bad_scene rayleigh-absorption "species.rayleigh.absorption: not supported"
bad_scene ozone-scattering "species.ozone.scattering: not supported"
bad_scene unknown-profile "species.mie.density.profile: unknown profile 'gaussian'; expected exponential, tent or layers"
bad_scene profile-field "species.rayleigh.density.center_km: not a parameter of the exponential profile; it takes scale_height_km"
bad_scene layers-count "species.ozone.density.layers: 3 layers; expected 1 or 2"
bad_scene layer-field "species.mie.density.layers[1].scale_height_km: unknown field; accepted: width_km, exp_term, exp_scale_per_km, linear_term_per_km, constant_term"
bad_scene layer-range "species.rayleigh.density.layers[0].exp_scale_per_km: -10000 is out of range; expected a number in [-1000, 1000]"
bad_scene phase-model "species.mie.phase.model: unknown value 'rayleigh'; expected henyey-greenstein or cornette-shanks"
bad_scene array-length "planet.ground_albedo: expected 3 numbers, got 2"
bad_scene not-integer "output.width: 64.5 is not an integer; expected an integer in [1, 16384] (as --width)"
bad_scene duplicate-field "camera.pitch_deg: given twice"
bad_scene bad-preset "quality.preset: unknown value 'extreme'; expected low, medium, high, ultra, lesson or cpu"
bad_scene max-steps-below "quality.max_steps: max_steps 16 is below steps 64"
bad_scene not-square "quality.multiscatter_directions: 50 is not a perfect square"
# the medium per wavelength (issue 32, app/scene/scene_spectral.c)
bad_scene spectral-mie-both "spectral.mie: give either optical_depth_500 (with single_scattering_albedo) or scattering_550_per_km"
bad_scene spectral-unknown-law "spectral.rayleigh.law: unknown value 'penndorf'; expected bodhaine or rgb"
bad_scene spectral-negative-column "spectral.ozone.column_du: -3 is out of range; expected a number in [0, 10000]"
for f in "$BAD"/*.json; do   # every fixture is exercised above
    grep -qF "bad_scene $(basename "$f" .json) " "$0" || fail "fixture $(basename "$f") is not tested"
done
printf '{"sun": {"elevation_deg": 1}}\0' >"$work/nul.json"
expect_bad "NUL byte" "nul.json:1:30: a NUL byte" --scene "$work/nul.json" "${R[@]}"
printf '{"a\\nb": 1}' >"$work/ctl.json"
expect_bad "control character in a key" "ctl.json: a?b: unknown field" --scene "$work/ctl.json" "${R[@]}"
expect_bad "missing file" "--scene: cannot read '$work/nope.json': No such file or directory" --scene "$work/nope.json" "${R[@]}"
mkdir -p "$work/dir.json"
expect_bad "directory" "--scene: cannot read '$work/dir.json'" --scene "$work/dir.json" "${R[@]}"
rmdir "$work/dir.json"
expect_bad "two scenes" "--scene: given twice" --scene "$MARS" --scene "$MARS" "${R[@]}"
expect_bad "no scene file" "--scene: missing value" "${R[@]}" --scene
expect_bad "albedo count" "--ground-albedo: '0.5,0.5' is not R,G,B" "${R[@]}" --ground-albedo 0.5,0.5
expect_bad "albedo range" "--ground-albedo: 2 is out of range; expected a number in [0, 1]" "${R[@]}" --ground-albedo 0.5,0.5,2
expect_bad "albedo junk" "--ground-albedo: 'x' is not a number" "${R[@]}" --ground-albedo 0.5,x,0.5
expect_bad "albedo extra" "--ground-albedo" "${R[@]}" --ground-albedo 0.1,0.2,0.3,0.4
expect_bad "illuminance range" "--sun-illuminance: -1 is out of range" "${R[@]}" --sun-illuminance 20,-1,20
expect_bad "illuminance NaN" "--sun-illuminance: 'nan' is not a number" "${R[@]}" --sun-illuminance 20,nan,20
expect_bad "mie phase" "--mie-phase: unknown value 'mie'" "${R[@]}" --mie-phase mie
expect_bad "sun radius" "--sun-angular-radius: 0 is out of range; expected a number in [0.01, 10]" "${R[@]}" --sun-angular-radius 0
expect_bad "limb darkening" "--limb-darkening: 1.5 is out of range; expected a number in [0, 1]" "${R[@]}" --limb-darkening 1.5
expect_bad "no-sun-disc value" "--no-sun-disc: takes no value" "${R[@]}" --no-sun-disc=1
expect_bad "bad flag after a scene" "--fov" --scene "$MARS" "${R[@]}" --fov 0

# ---- 4. the Mars sky's colours (sky only; the sun disc stays out of the probed pixel, bloom is off) --------
# rgb ARGS...: render a 65x37 EXR of the Mars scene (the centre pixel (32, 18) lies on the view axis) and print
# the centre pixel's R G B.
rgb() {
    "$VKSKY" --scene "$MARS" --width 65 --height 37 --no-bloom --validate --render "$work/mars.exr" "$@" 2>"$work/err" ||
        { fail "Mars render $* failed: $(head -c 400 "$work/err")"; echo "0 0 1"; return; }
    "$PROBE" "$work/mars.exr" 32 18 || { fail "exr_probe failed on the Mars render $*"; echo "0 0 1"; }
}
# ratio "R G B" -> R/B
ratio() { echo "$1" | awk '{ printf "%.4f", ($3 > 0 ? $1 / $3 : 0) }'; }
gt() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a > b) }'; }
day=$(rgb --sun-elevation 45 --sun-azimuth 0 --yaw 180 --pitch 40)        # 40 deg up, away from the sun
side=$(rgb --sun-elevation 45 --sun-azimuth 0 --yaw 90 --pitch 40)        # 40 deg up, 90 deg from the sun
gt "$(ratio "$day")" 1.15 && gt "$(ratio "$side")" 1.15 ||
    fail "Mars day sky is not butterscotch (R/B > 1.15): away $day, side $side"
noon=$(rgb --sun-elevation 60 --sun-azimuth 0 --yaw 0 --pitch 55)         # 5 deg below a high sun
sunset=$(rgb --sun-elevation 1 --sun-azimuth 0 --yaw 0 --pitch 6)         # 5 deg above the setting sun
gt "$(ratio "$noon")" "$(ratio "$sunset")" ||
    fail "Mars sunset aureole is not bluer than noon's: R/B noon $(ratio "$noon") ($noon), sunset $(ratio "$sunset") ($sunset)"
# Validated and its exit statuses checked (issue 31: an empty probe gave the ratio 0, which passed).
earth=$("$VKSKY" --scene "$SCENES/earth-clear.json" --width 65 --height 37 --no-bloom --validate \
        --render "$work/earth.exr" --sun-elevation 45 --yaw 180 --pitch 40 2>"$work/err" &&
        "$PROBE" "$work/earth.exr" 32 18) || fail "Earth render or probe failed: $(head -c 400 "$work/err")"
[ "$(echo "$earth" | wc -w)" -ge 3 ] && gt "$(echo "$earth" | awk '{ print $3 }')" 0 ||
    fail "the Earth day sky probe gave no blue channel: '$earth'"
gt 1 "$(ratio "$earth")" || fail "the Earth day sky is not blue (R/B < 1): $earth"
echo "scene_test: Mars R/B: day away $(ratio "$day"), side $(ratio "$side"), near the sun at noon $(ratio "$noon"), at sunset $(ratio "$sunset"); Earth day $(ratio "$earth")"

if [ $fails -ne 0 ]; then echo "scene_test: $fails failure(s)"; exit 1; fi
echo "scene_test: ok ($shipped shipped scenes)"
