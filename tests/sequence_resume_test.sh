#!/usr/bin/env bash
# tests/sequence_resume_test.sh VKSKY EXR_PIXELS: a sequence on any node, resumed (issue 30 items 1, 2; the Slurm farm
# itself: farm_test.sh).
#  1. Same frames on any device: --quality auto chooses a single render's configuration from its device kind's table
#     (forced with VKSKY_QUALITY_TABLE: the cpu and gpu tables give two configurations for a noon scene, the check
#     that the next one can fail), but a sequence's from the scene alone: a --frame-range rendered with the GPU table
#     forced, with the CPU table forced and on this machine's own device gives the same files, byte for byte, and
#     its frame's scene is the single render's under the GPU table (the documented rule).
#  2. --skip-existing: frames whose files exist are kept (not written again: same inodes) and counted; a missing file,
#     an EXR of another frame, of another scene or not an EXR at all is rendered again, with a note for each file
#     that exists; the result equals the uninterrupted render byte for byte. Two jobs with overlapping ranges at once
#     give the same files too. Only with a sequence: one line, exit 2.
# Every render under the validation layer with synchronization validation (VKSKY_VALIDATION=1).
set -u
VKSKY=$(realpath "${1:?usage: sequence_resume_test.sh VKSKY EXR_PIXELS}")
PIX=$(realpath "${2:?}")
export VKSKY_VALIDATION=1
unset VKSKY_QUALITY_TABLE
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
cd "$work" || exit 1

# 1. The quality choice. Noon: frame 2 of 50:70 over 5 frames is exactly 60.
NOON=(--width 48 --height 32 --pitch 30)
VKSKY_QUALITY_TABLE=cpu "$VKSKY" "${NOON[@]}" --sun-elevation 60 --render x.exr --dump-scene >single_cpu.json ||
    fail "--dump-scene with the CPU table: exit $?"
VKSKY_QUALITY_TABLE=gpu "$VKSKY" "${NOON[@]}" --sun-elevation 60 --render x.exr --dump-scene >single_gpu.json ||
    fail "--dump-scene with the GPU table: exit $?"
cmp -s single_cpu.json single_gpu.json && fail "the CPU and GPU tables choose the same configuration for noon: the next check cannot fail"
for table in cpu gpu own; do
    mkdir "$table"
    (cd "$table" && if [ $table = own ]; then
        "$VKSKY" "${NOON[@]}" --animate sun-elevation=50:70 --frame-count 5 --frame-range 1:2 --render 'n_%d.exr' 2>err
    else
        VKSKY_QUALITY_TABLE=$table "$VKSKY" "${NOON[@]}" --animate sun-elevation=50:70 --frame-count 5 --frame-range 1:2 \
            --render 'n_%d.exr' 2>err
    fi) || fail "the range with the $table table failed: $(cat "$table/err")"
done
for f in n_1.exr n_2.exr; do
    cmp -s "cpu/$f" "gpu/$f" || fail "$f differs between the CPU and the GPU table: a sequence's frames depend on the device"
    cmp -s "cpu/$f" "own/$f" || fail "$f on this machine's device differs from the one with the CPU table forced"
done
"$PIX" attr gpu/n_2.exr vksky:scene >frame2.json || fail "n_2.exr has no vksky:scene"
cmp -s frame2.json single_gpu.json || fail "frame 2's scene is not the single render's under the GPU table: $(diff frame2.json single_gpu.json | head -4)"

# 2. --skip-existing.
# RGB named (--spectral 0): under auto this twilight-to-afternoon run renders spectral (32g), whose groups recompute
# the LUTs in every frame; the LUT count below is the RGB loop's.
SEQ=(--width 48 --height 32 --animate sun-elevation=-2:30 --animate yaw=0:50 --frame-count 6 --spectral 0
     --render 'f_%03d.exr' --render 'f_%03d.png')
