#!/usr/bin/env bash
# F5 in the window (issue 25 item 2): the --scene file is read again and the command line's flags are applied over
# it again, as the values the start-up parse kept. Under Xvfb, with --validate (validation + synchronization
# validation; any message makes vksky exit 1):
#  - the window starts with a scene file and a flag that overrides one of its fields (--mie-g 0.6 over g 0.8);
#  - VKSKY_TEST_F5=5:FILE: after the 5th presented frame the window waits for FILE; the test edits the scene file on
#    disk meanwhile (Rayleigh scale height 8 -> 9 km, and the field the flag overrides: g 0.8 -> 0.3), then creates
#    FILE, and the window does what F5 does;
#  - the screenshot of its last frame is pixel-identical to `vksky --render` of the edited file with the same flags
#    (the file's new field applied, the flag's value kept), and differs from the edited file without the flag (the
#    file's g would have won) and from the old file with the flag (nothing reloaded).
# Exit 77 (ctest: skipped) without Xvfb or ImageMagick's compare.
set -u
VKSKY=${1:?usage: window_reload_test.sh path/to/vksky}
SELF=$(readlink -f "$0")
# Small frames, the window's preset named for the headless renders (the window starts from "low"), a fixed EV100.
common=(--validate --width 160 --height 90 --sun-elevation 5 --yaw 0 --pitch 5 --exposure 12)

# --- Inside Xvfb: start the window, edit the scene file while it waits after frame 5, let it go on.
if [ "${2:-}" = "--inside-xvfb" ]; then
    work=$3
    VKSKY_TEST_F5="5:$work/go" "$VKSKY" "${common[@]}" --frames 12 --mie-g 0.6 --scene "$work/scene.json" \
        --screenshot "$work/window.png" >"$work/window.out" 2>"$work/window.err" &
    pid=$!
    for _ in $(seq 600); do grep -q "^test: F5 at frame 5" "$work/window.out" && break; kill -0 $pid 2>/dev/null || break; sleep 0.1; done
    sed -i 's/"scale_height_km": 8\b/"scale_height_km": 9/; s/"g": 0.8/"g": 0.3/' "$work/scene.json"
    touch "$work/go"
    wait $pid
    echo $? >"$work/window.rc"
    exit 0
fi

# shellcheck source=lib/x_setup.sh
source "$(dirname "$SELF")/lib/x_setup.sh"
x_setup window_reload_test Xvfb compare
scene_src="$(dirname "$SELF")/../scenes/earth-clear.json"
# The scene says the EV100 too (the flag keeps it in every case; the file's lesson exposure would be stops).
sed 's/"exposure_ev": 0,/"exposure_ev100": 12,/' "$scene_src" >"$work/scene.json"
cp "$work/scene.json" "$work/old.json"
grep -q '"g": 0.8' "$work/scene.json" && grep -q '"scale_height_km": 8,\{0,1\}}' "$work/scene.json" \
    || { echo "window_reload_test: scenes/earth-clear.json no longer has g 0.8 and an 8 km scale height"; exit 1; }

timeout 240 "$(dirname "$SELF")/xvfb_run.sh" 640x480x24 "$SELF" "$VKSKY" --inside-xvfb "$work"
rc=$(cat "$work/window.rc" 2>/dev/null || echo 99)
[ "$rc" -eq 0 ] || fail "window run: exit status $rc (stderr: $(head -c 2000 "$work/window.err"))"
! grep -qi validation "$work/window.err" || fail "window run: validation messages: $(grep -i validation "$work/window.err" | head -5)"
grep -q "^scene reloaded: .*(LUTs recomputed" "$work/window.out" \
    || fail "no reload with new LUTs after the edit: $(cat "$work/window.out")"
grep -q "^frames 12 " "$work/window.out" || fail "the window did not present 12 frames: $(cat "$work/window.out")"

# The headless renders of the three candidates (the window's preset by name).
render() {   # render OUT.png ARGS...
    local out=$1
    shift
    "$VKSKY" "${common[@]}" --quality low "$@" --render "$work/$out" >"$work/$out.log" 2>&1 \
        || fail "vksky --render $*: $(tail -3 "$work/$out.log")"
}
render expected.png --mie-g 0.6 --scene "$work/scene.json"
render file_wins.png --scene "$work/scene.json"
render not_reloaded.png --mie-g 0.6 --scene "$work/old.json"
differing() { compare -metric AE "$work/window.png" "$work/$1" null: 2>&1 | cut -d' ' -f1; }
if [ -s "$work/window.png" ]; then
    e=$(differing expected.png) f=$(differing file_wins.png) n=$(differing not_reloaded.png)
    echo "pixels differing from the screenshot: expected $e, the file's g instead of the flag's $f, the old file $n (of 14400)"
    [ "$e" = 0 ] || fail "the window after F5 differs from vksky --render of the edited file with --mie-g 0.6 in $e pixels"
    [ "${f:-0}" -gt 1000 ] && [ "${n:-0}" -gt 1000 ] \
        || fail "the candidates are too alike to tell the override and the reload apart ($f, $n pixels)"
else
    fail "the window wrote no screenshot"
fi

echo "window_reload_test: $(($(date +%s) - t0)) s"
if [ $fails -ne 0 ]; then echo "window_reload_test: $fails failure(s)"; exit 1; fi
echo "window_reload_test: ok"
