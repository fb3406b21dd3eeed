#!/usr/bin/env bash
# tests/sequences_test.sh VKSKY EXR_PIXELS: sequences (--animate, --frame-count, --frame-range) and the EXR header.
#  1. A sequence split into two --frame-range jobs gives the same files, byte for byte, as the whole one.
#  2. Frame i is what a single render with the animated flags at frame i's values makes (bit-identical pixels, the
#     same --dump-scene text in the header): values chosen exactly representable (0:40 over 5 frames).
#  3. LUTs are recomputed only when their inputs change: a camera/sun animation computes them once (the progress
#     summary and --trace-passes's count of transmittance_lut passes agree), a medium animation every frame.
#  4. The header: chromaticities (Rec.709, D65), owner/software with the version, the command line, the frame number;
#     worldToNDC puts the sun's direction where the rendered disc is (within 1 px) and worldToCamera maps the view
#     axis to +z.
#  5. `--scene FRAME.exr` renders the same pixels (Earth with an angle sun, Mars, a date sun animated over fractional
#     seconds).
#  6. Bad values: one line on stderr, exit 2, no file.
#  7. --max-error in a sequence reports the pick its frames render with (issue 25): the printed configuration's knobs,
#     from its definition (QUALITY_KNOBS), are what every frame's header records; --quiet prints nothing.
set -u
VKSKY=${1:?usage: sequences_test.sh VKSKY EXR_PIXELS QUALITY_KNOBS}
PIX=${2:?}
KNOBS=${3:?}
export VKSKY_VALIDATION=1   # every render under the validation layer; any message fails it
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
cd "$work" || exit 1
version=$("$VKSKY" --version) || fail "--version: exit $?"
version=$(awk '{print $2}' <<<"$version")

# 1. Whole and split. The same command line in three directories (the header records it; --frame-range is left out).
SEQ=(--width 48 --height 32 --animate sun-elevation=-2:30 --animate yaw=0:50 --frame-count 6 --render 'f_%03d.exr'
     --render 'f_%03d.png')
mkdir whole split
(cd whole && "$VKSKY" "${SEQ[@]}" 2>../whole.err) || fail "the whole sequence failed: $(cat whole.err)"
(cd split && "$VKSKY" "${SEQ[@]}" --frame-range 0:2 2>../split1.err && "$VKSKY" "${SEQ[@]}" --frame-range=3:5 \
    2>../split2.err) || fail "a split job failed: $(cat split1.err split2.err)"