mkdir whole resume
(cd whole && "$VKSKY" "${SEQ[@]}" 2>err) || fail "the whole sequence failed: $(cat whole/err)"
rm -f whole/err
cp -p whole/* resume/
cd resume || exit 1
ino() { stat -c %i "$@" | tr '\n' ' '; }
before=$(ino f_*)
"$VKSKY" "${SEQ[@]}" --skip-existing 2>err || fail "a resume with nothing to do failed: $(cat err)"
grep -q '^vksky: 0 frames rendered, 6 skipped (written before); LUTs computed 0 times$' err || fail "nothing to do: $(tail -1 err)"
grep -q '^vksky: frame 4 (5 of 6; 5/6 of this job): f_004.exr, skipped (written before)$' err || fail "no progress line for skipped frame 4"
[ "$(ino f_*)" = "$before" ] || fail "a resume with nothing to do wrote files again"
# Frame 1: a file missing. Frame 2: not an EXR. Frame 3: frame 4's EXR. Frame 5: another scene's frame 5.
rm f_001.png
echo "not an image" >f_002.exr
cp ../whole/f_004.exr f_003.exr
(mkdir ../other && cd ../other && "$VKSKY" "${SEQ[@]}" --mie-g 0.7 --frame-range 5:5 2>/dev/null && cp f_005.exr ../resume/) \
    || fail "the other scene's frame failed"
"$PIX" same f_005.exr ../whole/f_005.exr >/dev/null && fail "the other scene's frame 5 has the same pixels: the check cannot fail"
kept=$(ino f_000.exr f_000.png f_004.exr f_004.png)
"$VKSKY" "${SEQ[@]}" --skip-existing 2>err || fail "the resume failed: $(cat err)"
grep -q '^vksky: 4 frames rendered, 2 skipped (written before); LUTs computed 1 time$' err || fail "the resume: $(tail -1 err)"
[ "$(grep -c 'rendering it again$' err)" -eq 3 ] || fail "expected 3 notes (frames 2, 3, 5): $(grep again err)"
grep -q '^vksky: frame 2: f_002.exr cannot be read as an EXR; rendering it again$' err || fail "no note for frame 2"
grep -q '^vksky: frame 3: f_003.exr is frame 4, not 3; rendering it again$' err || fail "no note for frame 3"
grep -q '^vksky: frame 5: f_005.exr is frame 5 of another scene' err || fail "no note for frame 5"
grep -q '^vksky: frame 1 (2 of 6; 2/6 of this job): f_001.exr, LUTs ' err || fail "frame 1 (a PNG missing) was not rendered"
[ "$(ino f_000.exr f_000.png f_004.exr f_004.png)" = "$kept" ] || fail "frames 0 and 4 were written again"
rm -f err
diff <(ls -A ../whole) <(ls -A .) >/dev/null || fail "the resumed files are not the whole render's: $(ls -A)"
for f in ../whole/*; do
    cmp -s "$f" "${f##*/}" || fail "resumed ${f##*/} differs from the uninterrupted render's"
done
# A --frame-range resumed: the job's own count.
rm f_003.exr
"$VKSKY" "${SEQ[@]}" --frame-range 2:4 --skip-existing 2>err || fail "the range resume failed"
grep -q '^vksky: 1 frame rendered, 2 skipped (written before); LUTs computed 1 time$' err || fail "range resume: $(tail -1 err)"
cmp -s f_003.exr ../whole/f_003.exr || fail "frame 3 of a range resume differs"
cd "$work" || exit 1

# Two jobs whose ranges overlap, at once: each file is written whole by one of them (temp name, rename), and both
# write the same bytes, so the result is the whole render's.
mkdir overlap && cd overlap || exit 1
"$VKSKY" "${SEQ[@]}" --frame-range 0:3 2>err1 &
first=$!
"$VKSKY" "${SEQ[@]}" --frame-range 2:5 2>err2 || fail "the second overlapping job failed: $(cat err2)"
wait $first || fail "the first overlapping job failed: $(cat err1)"
rm -f err1 err2
diff <(ls -A ../whole) <(ls -A .) >/dev/null || fail "overlapping jobs left other files: $(ls -A)"
for f in ../whole/*; do
    cmp -s "$f" "${f##*/}" || fail "overlapping jobs' ${f##*/} differs from the whole render's"
done
cd "$work" || exit 1

# Only with a sequence: one line, exit 2, no file.
mkdir bad && cd bad || exit 1
"$VKSKY" --width 16 --height 16 --render x.exr --skip-existing >out 2>err
rc=$?
[ $rc -eq 2 ] || fail "--skip-existing without a sequence: exit $rc, expected 2"
[ "$(wc -l <err)" -eq 1 ] && grep -q -- '--skip-existing' err || fail "--skip-existing without a sequence: $(cat err)"
[ ! -e x.exr ] || fail "--skip-existing without a sequence wrote x.exr"
"$VKSKY" --width 16 --height 16 --frame-count 2 --render 'x_%d.exr' --skip-existing=1 >out 2>err
[ $? -eq 2 ] && [ "$(wc -l <err)" -eq 1 ] || fail "--skip-existing=1: $(cat err)"
[ $fails -eq 0 ] && echo "sequence_resume: all checks pass"
exit $((fails > 0))
