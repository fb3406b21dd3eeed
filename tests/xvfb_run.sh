#!/usr/bin/env bash
# tests/xvfb_run.sh SCREEN CMD [ARGS...]: run CMD under a fresh virtual X server (Xvfb, screen SCREEN, e.g.
# 640x480x24) and exit with CMD's own status.
#
# Not xvfb-run. Three ways it failed the suite:
#  - its status is not the command's: under parallel ctest it exits 5 after a good run ("problem while cleaning up
#    temporary directory");
#  - `xvfb-run -a` picks a display number by looking for a free lock file, then starts the server on it: two runs
#    that look at once pick the same number, and the loser's server never starts;
#  - its server resets when its last client disconnects (the tests' xdotool polls connect and disconnect many times
#    a second), and a sanitized window soak on a loaded CI machine once found "no display available" after a probe
#    had connected: its window was the next client.
# Here Xvfb chooses the display itself (-displayfd: it takes the first number whose lock it wins and writes it once
# it accepts connections), never resets (-noreset), and listens on the local socket only. Access is the server's
# default for a server without an authority file: local clients only. A server that does not report a display
# within 20 s is stopped and started again (3 tries); its own messages go to stderr only then.
set -u
screen=${1:?usage: xvfb_run.sh SCREEN CMD [ARGS...]}
shift
tmp=$(mktemp -d)
server=""
stop_server() {
    if [ -n "$server" ]; then kill "$server" 2>/dev/null; wait "$server" 2>/dev/null; fi
    server=""
}
trap 'stop_server; rm -rf "$tmp"' EXIT
trap 'exit 143' TERM
trap 'exit 130' INT
for try in 1 2 3; do
    : >"$tmp/display"
    Xvfb -displayfd 3 -noreset -nolisten tcp -screen 0 "$screen" 3>"$tmp/display" >"$tmp/log" 2>&1 &
    server=$!
    for _ in $(seq 200); do
        grep -q '^[0-9][0-9]*$' "$tmp/display" && break
        kill -0 "$server" 2>/dev/null || break
        sleep 0.1
    done
    display=$(head -1 "$tmp/display")
    if [ -n "$display" ] && kill -0 "$server" 2>/dev/null; then
        DISPLAY=":$display" "$@"
        exit $?
    fi
    echo "xvfb_run.sh: Xvfb reported no display (try $try): $(tail -c 400 "$tmp/log")" >&2
    stop_server
    sleep "$try"
done
echo "xvfb_run.sh: the X server did not start (3 tries)" >&2
exit 1
