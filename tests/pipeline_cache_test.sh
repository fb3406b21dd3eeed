#!/usr/bin/env bash
# tests/pipeline_cache_test.sh VKSKY: the pipeline cache on disk and the start-up report (issue 27).
#  1. A first run writes $XDG_CACHE_HOME/vksky/pipelines-<UUID>-<driver>.bin: our header (magic, sizes, the FNV-1a
#     checksum recomputed here) around a Vulkan cache whose VkPipelineCacheHeaderVersionOne carries the UUID the file
#     is named by. A second run leaves it alone and says nothing. The cache never changes a pixel (= --no-cache).
#  2. A corrupt, truncated, foreign (another device's header, checksum made good) or alien file: one note on stderr,
#     the same image, and the file replaced by a good one. A file from another build: replaced without a note.
#  3. An unwritable cache directory: the render succeeds (one note); --no-cache writes nothing; a relative
#     XDG_CACHE_HOME is ignored (~/.cache); runs started together leave one good file and no temporary files.
#  4. --timings names every stage, its stages add up to its total and the total is the run's wall time; Mars builds
#     its pipeline variant once (the renderer used to build it three times) and computes each of its LUTs once.
#     A validated run adopts --quality auto's probe's instance, and the layer still catches a dropped barrier there.
#  5. Without validation one image leaves its device to the exit, still saves the cache, writes the same bytes.
set -u
VKSKY=${1:?usage: pipeline_cache_test.sh VKSKY}
export VKSKY_VALIDATION=1   # every render under the validation layer; any message fails it
export VKSKY_LUT_CACHE=0     # the pipeline cache alone (its directory must hold only its file); ctest lut_cache: the LUTs'
work=$(mktemp -d)
trap 'chmod -R u+w "$work" 2>/dev/null; rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
cd "$work" || exit 1
export HOME="$work/home" XDG_CACHE_HOME="$work/xdg"
# Small and quick: the multi-scattering LUT's directions dominate a tiny render on lavapipe.
ARGS=(--width 12 --height 8 --multiscatter-dirs 16)

# check FILE: prints "ok" or why not, from the file's bytes alone (an independent reading of the format).
check() {
    python3 - "$1" <<'EOF'
import struct, sys, os, re
p = sys.argv[1]; b = open(p, 'rb').read()
def fnv(d):
    h = 0xcbf29ce484222325
    for c in d: h = ((h ^ c) * 0x100000001b3) & 0xffffffffffffffff
    return h
if b[:8] != b'VKSKYPC1': print('magic'); sys.exit()
size, s = struct.unpack_from('<QQ', b, 48)
d = b[64:]
if size != len(d): print('size'); sys.exit()
if fnv(d) != s: print('checksum'); sys.exit()
hsize, hver = struct.unpack_from('<II', d, 0)
uuid = d[16:32].hex()
m = re.match(r'pipelines-([0-9a-f]{32})-[0-9a-f]{8}\.bin$', os.path.basename(p))
if hsize < 32 or hver != 1: print('vulkan header'); sys.exit()
if not m or m.group(1) != uuid: print('uuid %s vs name' % uuid); sys.exit()
print('ok')
EOF
}
# rewrite FILE OFFSET HEXBYTES: patch bytes of the Vulkan data (offset within it) and make the checksum good again.
rewrite() {
    python3 - "$@" <<'EOF'
import struct, sys
p, off, hexb = sys.argv[1], int(sys.argv[2]), bytes.fromhex(sys.argv[3])
b = bytearray(open(p, 'rb').read())
b[64 + off:64 + off + len(hexb)] = hexb
h = 0xcbf29ce484222325
for c in b[64:]: h = ((h ^ c) * 0x100000001b3) & 0xffffffffffffffff
struct.pack_into('<Q', b, 56, h)
open(p, 'wb').write(bytes(b))
EOF
}
notes() { grep -c 'pipeline cache' "$1"; }
# render NAME [FLAGS...]: NAME/out.exr and out.png (the same names every time: the EXR header records the command
# line, so EXRs are compared only between runs of one command line; the PNGs always).
render() {
    local name=$1; shift
    mkdir -p "$name" && (cd "$name" && "$VKSKY" "${ARGS[@]}" --render out.exr --render out.png "$@" 2>../"$name".err)
}
same() { cmp -s ref/out.png "$1/out.png" && { [ "$1" = nocache ] || cmp -s ref/out.exr "$1/out.exr"; }; }

