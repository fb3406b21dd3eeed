#!/usr/bin/env bash
# The interactive window under Xvfb (no window manager), every run with --validate (validation +
# synchronization validation; any message makes vksky exit 1, and stderr must not mention validation):
#  1. no display: exit 2 with one line;
#  2. >= 100 presented frames while the window is resized 3 times and minimised/restored once
#     (VKSKY_TEST_RESIZE=1 drives it from inside: no window manager is needed);
#  3. real key events (xdotool, XTEST): holding Up raises the sun from -5 deg to > +10 deg, and the screenshot
#     of that run is brighter than one of a run without keys.
# Exit 77 (ctest: skipped) when Xvfb, xdotool or ImageMagick's convert is missing.
set -u
VKSKY=${1:?usage: window_test.sh path/to/vksky}
SELF=$(readlink -f "$0")

# --- Inside Xvfb: run vksky, wait for its window, hold Up until the title shows the sun high, quit with Escape.
if [ "${2:-}" = "--keys-inside-xvfb" ]; then
    work=$3
    # A scene file to edit and reload with F5 while the window runs.
    cp "$(dirname "$SELF")/../scenes/earth-clear.json" "$work/scene.json"
    # A fixed EV100 (here and in the baseline, 3a): auto exposure, the photometric default of the window, would
    # bring both frames to the same mean level; F5 reloads the scene file, so the scene says it too.
    sed -i 's/"exposure_ev": 0,/"exposure_ev100": 12,/' "$work/scene.json"
    "$VKSKY" --validate --frames 100000 --width 320 --height 180 --sun-elevation -5 --pitch 10 --exposure 12 \
        --scene "$work/scene.json" --screenshot "$work/keys.png" >"$work/keys.out" 2>"$work/keys.err" &
    pid=$!
    # Window title "vksky | 12.3 fps | GPU 45.60 ms | sun 12.0° | ..." appears once frames are being presented.
    title() { timeout 5 xdotool getwindowname "$wid" 2>/dev/null; }
    sun_in_title() { title | sed -n 's/.*| sun \(-\{0,1\}[0-9.]*\).*/\1/p'; }
    wid=""
    for _ in $(seq 300); do
        wid=$(timeout 5 xdotool search --name '^vksky' 2>/dev/null | head -1)
        [ -n "$wid" ] && title | grep -q fps && break
        kill -0 $pid 2>/dev/null || break
        sleep 0.1
    done
    if [ -z "$wid" ]; then echo "no vksky window appeared" >"$work/keys.fail"; kill $pid; wait $pid; exit 1; fi
    # No window manager: give the window the keyboard focus ourselves (XSetInputFocus).
    timeout 10 xdotool windowfocus --sync "$wid"
    timeout 5 xdotool keydown Up
    # Hold until the effect is visible (at least 1 s, at most 30 s): not tied to the frame rate.
    sleep 1
    for _ in $(seq 290); do
        s=$(sun_in_title)
        [ -n "$s" ] && awk -v s="$s" 'BEGIN { exit !(s > 15) }' && break
        sleep 0.1
    done
    timeout 5 xdotool keyup Up
    # Edit the scene (denser Rayleigh: the LUTs must be recomputed) and reload it with F5.
    sed -i 's/"scale_height_km": 8\b/"scale_height_km": 9/' "$work/scene.json"
    timeout 5 xdotool key F5
    for _ in $(seq 100); do grep -q "scene reloaded" "$work/keys.out" && break; sleep 0.1; done
    timeout 5 xdotool key Escape   # cursor not captured: Escape quits (after one more frame: the screenshot)
    for _ in $(seq 300); do kill -0 $pid 2>/dev/null || break; sleep 0.1; done
    kill -0 $pid 2>/dev/null && { echo "vksky did not quit on Escape" >"$work/keys.fail"; kill $pid; }
    wait $pid
    echo $? >"$work/keys.rc"
    exit 0
fi

# shellcheck source=lib/x_setup.sh
source "$(dirname "$SELF")/lib/x_setup.sh"
x_setup window_test Xvfb xdotool convert
# A fresh server per run; 24-bit depth (Xvfb's default depth of 8 has no Vulkan surface formats).
xvfb() { timeout 240 "$(dirname "$SELF")/xvfb_run.sh" 1280x1024x24 "$@"; }
# expect_clean "what" rc stderr-file: exit 0 and not a word about validation on stderr.
expect_clean() {
    [ "$2" -eq 0 ] || fail "$1: exit status $2 (stderr: $(head -c 2000 "$3"))"
    ! grep -qi validation "$3" || fail "$1: validation messages: $(grep -i validation "$3" | head -5)"
}
t0=$(date +%s)

