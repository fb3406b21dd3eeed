#!/usr/bin/env bash
# The graceful stop (issue 15 item 3): SIGINT / SIGTERM end a long run cleanly. For each run:
#  - exit status 128 + the signal (130 SIGINT, 143 SIGTERM), and the one line "vksky: stopped by SIG...";
#  - no output file and no temporary file left in the output directory;
#  - not a word about validation on stderr (every run has --validate: validation + synchronization validation,
#    so a skipped wait-idle or a destroyed-while-in-use object would be reported);
#  - it stopped promptly: well before the run would have finished on its own.
# A signal is sent only once the handler is installed (the SigCgt mask in /proc/PID/status has it): before that the
# default action would end the process, which is not what is under test. Runs: a headless render stopped while its
# frame is on the device; --bench stopped between frames; the path tracer stopped between pixels; a sequence stopped
# between frames (the frames it finished stay, whole); the window under Xvfb stopped while presenting (with
# --screenshot: no screenshot) and while minimised (in the event wait).
# Usage: signals_test.sh path/to/vksky
set -u
VKSKY=${1:?usage: signals_test.sh path/to/vksky}
SELF=$(readlink -f "$0")
HERE=$(dirname "$SELF")

# handler_installed PID: both SIGINT (bit 2) and SIGTERM (bit 15) are caught.
handler_installed() {
    local mask
    mask=$(sed -n 's/^SigCgt:\s*//p' "/proc/$1/status" 2>/dev/null) || return 1
    [ -n "$mask" ] && (( (16#$mask & 0x4002) == 0x4002 ))
}
# wait_for COND_CMD... : poll up to 60 s; 1 when the process ($pid) ended first or time ran out.
wait_for() {
    for _ in $(seq 600); do
        "$@" && return 0
        kill -0 "$pid" 2>/dev/null || return 1
        sleep 0.1
    done
    return 1
}
# stop_and_check WHAT SIGNAL EXPECTED_STATUS MAX_SECONDS DIR: send the signal to $pid, wait for it, check.
stop_and_check() {
    local what=$1 sig=$2 want=$3 max=$4 dir=$5 t0 t1 rc
    t0=$(date +%s.%N)
    kill -"$sig" "$pid"
    wait "$pid"
    rc=$?
    t1=$(date +%s.%N)
    local took
    took=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }')
    echo "$what: SIG$sig -> exit $rc after $took s"
    [ "$rc" -eq "$want" ] || fail "$what: exit status $rc, expected $want (stderr: $(head -c 1500 "$dir/err"))"
    grep -q "^vksky: stopped by SIG$sig: exit status $want" "$dir/err" || fail "$what: no 'stopped by SIG$sig' line: $(head -c 600 "$dir/err")"
    ! grep -qi validation "$dir/err" || fail "$what: validation messages: $(grep -i validation "$dir/err" | head -5)"
    local left
    left=$(ls -A "$dir" | grep -v -x -e out -e err)
    [ -z "$left" ] || fail "$what: files left behind: $left"
    awk -v t="$took" -v m="$max" 'BEGIN { exit !(t < m) }' || fail "$what: took $took s to stop (expected < $max s)"
}

# --- Inside Xvfb: the window, stopped while presenting and while minimised. --------------------------------------
if [ "${2:-}" = "--inside-xvfb" ]; then
    work=$3
    fails=0
    fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
    title_has_fps() { timeout 5 xdotool search --name 'fps' >/dev/null 2>&1; }
    # a. Presenting, with --screenshot (which a normal quit would write): SIGINT -> 130, no screenshot.
    mkdir -p "$work/w1"
    "$VKSKY" --validate --frames 1000000 --width 160 --height 90 --screenshot "$work/w1/shot.png" \
        >"$work/w1/out" 2>"$work/w1/err" &
    pid=$!
    wait_for handler_installed "$pid" && wait_for title_has_fps || fail "window: never presented: $(head -c 600 "$work/w1/err")"
    stop_and_check "window presenting" INT 130 10 "$work/w1"
    grep -q "^validation_messages 0$" "$work/w1/out" || fail "window presenting: no 'validation_messages 0': $(tail -3 "$work/w1/out")"
    # b. Minimised (unmapped, as a window manager does to an iconified window): the loop sleeps in the event wait.
    mkdir -p "$work/w2"
    "$VKSKY" --validate --frames 1000000 --width 160 --height 90 >"$work/w2/out" 2>"$work/w2/err" &
    pid=$!
    wait_for handler_installed "$pid" && wait_for title_has_fps || fail "window 2: never presented: $(head -c 600 "$work/w2/err")"
    wid=$(timeout 5 xdotool search --name '^vksky' | head -1)
    timeout 5 xdotool windowunmap --sync "$wid"
    sleep 1
    stop_and_check "window minimised" TERM 143 10 "$work/w2"
    grep -q "^validation_messages 0$" "$work/w2/out" || fail "window minimised: no 'validation_messages 0'"
    echo "$fails" >"$work/xvfb.fails"
    exit 0
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
t_start=$(date +%s)
help=$("$VKSKY" --help) && grep -q "^  130 / 143 stopped by SIGINT" <<<"$help" || fail "--help does not document the exit statuses 130 / 143"

# 1. Headless render: SIGINT once the frame is recorded (the pass trace is printed while recording, just before the
#    submit), so the frame is on the device when the signal lands: 768x768 at "high" takes seconds on a CPU device
#    (lavapipe, as in CI). A GPU may finish the frame and write both files before the signal arrives; an output
#    renamed into place before the stop is whole and may stay, so there only "no temporary, nothing partial" holds.
mkdir -p "$work/r"
stdbuf -oL "$VKSKY" --validate --trace-passes --quality high --width 768 --height 768 \
    --render "$work/r/sky.exr" --render "$work/r/sky.png" >"$work/r/out" 2>"$work/r/err" &
pid=$!
wait_for grep -q '^pass ' "$work/r/out" || fail "render: no frame recorded: $(head -c 600 "$work/r/err")"
handler_installed "$pid" || fail "render: no handler installed while rendering"
devices=$("$VKSKY" --list-devices) || fail "--list-devices: exit $?"
if ! grep -q -v "(cpu," <<<"$devices"; then   # only CPU devices: the one chosen is a CPU
    stop_and_check "headless render" INT 130 30 "$work/r"
else
    kill -INT "$pid"; wait "$pid"; rc=$?
    [ "$rc" -eq 130 ] || [ "$rc" -eq 0 ] || fail "headless render (GPU): exit status $rc"
    [ -z "$(ls -A "$work/r" | grep tmp)" ] || fail "headless render (GPU): temporary left: $(ls -A "$work/r")"
    [ ! -e "$work/r/sky.exr" ] || exrheader "$work/r/sky.exr" >/dev/null 2>&1 || fail "headless render (GPU): partial EXR"
    echo "headless render: a GPU device (not a CPU one): exit $rc, nothing partial"
fi

# 2. --bench with far more frames than the test could wait for: SIGTERM between frames, no figures printed.
mkdir -p "$work/b"
"$VKSKY" --validate --bench 100000 --width 64 --height 64 >"$work/b/out" 2>"$work/b/err" &
pid=$!
wait_for handler_installed "$pid" || fail "bench: handler never installed"
sleep 2
stop_and_check "bench" TERM 143 10 "$work/b"
! grep -q '^frame ' "$work/b/out" || fail "bench: printed figures of a cut-short run"

# 3. The path tracer: 32x32 pixels of 4096 paths (over a minute of work): SIGTERM between pixels.
mkdir -p "$work/p"
"$VKSKY" --reference --path-trace --samples 4096 --width 32 --height 32 --render "$work/p/pt.exr" \
    >"$work/p/out" 2>"$work/p/err" &
pid=$!
wait_for handler_installed "$pid" || fail "path trace: handler never installed"
sleep 1
stop_and_check "path trace" TERM 143 10 "$work/p"
# ... the converged model (--reference without --path-trace) while it builds its multiple-scattering table (about 2 s
# of CPU before the row threads start; the build looks at the flag between its rows: ref_set_cancel), SIGTERM:
# stopped within 1 s, where waiting for the table would take longer ...
mkdir -p "$work/t"
"$VKSKY" --reference --width 256 --height 256 --render "$work/t/ref.exr" >"$work/t/out" 2>"$work/t/err" &
pid=$!
wait_for handler_installed "$pid" || fail "reference table: handler never installed"
t_tasks=$(ls "/proc/$pid/task" 2>/dev/null | wc -l)
sleep 0.2
if [ "$(ls "/proc/$pid/task" 2>/dev/null | wc -l)" -eq "$t_tasks" ]; then   # no row thread yet: still the table
    stop_and_check "reference table" TERM 143 1.0 "$work/t"
else
    kill "$pid"; wait "$pid"
    echo "reference table: built before the signal could land (a fast machine): not checked"
fi
# ... and its rows, SIGINT, once its two row threads run.
mkdir -p "$work/m"
"$VKSKY" --reference --width 2048 --height 2048 --render "$work/m/ref.exr" >"$work/m/out" 2>"$work/m/err" &
pid=$!
wait_for handler_installed "$pid" || fail "reference: handler never installed"
tasks() { ls "/proc/$pid/task" 2>/dev/null | wc -l; }
base_tasks=$(tasks)
row_threads() { [ "$(tasks)" -ge $((base_tasks + 2)) ]; }
wait_for row_threads || fail "reference: the row threads never started"
sleep 0.5
stop_and_check "reference rows" INT 130 10 "$work/m"

# 4. A sequence of 1000 frames: SIGINT once two frames are written. It stops between frames: the frames it finished
#    stay and are whole (each loads back as a scene: its header is read to the end of the attributes, and the file
#    is all there), no later frame and no temporary is left.
mkdir -p "$work/s"
"$VKSKY" --validate --width 64 --height 64 --quality low --frame-count 1000 --animate sun-elevation=0:40 \
    --render "$work/s/f_%04d.exr" >"$work/s/out" 2>"$work/s/err" &
pid=$!
wait_for grep -q '^vksky: frame 1 ' "$work/s/err" || fail "sequence: frame 1 never written: $(head -c 600 "$work/s/err")"
kill -INT "$pid"
wait "$pid"
rc=$?
written=$(ls "$work/s" | grep -c '^f_[0-9]*\.exr$')
echo "sequence: SIGINT -> exit $rc, $written frames kept"
[ "$rc" -eq 130 ] || fail "sequence: exit status $rc, expected 130 (stderr: $(tail -c 600 "$work/s/err"))"
grep -q "^vksky: stopped by SIGINT: exit status 130" "$work/s/err" || fail "sequence: no 'stopped by SIGINT' line"
! grep -qi validation "$work/s/err" || fail "sequence: validation messages: $(grep -i validation "$work/s/err" | head -3)"
! grep -q "frames rendered" "$work/s/err" || fail "sequence: a stopped sequence reported itself done"
left=$(ls -A "$work/s" | grep -v -x -e out -e err | grep -v '^f_[0-9]*\.exr$')
[ -z "$left" ] || fail "sequence: files left behind: $left"
[ "$written" -ge 2 ] && [ "$written" -lt 1000 ] || fail "sequence: $written frames written (expected 2 to 999)"
for ((i = 0; i < written; ++i)); do
    f=$(printf '%s/s/f_%04d.exr' "$work" "$i")
    [ -f "$f" ] || { fail "sequence: frame $i missing ($written written: not the first ones)"; continue; }
    "$VKSKY" --scene "$f" --dump-scene >/dev/null 2>"$work/s/load.err" || fail "sequence: frame $i unreadable: $(cat "$work/s/load.err")"
done

# 5. The window, under Xvfb (skipped without Xvfb / xdotool).
if command -v Xvfb >/dev/null && command -v xdotool >/dev/null; then
    timeout 120 "$HERE/xvfb_run.sh" 640x480x24 "$SELF" "$VKSKY" --inside-xvfb "$work"
    f=$(cat "$work/xvfb.fails" 2>/dev/null || echo 1)
    [ "$f" -eq 0 ] || fail "window runs: $f failure(s)"
else
    echo "signals: Xvfb or xdotool not installed; window runs skipped"
fi

echo "signals: $(($(date +%s) - t_start)) s"
if [ $fails -ne 0 ]; then echo "signals: $fails failure(s)"; exit 1; fi
# A section skipped is not a pass (issue 31): ctest shows SKIP (SKIP_RETURN_CODE 77), and CI fails on any skip.
if ! command -v Xvfb >/dev/null || ! command -v xdotool >/dev/null; then
    echo "signals: SKIP: the window runs need xvfb and xdotool"; exit 77
fi
echo "signals: ok"
