#!/usr/bin/env bash
# tests/xvfb_run.sh SCREEN CMD [ARGS...]: run CMD under a fresh virtual X server (xvfb-run -a, screen SCREEN, e.g.
# 640x480x24) and exit with CMD's own status. xvfb-run's status is not the command's: under parallel ctest it
# exits 5 after a good run ("problem while cleaning up temporary directory"), and when two runs race for a display
# number the server never starts. A run whose command never started is retried (5 tries), and so is one whose server
# never answered: the command starts only once a client can connect (xdotool getdisplaygeometry, up to 10 s). A
# sanitized window soak once found no usable display inside its xvfb-run on a loaded machine and failed every check.
set -u
screen=${1:?usage: xvfb_run.sh SCREEN CMD [ARGS...]}
shift
status=$(mktemp)
trap 'rm -f "$status"' EXIT
for try in 1 2 3 4 5; do
    : >"$status"
    xvfb-run -a -s "-screen 0 $screen" sh -c '
        if command -v xdotool >/dev/null 2>&1; then
            n=0
            until xdotool getdisplaygeometry >/dev/null 2>&1; do
                n=$((n + 1))
                [ "$n" -lt 50 ] || exit 0   # no answer in 10 s: not started, tried again
                sleep 0.2
            done
        fi
        "$@"; echo $? >"$0"' "$status" "$@"
    [ -s "$status" ] && exit "$(cat "$status")"
    sleep "$try"
done
echo "xvfb_run.sh: the X server did not start ($try tries)" >&2
exit 1