# 1. No display at all: one line, exit 2, nothing else.
env -u DISPLAY -u WAYLAND_DISPLAY "$VKSKY" --validate --frames 5 >"$work/nd.out" 2>"$work/nd.err"
rc=$?
[ $rc -eq 2 ] || fail "no display: exit status $rc, expected 2"
[ "$(wc -l <"$work/nd.err")" -eq 1 ] || fail "no display: expected one line on stderr, got: $(cat "$work/nd.err")"
grep -q "^vksky: no display available" "$work/nd.err" || fail "no display: message: $(cat "$work/nd.err")"

# 2. Resizes and a minimise/restore while presenting 120 frames.
VKSKY_TEST_RESIZE=1 xvfb "$VKSKY" --validate --frames 120 --width 320 --height 180 >"$work/rs.out" 2>"$work/rs.err"
expect_clean "resize run" $? "$work/rs.err"
grep -q "^frames 120 " "$work/rs.out" || fail "resize run: did not present 120 frames: $(cat "$work/rs.out")"
sizes=$(grep -c "^swapchain " "$work/rs.out")
distinct=$(grep "^swapchain " "$work/rs.out" | cut -d' ' -f2 | sort -u | wc -l)
[ "$sizes" -ge 4 ] && [ "$distinct" -ge 4 ] || fail "resize run: expected >= 3 recreations at new sizes: $(grep "^swapchain" "$work/rs.out")"
grep -q "^test: minimized for" "$work/rs.out" || fail "resize run: the minimised path did not run"
grep -q "^validation_messages 0$" "$work/rs.out" || fail "resize run: no validation count printed"

# 3a. Baseline: the same start without keys (sun at -5 deg).
xvfb "$VKSKY" --validate --frames 20 --width 320 --height 180 --sun-elevation -5 --pitch 10 --exposure 12 \
    --screenshot "$work/base.png" >"$work/base.out" 2>"$work/base.err"
expect_clean "baseline run" $? "$work/base.err"
grep -q "^sun_elevation -5.000$" "$work/base.out" || fail "baseline run: sun moved: $(grep sun_ "$work/base.out")"

# 3b. Hold Up under Xvfb: the sun rises above +10 deg and the sky brightens.
xvfb "$SELF" "$VKSKY" --keys-inside-xvfb "$work"
[ ! -e "$work/keys.fail" ] || fail "key run: $(cat "$work/keys.fail")"
expect_clean "key run" "$(cat "$work/keys.rc" 2>/dev/null || echo 99)" "$work/keys.err"
grep -q "scene reloaded: .*(LUTs recomputed" "$work/keys.out" \
    || fail "F5 after editing the scene's Rayleigh profile did not reload it with new LUTs: $(grep -i scene "$work/keys.out")"
elev=$(sed -n 's/^sun_elevation //p' "$work/keys.out")
awk -v e="${elev:-nan}" 'BEGIN { exit !(e > 10) }' || fail "key run: sun elevation at exit '${elev}', expected > 10"
for f in base keys; do
    [ -s "$work/$f.png" ] || { fail "$f run wrote no screenshot"; continue; }
    file "$work/$f.png" | grep -q "320 x 180, 8-bit/color RGBA" || fail "$f screenshot: $(file "$work/$f.png")"
done
if [ -s "$work/base.png" ] && [ -s "$work/keys.png" ]; then
    lb=$(convert "$work/base.png" -colorspace gray -format "%[fx:mean]" info:)
    lk=$(convert "$work/keys.png" -colorspace gray -format "%[fx:mean]" info:)
    echo "mean luminance: sun at -5 deg $lb, after holding Up (sun at $elev deg) $lk"
    awk -v a="$lb" -v b="$lk" 'BEGIN { exit !(b > a + 0.05) }' || fail "the sky did not brighten: $lb -> $lk"
fi

echo "window_test: $(($(date +%s) - t0)) s"
if [ $fails -ne 0 ]; then echo "window_test: $fails failure(s)"; exit 1; fi
echo "window_test: ok"
