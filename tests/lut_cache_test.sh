#!/usr/bin/env bash
# tests/lut_cache_test.sh VKSKY: the LUT cache on disk (sky/lut_cache.h, issue 27).
#  1. A first run computes the LUTs and writes $XDG_CACHE_HOME/vksky/luts-<UUID>-<driver>-<key>.bin, read here
#     independently of vksky: our header (magic, version, sizes, the FNV-1a checksum recomputed), then a payload of
#     the transmittance LUT (256 x 64 RGBA half floats: every texel finite, RGB in [0, 1], a transmittance, some near 1) and the
#     multi-scattering LUT. A second run uploads them (--timings: "hit"; --trace-passes: no LUT pass), its frame
#     is faster than the first's, and its EXR and PNG equal the first's byte for byte.
#  2. A corrupt, truncated, foreign-key (key byte changed, checksum made good) or alien file: the LUTs computed,
#     one note at most, the same images, and the file rewritten good (the next run hits).
#  3. An unwritable cache directory still renders (one "not saved" note); --no-cache neither reads nor writes.
#  4. VKSKY_LUT_CACHE=ro: a hit uploads without touching the file, a miss computes and writes no LUT file.
#  7. A spectral image: one file per wavelength group, all hit by a warm run; an animated medium stops at 16 files.
#  8. The sun disc is no part of the key (the LUT passes never read it): one file for frames with and without it.
#  9. A sequence through the readback ring stores its first frame's LUTs; a warm one hits them.
# 10. --composite and --aovs store their LUTs (RGB: one file; spectral: one per group); warm runs upload them.
set -u
VKSKY=${1:?usage: lut_cache_test.sh VKSKY GEN_COMPOSITE_SCENE}
GEN=${2:?usage: lut_cache_test.sh VKSKY GEN_COMPOSITE_SCENE}
export VKSKY_VALIDATION=1   # every render under the validation layer; any message fails it
unset VKSKY_LUT_CACHE       # the suite turns the LUT cache off (tests/CMakeLists.txt): this test is about it
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
cd "$work" || exit 1
export HOME="$work/home" XDG_CACHE_HOME="$work/xdg"
ARGS=(--width 16 --height 16 --multiscatter-dirs 16)

# check FILE: "ok" or why not, from the file's bytes alone.
check() {
    python3 - "$1" <<'PY'
import struct, sys, math
b = open(sys.argv[1], 'rb').read()
def fnv(d):
    h = 0xcbf29ce484222325
    for c in d: h = ((h ^ c) * 0x100000001b3) & 0xffffffffffffffff
    return h
if b[:8] != b'VKSKYBC1': print('magic'); sys.exit()
ver, = struct.unpack_from('<I', b, 8)
ks, ps, s = struct.unpack_from('<QQQ', b, 16)
if ver != 1: print('version'); sys.exit()
if 40 + ks + ps != len(b): print('size'); sys.exit()
if fnv(b[40:]) != s: print('checksum'); sys.exit()
tw, th = 256, 64
if ps <= tw * th * 8: print('payload too small for a 256x64 RGBA16F transmittance LUT'); sys.exit()
if (ps - tw * th * 8) % (32 * 32 * 8): print('payload: not a transmittance LUT plus 32x32 RGBA16F parts'); sys.exit()
t = struct.unpack_from('<%de' % (tw * th * 4), b, 40 + ks)
rgb = [v for i, v in enumerate(t) if i % 4 != 3]
if not all(math.isfinite(v) and 0.0 <= v <= 1.0 for v in rgb): print('transmittance outside [0, 1]'); sys.exit()
if max(rgb) < 0.9: print('no transmittance near 1 (the zenith from the top of the atmosphere)'); sys.exit()
print('ok')
PY
}
# rekey FILE: change a byte of the key and make the checksum good again (a file under this key's name that holds
# another key).
rekey() {
    python3 - "$1" <<'PY'
import struct, sys
p = sys.argv[1]; b = bytearray(open(p, 'rb').read())
b[40 + 40] ^= 0x01
h = 0xcbf29ce484222325
for c in b[40:]: h = ((h ^ c) * 0x100000001b3) & 0xffffffffffffffff
struct.pack_into('<Q', b, 32, h)
open(p, 'wb').write(bytes(b))
PY
}
notes() { grep -c 'cache file' "$1"; }
# render NAME [FLAGS...]: NAME/out.exr and out.png (the same names every time: the EXR header records the command
# line), --timings and --trace-passes into NAME.err / NAME.out.
render() {
    local name=$1; shift
    mkdir -p "$name" && (cd "$name" && "$VKSKY" "${ARGS[@]}" --render out.exr --render out.png --timings \
        --trace-passes "$@" >../"$name".out 2>../"$name".err)
}
same() { cmp -s cold/out.png "$1/out.png" && cmp -s cold/out.exr "$1/out.exr"; }
state() { sed -n 's/^  LUT cache  //p' "$1.err"; }
frame_ms() { awk '$1 == "frame" { print $2 }' "$1.err"; }