# 1. First run, second run, --no-cache.
render ref || fail "first run failed: $(cat ref.err)"
cp ref.err first.err
files=("$XDG_CACHE_HOME"/vksky/pipelines-*.bin)
cache=${files[0]}
[ ${#files[@]} -eq 1 ] && [ -f "$cache" ] || fail "expected one cache file, found: ${files[*]}"
[ "$(check "$cache")" = ok ] || fail "the cache file does not read back: $(check "$cache")"
[ "$(notes first.err)" -eq 0 ] || fail "a first run with no cache file printed a note: $(cat first.err)"
cp "$cache" good.bin
touch -d '2000-01-01' "$cache"
render warm || fail "warm run failed: $(cat warm.err)"
[ "$(notes warm.err)" -eq 0 ] || fail "a warm run printed a note: $(cat warm.err)"
[ "$(stat -c %Y "$cache")" = "$(date -d '2000-01-01' +%s)" ] || fail "a warm run with nothing new rewrote the file"
same warm || fail "the warm run's image differs from the cold run's"
render nocache --no-cache || fail "--no-cache failed"
same nocache || fail "--no-cache's image differs from the cached run's"

# 2. Bad files: one note, the same image, the file replaced by a good one.
bad_case() {   # NAME EXPECTED-WORDS (in the note)
    render "$1" || fail "$1: the render failed: $(cat "$1.err")"
    [ "$(notes "$1.err")" -eq 1 ] || fail "$1: expected one note, got: $(cat "$1.err")"
    grep -q "pipeline cache .*: .*$2.*; ignored" "$1.err" ||
        fail "$1: the note does not say '$2 ... ignored': $(cat "$1.err")"
    same "$1" || fail "$1: the image differs"
    [ "$(check "$cache")" = ok ] || fail "$1: the file was not replaced by a good one ($(check "$cache"))"
}
cp good.bin "$cache" && printf '\x5a' | dd of="$cache" bs=1 seek=$((64 + 20)) conv=notrunc status=none
bad_case corrupt "corrupt"
head -c 70 good.bin >"$cache"
bad_case truncated "truncated"
cp good.bin "$cache" && rewrite "$cache" 8 ffffffff      # vendorID: another vendor's driver
bad_case foreign_vendor "another device"
cp good.bin "$cache" && rewrite "$cache" 16 00112233445566778899aabbccddeeff   # pipelineCacheUUID
bad_case foreign_uuid "another device"
cp good.bin "$cache" && rewrite "$cache" 4 02000000      # headerVersion 2: not one we know
bad_case header_version "not a Vulkan pipeline cache"
printf 'P6 1 1 255 xyz' >"$cache"
bad_case alien "not a vksky pipeline cache"
cp good.bin "$cache" && printf 'another-build-key' | dd of="$cache" bs=1 seek=16 conv=notrunc status=none
render build || fail "another build's file: the render failed"
[ "$(notes build.err)" -eq 0 ] || fail "another build's file printed a note: $(cat build.err)"
cmp -s "$cache" good.bin || fail "another build's file was not replaced by this build's"

# 3. Unwritable directory (a file where the directory should be: refused even to root), --no-cache, relative XDG.
touch notadir
XDG_CACHE_HOME="$work/notadir" render ro || fail "unwritable cache dir: the render failed: $(cat ro.err)"
same ro || fail "unwritable cache dir: the image differs"
[ "$(notes ro.err)" -eq 1 ] && grep -q 'not saved' ro.err ||
    fail "unwritable cache dir: expected one 'not saved' note: $(cat ro.err)"
XDG_CACHE_HOME="$work/fresh" render fresh --no-cache || fail "--no-cache failed"
[ ! -e "$work/fresh/vksky" ] || fail "--no-cache wrote into the cache directory"
XDG_CACHE_HOME=relative/dir render rel || fail "relative XDG_CACHE_HOME: failed"
[ ! -e rel/relative ] && ls "$HOME"/.cache/vksky/pipelines-*.bin >/dev/null 2>&1 ||
    fail "a relative XDG_CACHE_HOME was not ignored for ~/.cache"
pids=()
for i in 1 2 3; do
    XDG_CACHE_HOME="$work/together" "$VKSKY" "${ARGS[@]}" --render "t$i.exr" 2>"t$i.err" & pids+=($!)
done
for i in 0 1 2; do wait "${pids[$i]}" || fail "run $((i + 1)) of three together failed: $(cat "t$((i + 1)).err")"; done
together=("$work"/together/vksky/*)
[ ${#together[@]} -eq 1 ] && [ "$(check "${together[0]}")" = ok ] || fail "three runs together left: ${together[*]}"

# 4. --timings, and the variant built once.
start=$(date +%s%N)
"$VKSKY" "${ARGS[@]}" --scene mars --render mars.exr --timings --trace-passes >mars.out 2>mars.err ||
    fail "--timings failed: $(cat mars.err)"
wall=$((($(date +%s%N) - start) / 1000000))
for lut in transmittance_lut multiscatter_lut ground_irradiance_lut; do
    [ "$(grep -c "^pass $lut\$" mars.out)" -eq 1 ] || fail "Mars: $lut computed $(grep -c "^pass $lut\$" mars.out) times"
done
for stage in exec options probe instance device cache pipelines setup LUTs frame readback encode write teardown total; do
    grep -q "^  $stage " mars.err || [ "$stage" = readback ] || fail "--timings has no '$stage' line: $(cat mars.err)"
done
grep -q 'variant built 1 time)' mars.err ||
    fail "Mars built its pipeline variant more than once: $(grep variant mars.err)"
# The table accounts for the run: its stages (all but LUTs and readback, which are inside the frame) add up to its
# total, to the rounding of its lines (0.05 ms each); and the total is the process's own wall time as this shell saw
# it, which adds fork and exec before (the exec line reads process start to a 10 ms tick) and the exit after the
# report (the validation layer's unload: ~60 ms here), so within 11 ms above and a tenth + 200 ms below.
total=$(awk '$1 == "total" {print $2}' mars.err)
awk -v t="$total" '$1 ~ /^(exec|options|probe|instance|device|cache|pipelines|setup|frame|encode|write|teardown)$/ &&
    $2 != "-" {s += $2; n++}
    END {d = s - t; if (d < 0) d = -d; exit !(n >= 12 && d <= 1.0)}' mars.err ||
    fail "--timings' stages do not add up to its total: $(cat mars.err)"
awk -v t="$total" -v w="$wall" 'BEGIN {exit !(t <= w + 11 && t >= w - (0.1 * w + 200))}' ||
    fail "--timings' total $total ms is not the process's wall time ($wall ms seen from outside): $(cat mars.err)"

# 4b. The device probed once (issue 27): --quality auto's probe makes the instance the run then adopts, with the
#     validation layer on when the run validates (VKSKY_VALIDATION=1 here); and the layer still reports through the
#     adopted instance: a barrier left out is caught, its hazard on stderr and the exit status non-zero.
grep -q "^  instance .*(the device probe's, reused)" mars.err ||
    fail "a validated run made a second instance after the probe's: $(grep -E '^  (probe|instance)' mars.err)"
VKSKY_DROP_BARRIER=hdr.write_to_sample "$VKSKY" "${ARGS[@]}" --render drop.exr --timings >drop.out 2>drop.err &&
    fail "hdr.write_to_sample dropped, under the probe's instance: exit 0"
grep -q "SYNC-HAZARD-READ-AFTER-WRITE" drop.err && grep -q "(the device probe's, reused)" drop.err ||
    fail "hdr.write_to_sample dropped, under the probe's instance: no hazard reported: $(head -c 600 drop.err)"

# 5. One image without validation leaves its renderer, device and instance to the exit (startup_keep_for_exit):
#    the run still succeeds, still saves the pipeline cache (a fresh directory gets a whole file), and writes the same
#    bytes as the full teardown (VKSKY_TEARDOWN=1). The runs above (validated) destroyed everything.
for mode in kept full; do
    td=0; [ "$mode" = full ] && td=1
    XDG_CACHE_HOME="$work/xdg_$mode" VKSKY_VALIDATION=0 VKSKY_TEARDOWN=$td "$VKSKY" "${ARGS[@]}" --render "one.exr" \
        --timings >"$mode.out" 2>"$mode.err" || fail "$mode teardown: exit $?: $(cat "$mode.err")"
    cp one.exr "$mode.exr"
    kept_files=("$work/xdg_$mode"/vksky/pipelines-*.bin)
    [ -f "${kept_files[0]}" ] && [ "$(check "${kept_files[0]}")" = ok ] ||
        fail "$mode teardown: no whole pipeline cache file saved: $(ls "$work/xdg_$mode/vksky" 2>&1)"
done
grep -q 'left to the exit' kept.err || fail "no validation: the teardown was not left to the exit: $(grep teardown kept.err)"
grep -q 'instance destroyed' full.err || fail "VKSKY_TEARDOWN=1: not destroyed: $(grep teardown full.err)"
cmp -s kept.exr full.exr || fail "the kept and the full teardown wrote different bytes"

[ "$fails" -eq 0 ] && echo "pipeline cache: all checks passed"
exit $((fails > 0))
