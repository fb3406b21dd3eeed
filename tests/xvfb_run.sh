#!/usr/bin/env bash
# tests/xvfb_run.sh SCREEN CMD [ARGS...]: run CMD under a fresh virtual X server (xvfb-run -a, screen SCREEN, e.g.
# 640x480x24) and exit with CMD's own status. xvfb-run's status is not the command's: under parallel ctest it
# exits 5 after a good run ("problem while cleaning up temporary directory"), and when two runs race for a display
# number the server never starts. A run whose command never started is retried (5 tries).
set -u
screen=${1:?usage: xvfb_run.sh SCREEN CMD [ARGS...]}
shift
status=$(mktemp)
trap 'rm -f "$status"' EXIT
for try in 1 2 3 4 5; do
    : >"$status"
    xvfb-run -a -s "-screen 0 $screen" sh -c '"$@"; echo $? >"$0"' "$status" "$@"
    [ -s "$status" ] && exit "$(cat "$status")"
    sleep "$try"
done
echo "xvfb_run.sh: the X server did not start ($try tries)" >&2
exit 1