# 1. Cold, then warm.
render cold || fail "first run failed: $(cat cold.err)"
files=("$XDG_CACHE_HOME"/vksky/luts-*.bin)
cache=${files[0]}
[ ${#files[@]} -eq 1 ] && [ -f "$cache" ] || fail "expected one LUT cache file, found: ${files[*]}"
[ "$(check "$cache")" = ok ] || fail "the LUT cache file does not read back: $(check "$cache")"
[ "$(state cold)" = "computed and stored" ] || fail "first run: LUT cache '$(state cold)'"
grep -q '^pass transmittance_lut$' cold.out || fail "first run: no transmittance_lut pass"
[ "$(notes cold.err)" -eq 0 ] || fail "a first run printed a note: $(cat cold.err)"
cp "$cache" good.bin
touch -d '2000-01-01' "$cache"
render warm || fail "warm run failed: $(cat warm.err)"
[ "$(state warm)" = "hit: uploaded, not computed" ] || fail "second run: LUT cache '$(state warm)'"
! grep -Eq '^pass (transmittance|multiscatter|ground_irradiance)_lut$' warm.out ||
    fail "second run: LUT passes traced: $(grep '_lut$' warm.out)"
grep -q '^pass lut_cache_upload$' warm.out || fail "second run: no lut_cache_upload pass"
[ "$(notes warm.err)" -eq 0 ] || fail "a warm run printed a note: $(cat warm.err)"
[ "$(stat -c %Y "$cache")" = "$(date -d '2000-01-01' +%s)" ] || fail "a warm run rewrote the LUT cache file"
same warm || fail "the warm run's images differ from the cold run's"
awk -v c="$(frame_ms cold)" -v w="$(frame_ms warm)" 'BEGIN { exit !(w < c) }' ||
    fail "the warm frame ($(frame_ms warm) ms) is not faster than the cold one ($(frame_ms cold) ms)"
echo "frame (submit to fence): cold $(frame_ms cold) ms, warm $(frame_ms warm) ms"

# 2. Bad files: computed, at most one note, the same images, the file rewritten good.
bad_case() {   # NAME EXPECTED-WORDS (in the note)
    render "$1" || fail "$1: the render failed: $(cat "$1.err")"
    [ "$(notes "$1.err")" -eq 1 ] || fail "$1: expected one note, got: $(cat "$1.err")"
    grep -q "cache file .*luts-.*: .*$2.*; ignored" "$1.err" || fail "$1: the note does not say '$2 ... ignored': $(cat "$1.err")"
    [ "$(state "$1")" = "computed and stored" ] || fail "$1: LUT cache '$(state "$1")'"
    same "$1" || fail "$1: the images differ"
    cmp -s "$cache" good.bin || fail "$1: the file was not rewritten as the good one ($(check "$cache"))"
}
cp good.bin "$cache" && printf '\x5a' | dd of="$cache" bs=1 seek=1000 conv=notrunc status=none
bad_case corrupt "corrupt"
head -c 5000 good.bin >"$cache"
bad_case truncated "truncated"
cp good.bin "$cache" && rekey "$cache"
[ "$(check "$cache")" = ok ] || fail "rekey broke the file's own checks"
bad_case foreign "other inputs"
printf 'P6 1 1 255 xyz' >"$cache"
bad_case alien "not a vksky cache file"
render again || fail "run after the bad files failed"
[ "$(state again)" = "hit: uploaded, not computed" ] || fail "the rewritten file was not hit: '$(state again)'"

# 3. Unwritable directory (a file where the directory should be), --no-cache.
touch notadir
XDG_CACHE_HOME="$work/notadir" render ro || fail "unwritable cache dir: the render failed: $(cat ro.err)"
same ro || fail "unwritable cache dir: the images differ"
[ "$(grep -c 'cache file not saved' ro.err)" -eq 1 ] && [ "$(state ro)" = "computed, not stored" ] ||
    fail "unwritable cache dir: expected one 'not saved' note for the LUTs: $(cat ro.err)"
XDG_CACHE_HOME="$work/fresh" render fresh --no-cache || fail "--no-cache failed"
[ ! -e "$work/fresh/vksky" ] || fail "--no-cache wrote into the cache directory"
touch -d '2000-01-01' "$cache"
render nocache --no-cache || fail "--no-cache with a warm cache failed"
[ "$(state nocache)" = off ] && grep -q '^pass transmittance_lut$' nocache.out ||
    fail "--no-cache read the LUT cache: '$(state nocache)'"
[ "$(stat -c %Y "$cache")" = "$(date -d '2000-01-01' +%s)" ] || fail "--no-cache rewrote the LUT cache file"
cmp -s cold/out.png nocache/out.png || fail "--no-cache's PNG differs"

# 4. VKSKY_LUT_CACHE=ro (the readers of a ctest LUT fixture, tests/CMakeLists.txt): a hit uploads and leaves the
#    file alone; a miss computes the LUTs and writes no LUT file.
touch -d '2000-01-01' "$cache"
VKSKY_LUT_CACHE=ro render ro_hit || fail "VKSKY_LUT_CACHE=ro, warm: $(cat ro_hit.err)"
[ "$(state ro_hit)" = "hit: uploaded, not computed" ] || fail "VKSKY_LUT_CACHE=ro, warm: LUT cache '$(state ro_hit)'"
[ "$(stat -c %Y "$cache")" = "$(date -d '2000-01-01' +%s)" ] || fail "VKSKY_LUT_CACHE=ro rewrote the LUT cache file"
same ro_hit || fail "VKSKY_LUT_CACHE=ro, warm: the images differ"
XDG_CACHE_HOME="$work/ro_empty" VKSKY_LUT_CACHE=ro render ro_miss || fail "VKSKY_LUT_CACHE=ro, cold: $(cat ro_miss.err)"
grep -q '^pass transmittance_lut$' ro_miss.out || fail "VKSKY_LUT_CACHE=ro, cold: the LUTs were not computed"
! ls "$work"/ro_empty/vksky/luts-*.bin >/dev/null 2>&1 || fail "VKSKY_LUT_CACHE=ro, cold: a LUT cache file was written"
[ "$(notes ro_miss.err)" -eq 0 ] || fail "VKSKY_LUT_CACHE=ro, cold: a note: $(cat ro_miss.err)"
same ro_miss || fail "VKSKY_LUT_CACHE=ro, cold: the images differ"

# 6. The command line's single frame as a host of include/vksky.h (no --timings: headless_api.c): the library's
#    vksky_context_set_cache_directory + vksky_renderer_store_luts write the file on a miss and upload it on a hit.
api() {   # api NAME [FLAGS...]: one PNG through the API path, the pass trace into NAME.out
    local name=$1; shift
    mkdir -p "$name" && (cd "$name" && "$VKSKY" "${ARGS[@]}" --render out.png --trace-passes "$@" >../"$name".out \
        2>../"$name".err)
}
export XDG_CACHE_HOME="$work/api"
api api_cold --validate || fail "API path, cold: $(cat api_cold.err)"
ls "$XDG_CACHE_HOME"/vksky/luts-*.bin >/dev/null 2>&1 || fail "API path: no LUT cache file written on a miss"
api api_warm --validate || fail "API path, warm: $(cat api_warm.err)"
grep -q '^pass transmittance_lut$' api_cold.out || fail "API path, cold: the LUTs were not computed"
grep -q '^pass lut_cache_upload$' api_warm.out && ! grep -q '^pass transmittance_lut$' api_warm.out ||
    fail "API path, warm: the LUTs were not uploaded from the cache"
cmp -s api_cold/out.png api_warm/out.png || fail "API path: the warm PNG differs from the cold one"

# 7. A spectral image's wavelength groups take turns on one renderer (app/runs/spectral_host.c): a cold run writes one
#    file per group (24 wavelengths, a sky-only view without bloom: four to a pass, 6 groups; with the horizon in the
#    frame, or with bloom, three to a pass, 8), a warm run writes none and rewrites none (a group that missed would compute its LUTs and store them:
#    a new or rewritten file), and its EXR equals the cold one's byte for byte. Before, a renderer wrote one file in
#    its life: each warm start computed all but one more group's LUTs again.
export XDG_CACHE_HOME="$work/spectral"
spectral() {   # spectral NAME GROUPS [FLAGS...]
    local name=$1 groups=$2; shift 2
    mkdir -p "$name"_cold "$name"_warm
    (cd "$name"_cold && "$VKSKY" "${ARGS[@]}" --spectral 24 --render out.exr "$@" >/dev/null 2>../"$name".err) ||
        fail "spectral $name, cold: $(cat "$name".err)"
    local n
    n=$(ls "$XDG_CACHE_HOME"/vksky/luts-*.bin 2>/dev/null | wc -l)
    [ "$n" -eq "$groups" ] || fail "spectral $name, cold: $n LUT cache files, expected one per group ($groups)"
    touch -d '2000-01-01' "$XDG_CACHE_HOME"/vksky/luts-*.bin
    (cd "$name"_warm && "$VKSKY" "${ARGS[@]}" --spectral 24 --render out.exr --timings "$@" >/dev/null \
        2>../"$name"_warm.err) || fail "spectral $name, warm: $(cat "$name"_warm.err)"
    [ "$(ls "$XDG_CACHE_HOME"/vksky/luts-*.bin | wc -l)" -eq "$groups" ] || fail "spectral $name, warm: a file added"
    [ -z "$(find "$XDG_CACHE_HOME"/vksky -name 'luts-*.bin' -newermt '2000-01-02')" ] ||
        fail "spectral $name, warm: a group missed the cache (its file rewritten)"
    [ "$(state "$name"_warm)" = "hit: uploaded, not computed" ] || fail "spectral $name, warm: '$(state "$name"_warm)'"
    cmp -s "$name"_cold/out.exr "$name"_warm/out.exr || fail "spectral $name: the warm EXR differs from the cold one"
    rm -f "$XDG_CACHE_HOME"/vksky/luts-*.bin
}
spectral sky 6 --pitch 60 --fov 30 --no-bloom
spectral horizon 8
# The budget (sky/lut_cache.h, SKY_LUT_CACHE_FILES_MAX): a medium animated over 20 frames (the serial loop, which
# stores each frame's LUTs on a miss) writes 16 files, not one a frame.
(VKSKY_READBACK_SLOTS=1 "$VKSKY" "${ARGS[@]}" --frame-count 20 --animate mie-g=0.70:0.89 --render "$work/m%02d.exr" \
    >/dev/null 2>budget.err) || fail "animated medium: $(cat budget.err)"
n=$(ls "$XDG_CACHE_HOME"/vksky/luts-*.bin 2>/dev/null | wc -l)
[ "$n" -eq 16 ] || fail "an animated medium's 20 frames wrote $n LUT cache files, expected 16 (the budget)"

# 8. The sun disc is no part of the key: the LUTs of a frame without it, computed in a directory of their own, are the
#    same file (name and bytes) as those of a frame with it, and a run without the disc hits the file of one with it.
for d in disc nodisc; do
    mkdir -p "$d" && (cd "$d" && XDG_CACHE_HOME="$work/key_$d" "$VKSKY" "${ARGS[@]}" --render out.exr \
        $([ $d = nodisc ] && echo --no-sun-disc) >/dev/null 2>../"$d".err) || fail "key, $d: $(cat "$d".err)"
done
a=$(cd "$work/key_disc/vksky" && ls luts-*.bin) b=$(cd "$work/key_nodisc/vksky" && ls luts-*.bin)
[ -n "$a" ] && [ "$a" = "$b" ] && cmp -s "$work/key_disc/vksky/$a" "$work/key_nodisc/vksky/$b" ||
    fail "the LUT files with and without the sun disc differ: '$a' / '$b'"
(cd nodisc && XDG_CACHE_HOME="$work/key_disc" "$VKSKY" "${ARGS[@]}" --render out.exr --no-sun-disc --timings \
    >/dev/null 2>../nodisc_warm.err) || fail "key, without the disc, warm: $(cat nodisc_warm.err)"
[ "$(state nodisc_warm)" = "hit: uploaded, not computed" ] ||
    fail "a run without the sun disc missed the LUTs of one with it: '$(state nodisc_warm)'"

# 9. A sequence through the readback ring (the default from two frames on) stores its first frame's LUTs as the serial
#    loop does: a cold 3-frame sequence writes the file, a warm one rewrites nothing and writes the same frames.
export XDG_CACHE_HOME="$work/ring"
for run in cold warm; do
    mkdir -p "ring_$run" && (cd "ring_$run" && "$VKSKY" "${ARGS[@]}" --frame-count 3 --animate sun-elevation=10:20 \
        --render 'f%d.exr' >/dev/null 2>../ring_$run.err) || fail "ring sequence, $run: $(cat ring_$run.err)"
    if [ $run = cold ]; then
        [ "$(ls "$XDG_CACHE_HOME"/vksky/luts-*.bin 2>/dev/null | wc -l)" -eq 1 ] ||
            fail "a ring sequence wrote no LUT cache file (or more than one)"
        touch -d '2000-01-01' "$XDG_CACHE_HOME"/vksky/luts-*.bin
    fi
done
[ -z "$(find "$XDG_CACHE_HOME"/vksky -name 'luts-*.bin' -newermt '2000-01-02')" ] ||
    fail "the warm ring sequence missed its LUTs (the file rewritten)"
for k in 0 1 2; do cmp -s "ring_cold/f$k.exr" "ring_warm/f$k.exr" || fail "ring sequence: frame $k differs warm"; done

# 10. --composite (app/runs/composite_app.c; spectral: composite_spectral.c) and --aovs store the LUTs their first
#     band computed, as a still does (they stored none: every composite of a render sequence computed the same LUTs
#     again; composite_spectral's --spectral 24 composite on lavapipe: 18.6 s cold, 1.2 s warm). Cold: the files
#     (RGB one, --spectral 24 one per group: 8) and the LUT passes traced; warm: no file added or rewritten,
#     lut_cache_upload traced and no LUT pass, and the same EXR byte for byte (the same names: the header records
#     the command line).
mkdir -p "$work/cs" && "$GEN" "$work/cs" 32 18 >/dev/null || fail "gen_composite_scene"
composite() {   # composite NAME FILES FLAGS...
    local name=$1 files=$2; shift 2
    export XDG_CACHE_HOME="$work/composite_$name"
    for run in cold warm; do
        mkdir -p "${name}_$run" && (cd "${name}_$run" && "$VKSKY" --multiscatter-dirs 16 --sun-elevation 3 \
            --render out.exr --trace-passes "$@" >../"${name}_$run".out 2>../"${name}_$run".err) ||
            fail "$name, $run: $(head -c 300 "${name}_$run".err)"
        local n
        n=$(ls "$XDG_CACHE_HOME"/vksky/luts-*.bin 2>/dev/null | wc -l)
        [ "$n" -eq "$files" ] || fail "$name, $run: $n LUT cache files, expected $files"
        [ $run = cold ] && touch -d '2000-01-01' "$XDG_CACHE_HOME"/vksky/luts-*.bin
    done
    grep -q '^pass transmittance_lut$' "${name}_cold.out" || fail "$name, cold: no LUT pass traced"
    ! grep -q '^pass \(transmittance\|multiscatter\)_lut$' "${name}_warm.out" &&
        grep -q '^pass lut_cache_upload$' "${name}_warm.out" || fail "$name, warm: the LUTs computed, not uploaded"
    [ -z "$(find "$XDG_CACHE_HOME"/vksky -name 'luts-*.bin' -newermt '2000-01-02')" ] ||
        fail "$name, warm: a file rewritten (a miss)"
    cmp -s "${name}_cold/out.exr" "${name}_warm/out.exr" || fail "$name: the warm EXR differs from the cold one"
}
composite rgb 1 --composite "$work/cs/render.exr" --spectral 0
composite spectral 8 --composite "$work/cs/render.exr" --spectral 24
composite aovs 8 --aovs --width 24 --height 12 --spectral 24

[ $fails -eq 0 ] && echo "ok: LUT cache" || echo "$fails failure(s)"
[ $fails -eq 0 ]