[ "$(ls whole | wc -l)" -eq 12 ] || fail "the whole sequence wrote $(ls whole | wc -l) files; expected 12"
for f in whole/*; do
    cmp -s "$f" "split/${f#whole/}" || fail "split/${f#whole/} differs from $f"
done
grep -q '^vksky: frame 4 (5 of 6; 2/3 of this job): f_004.exr' split2.err || fail "no progress line 'frame 4 (5 of 6...)'"

# 2. Frame 2 of 0:40 x 5 is a single render at 20. A named preset: under auto a sequence picks once for every class its
#    frames pass through, from the GPU table on any device (farm jobs agree), and a single render for its own class
#    from its device's table, so the two picks agree only by chance (they parted when the GPU table was re-measured).
COMMON=(--width 40 --height 30 --fov 70 --pitch 15 --quality medium)
"$VKSKY" "${COMMON[@]}" --animate sun-elevation=0:40 --animate yaw=0:80 --frame-count 5 --render 'g_%d.exr' 2>g.err \
    || fail "sequence g failed: $(cat g.err)"
"$VKSKY" "${COMMON[@]}" --sun-elevation 20 --yaw 40 --render single.exr 2>/dev/null || fail "single render failed"
"$PIX" same g_2.exr single.exr || fail "frame 2 differs from the single render with --sun-elevation 20 --yaw 40"
"$PIX" same g_1.exr single.exr >/dev/null && fail "frame 1 equals frame 2's single render (the animation did nothing)"
"$PIX" attr g_2.exr vksky:scene >g_2.json || fail "g_2.exr has no vksky:scene"
"$VKSKY" "${COMMON[@]}" --sun-elevation 20 --yaw 40 --dump-scene >single.json || fail "--dump-scene of the single render: exit $?"
cmp -s g_2.json single.json || fail "frame 2's vksky:scene is not the --dump-scene of the single render"

# 3. LUT recomputations.
#    RGB named: a sunset under auto renders spectral (32g), a pass per wavelength group, each with its own LUTs.
"$VKSKY" --width 32 --height 24 --animate yaw=0:90 --animate pitch=0:30 --animate fov=40:80 --animate exposure=-1:1 \
    --animate sun-elevation=5:25 --frame-count 4 --spectral 0 --render 'c_%d.exr' --trace-passes >c.out 2>c.err \
    || fail "camera animation failed: $(cat c.err)"
grep -q '^vksky: 4 frames rendered; LUTs computed 1 time$' c.err || fail "camera animation: $(tail -1 c.err); expected 1 computation"
[ "$(grep -c '^pass transmittance_lut$' c.out)" -eq 1 ] || fail "camera animation traced $(grep -c '^pass transmittance_lut$' c.out) transmittance passes; expected 1"
[ "$(grep -c 'LUTs reused$' c.err)" -eq 3 ] || fail "camera animation: frames 1-3 should reuse the LUTs"
"$VKSKY" --width 32 --height 24 --animate mie-scale=1:2 --frame-count 3 --render 'm_%d.exr' --trace-passes >m.out 2>m.err \
    || fail "medium animation failed: $(cat m.err)"
grep -q '^vksky: 3 frames rendered; LUTs computed 3 times$' m.err || fail "medium animation: $(tail -1 m.err); expected 3"
[ "$(grep -c '^pass transmittance_lut$' m.out)" -eq 3 ] || fail "medium animation traced $(grep -c '^pass transmittance_lut$' m.out) transmittance passes; expected 3"
"$VKSKY" --width 32 --height 24 --animate mie-scale=1.5:1.5 --frame-count 3 --render 'k_%d.exr' 2>k.err \
    || fail "constant medium animation failed"
grep -q 'LUTs computed 1 time$' k.err || fail "a constant medium animation recomputed the LUTs: $(tail -1 k.err)"

# 4. The header.
hdr=$(exrheader whole/f_004.exr 2>&1) || fail "exrheader cannot read whole/f_004.exr"
for want in 'red   (0.64 0.33)' 'green (0.3 0.6)' 'blue  (0.15 0.06)' 'white (0.3127 0.329)' \
            "owner (type string): \"vksky $version\"" "software (type string): \"vksky $version\"" \
            'worldToCamera (type m44f)' 'worldToNDC (type m44f)' 'vksky:frame (type int): 4' \
            "vksky:commandLine (type string): \"vksky ${SEQ[*]}\""; do
    grep -qF "$want" <<<"$hdr" || fail "whole/f_004.exr's header lacks: $want"
done
W=160 H=100
"$VKSKY" --width $W --height $H --fov 50 --yaw 30 --pitch 8 --sun-elevation 14 --sun-azimuth 47 --sun-angular-radius 0.6 \
    --no-bloom --exposure -6 --render sun.exr 2>/dev/null || fail "the sun render failed"
read -r sx sy < <("$PIX" sun sun.exr)
{ read -r px py; read -r _ cx cy cz; } < <("$PIX" project sun.exr 47 14)
awk -v sx="$sx" -v sy="$sy" -v px="$px" -v py="$py" 'BEGIN { exit !((sx - px)^2 + (sy - py)^2 <= 1.0) }' \
    || fail "worldToNDC puts the sun at ($px, $py); the rendered disc is at ($sx, $sy)"
read -r _ ax ay az < <("$PIX" project sun.exr 30 8 | tail -1)
awk -v x="$ax" -v y="$ay" -v z="$az" 'BEGIN { exit !(x^2 + y^2 < 1e-10 && (z - 1)^2 < 1e-10) }' \
    || fail "worldToCamera maps the view axis to ($ax, $ay, $az); expected (0, 0, 1)"
awk -v x="$cx" -v y="$cy" 'BEGIN { exit !(x > 0 && y > 0) }' || fail "the sun right of and above the view axis has camera ($cx, $cy)"

# 5. Round trips.
"$VKSKY" --scene whole/f_004.exr --render rt.exr 2>rt.err || fail "--scene whole/f_004.exr failed: $(cat rt.err)"
"$PIX" same rt.exr whole/f_004.exr || fail "--scene f_004.exr renders other pixels"
"$VKSKY" --scene mars --width 40 --height 24 --yaw 100 --render mars.exr 2>/dev/null || fail "--scene mars failed"
"$VKSKY" --scene mars.exr --render mars_again.exr 2>/dev/null || fail "--scene mars.exr failed"
"$PIX" same mars.exr mars_again.exr || fail "--scene mars.exr renders other pixels than the Mars render it came from"
PLACE=(--date 2026-06-21 --utc-offset 2 --latitude 46.2 --longitude 6.1 --yaw 60 --pitch 5)
"$VKSKY" "${PLACE[@]}" --width 40 --height 24 --animate time=5.123:5.9 --frame-count 3 --render 'd_%d.exr' 2>d.err \
    || fail "time animation failed: $(cat d.err)"
grep -q '"time":[[:space:]]*"05:' <("$PIX" attr d_1.exr vksky:scene) || fail "d_1.exr's scene has no 05:xx time"
[ "$("$PIX" attr d_0.exr vksky:scene | grep -c computed_elevation)" -eq 1 ] || fail "d_0.exr's scene lacks the computed sun"
"$PIX" same d_0.exr d_2.exr >/dev/null && fail "the sun did not move between 05:07 and 05:54"
for i in 0 1 2; do
    "$VKSKY" --scene "d_$i.exr" --render "drt_$i.exr" 2>/dev/null || fail "--scene d_$i.exr failed"
    "$PIX" same "drt_$i.exr" "d_$i.exr" || fail "--scene d_$i.exr renders other pixels"
done
grep -q 'capDate (type string): "2026:06:21 05:' <(exrheader d_0.exr) || fail "d_0.exr has no capDate"

# 7. --max-error's pick in a sequence: the frames' (the pick for every scene class they pass through: a sunset here,
# whose pick is not the default afternoon view's), not the un-animated base view's.
PICK=(--max-error 0.01 --animate sun-elevation=5:3 --frame-count 3 --width 48 --height 27 --render 'p_%d.exr')
"$VKSKY" "${PICK[@]}" >pick.out 2>pick.err || fail "--max-error sequence failed: $(cat pick.err)"
picked=$(sed -n "s/^vksky: --max-error 0.01: picked '\([^']*\)' for frames 0-2 .*/\1/p" pick.out)
[ "$(grep -c "picked '" pick.out)" -eq 1 ] && [ -n "$picked" ] ||
    fail "--max-error sequence: expected one 'picked ... for frames 0-2' line on stdout: $(cat pick.out)"
if [ -n "$picked" ] && "$KNOBS" "$picked" >want.knobs; then
    for i in 0 1 2; do
        "$PIX" attr "p_$i.exr" vksky:scene | sed -n '/"quality":/,/}/p' >scene.q || fail "p_$i.exr: no vksky:scene"
        while read -r key want; do
            got=$(sed -n "s/^[[:space:]]*\"$key\":[[:space:]]*//p" scene.q | tr -d '[]",')
            [ "$got" = "$want" ] || fail "--max-error printed '$picked' ($key $want); p_$i.exr's header records $key '$got'"
        done <want.knobs
    done
else
    fail "--max-error printed '$picked', which names no configuration"
fi
"$VKSKY" "${PICK[@]}" --quiet >quiet.out 2>quiet.err || fail "--max-error sequence --quiet failed: $(cat quiet.err)"
[ ! -s quiet.out ] || fail "--quiet still printed on stdout: $(cat quiet.out)"

# 6. Bad values: one line, exit 2, no file.
bad() {   # bad WHAT ARGS...
    local what=$1
    shift
    mkdir -p "$work/bad" && rm -f "$work/bad"/*
    (cd "$work/bad" && "$VKSKY" --width 16 --height 16 "$@" >out 2>err)
    local rc=$?
    local lines
    lines=$(wc -l <"$work/bad/err")
    [ $rc -eq 2 ] || fail "$what: exit $rc, expected 2 ($(cat "$work/bad/err"))"
    [ "$lines" -eq 1 ] || fail "$what: $lines lines on stderr, expected 1: $(cat "$work/bad/err")"
    [ "$(ls "$work/bad" | grep -v -x -e out -e err | wc -l)" -eq 0 ] || fail "$what: left files: $(ls "$work/bad")"
}
bad "pattern without %d" --frame-count 3 --render x.exr
bad "two %d" --frame-count 3 --render 'x_%d_%d.exr'
bad "%s in a pattern" --frame-count 3 --render 'x_%s.exr'
bad "range past the end" --frame-count 4 --frame-range 2:4 --render 'x_%d.exr'
bad "range without a count" --frame-range 1:1 --render 'x_%d.exr'
bad "empty range" --frame-count 4 --frame-range 3:2 --render 'x_%d.exr'
bad "malformed range" --frame-count 4 --frame-range 3 --render 'x_%d.exr'
bad "negative range" --frame-count 4 --frame-range -1:2 --render 'x_%d.exr'
bad "FROM-TO" --animate sun-elevation=1-2 --frame-count 2 --render 'x_%d.exr'
bad "FROM:TO words" --animate sun-elevation=a:b --frame-count 2 --render 'x_%d.exr'
bad "three numbers" --animate sun-elevation=1:2:3 --frame-count 2 --render 'x_%d.exr'
bad "no PARAM" --animate =1:2 --frame-count 2 --render 'x_%d.exr'
bad "no =" --animate sun-elevation --frame-count 2 --render 'x_%d.exr'
bad "unknown PARAM" --animate sun-height=1:2 --frame-count 2 --render 'x_%d.exr'
bad "non-numeric PARAM" --animate tonemap=1:2 --frame-count 2 --render 'x_%d.exr'
bad "PARAM fixed for a sequence" --animate width=16:32 --frame-count 2 --render 'x_%d.exr'
bad "FROM out of range" --animate sun-elevation=-100:10 --frame-count 2 --render 'x_%d.exr'
bad "time past midnight" --animate time=23:24 --frame-count 2 --render 'x_%d.exr' "${PLACE[@]}"
bad "time without a date" --animate time=5:6 --frame-count 2 --render 'x_%d.exr'
bad "angle animation with a date" --animate sun-elevation=1:2 --time 06:00 --frame-count 2 --render 'x_%d.exr' "${PLACE[@]}"
bad "frame count 0" --frame-count 0 --render 'x_%d.exr'
bad "animate without --render" --animate yaw=1:2 --frame-count 2 --bench 2
bad "a sequence of AOV renders" --aovs --frame-count 2 --render 'x_%d.exr'
"$PIX" plain plain.exr || fail "exr_pixels cannot write an EXR"
echo "not an image" >fake.exr
bad "--scene of an EXR without a scene" --scene "$work/plain.exr" --render x.exr
bad "--scene of a text file named .exr" --scene "$work/fake.exr" --render x.exr
[ $fails -eq 0 ] && echo "sequences: all checks pass"
exit $((fails > 0))
