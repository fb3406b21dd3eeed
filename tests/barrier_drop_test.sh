#!/usr/bin/env bash
# Each barrier proven necessary: leave one barrier out (VKSKY_DROP_BARRIER=<name>) and check that the validation
# layer, with synchronization validation, reports exactly the hazard tests/barrier_drops.txt expects for it.
#
#   barrier_drop_test.sh VKSKY LIST BARRIER CONFIG    drop BARRIER in the frame of CONFIG (a line of LIST)
#   barrier_drop_test.sh VKSKY LIST - CONFIG          drop nothing: the frame must be clean
#
# Headless configs record two frames into one command buffer (VKSKY_FRAMES=2): sync validation checks within a
# command buffer, so the second frame's first use of each image meets the first frame's last use, and the
# write-after-read barriers that only matter from the second frame on are checked too. Window configs run the
# GLFW window for two frames (under xvfb-run when there is no DISPLAY; skipped, exit 77, if neither).
#
# Reported messages are sorted into RAW / WAR / WAW (SYNC-HAZARD-READ-AFTER-WRITE, -WRITE-AFTER-READ,
# -WRITE-AFTER-WRITE), "layout" (the core checks' image-layout errors) or other:<message id>; the set must equal
# the expected one exactly, so a change in what validation sees is noticed.
set -u
VKSKY=${1:?usage: barrier_drop_test.sh VKSKY LIST BARRIER|- CONFIG}
LIST=${2:?}
NAME=${3:?}
CONFIG=${4:?}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The config line: "config ID KIND ARGS..."
read -r kind args < <(awk -v id="$CONFIG" '$1 == "config" && $2 == id { $1 = $2 = ""; sub(/^ +/, ""); print; exit }' "$LIST")
[ -n "${kind:-}" ] || { echo "FAIL: no 'config $CONFIG' line in $LIST"; exit 1; }
args=${args//OUT/$work/out}

# The barrier line: "NAME CONFIG EXPECTED [untraced] [NOTE]"
expected=none
untraced=0
if [ "$NAME" != "-" ]; then
    line=$(awk -v n="$NAME" -v c="$CONFIG" '$1 == n && $2 == c { print; exit }' "$LIST")
    [ -n "$line" ] || { echo "FAIL: no line '$NAME $CONFIG ...' in $LIST"; exit 1; }
    expected=$(awk '{ print $3 }' <<<"$line")
    [ "$(awk '{ print $4 }' <<<"$line")" = untraced ] && untraced=1
fi

run=("$VKSKY")
env_vars=(VKSKY_DROP_BARRIER="$([ "$NAME" = - ] || echo "$NAME")")
if [ "$kind" = render ]; then
    env_vars+=(VKSKY_FRAMES=2)
elif [ -z "${DISPLAY:-}" ]; then
    command -v xvfb-run >/dev/null || { echo "SKIP: no DISPLAY and no xvfb-run for the window"; exit 77; }
    run=("$(dirname "$0")/xvfb_run.sh" 640x480x24 "$VKSKY")
fi
# shellcheck disable=SC2086  # ARGS are words
env "${env_vars[@]}" "${run[@]}" $args --validate --trace-barriers >"$work/stdout" 2>"$work/stderr"
rc=$?

# What was reported, as a set: one token per distinct kind, sorted and joined by "+" like EXPECTED.
got=$(awk '
    /^vksky: validation (error|warning)/ {
        if (!match($0, /\[ [^] ]+ \]/)) { print "other:unparsed"; next }
        id = substr($0, RSTART + 2, RLENGTH - 4)
        if (id == "SYNC-HAZARD-READ-AFTER-WRITE") print "RAW"
        else if (id == "SYNC-HAZARD-WRITE-AFTER-READ") print "WAR"
        else if (id == "SYNC-HAZARD-WRITE-AFTER-WRITE") print "WAW"
        else if (id ~ /^SYNC-HAZARD-/) print substr(id, 13)
        # Core checks: an image used, transitioned or presented in a layout it is not in.
        else if (id ~ /InvalidImageLayout|oldLayout-01197|imageLayout-00344|None-02699|srcImageLayout-00189|dstImageLayout-00180|pImageIndices-01296/)
            print "layout"
        else print "other:" id
    }' "$work/stderr" | LC_ALL=C sort -u | paste -sd+ -)
got=${got:-none}
want=$(tr '+' '\n' <<<"$expected" | LC_ALL=C sort -u | paste -sd+ -)

fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
label=$([ "$NAME" = - ] && echo "clean frame ($CONFIG)" || echo "drop $NAME ($CONFIG)")
# The barrier must really have been left out (else "none" would pass for a renamed barrier).
if [ "$NAME" != - ] && [ $untraced -eq 0 ] && ! awk -v n="$NAME" '$1 == "barrier" && $2 == n && $NF == "DROPPED" { found = 1 } END { exit !found }' "$work/stdout"; then
    fail "$label: the trace shows no dropped '$NAME': was it renamed? (tools/sync_doc.sh --check-list)"
fi
[ "$got" = "$want" ] || fail "$label: validation reported {$got}, expected {$want}"
if [ "$want" = none ] && [ $rc -ne 0 ]; then fail "$label: exit status $rc, expected 0"; fi
if [ "$want" != none ] && [ $rc -ne 1 ]; then fail "$label: exit status $rc, expected 1 (validation messages)"; fi
if [ $fails -ne 0 ]; then
    echo "--- stderr (first 20 lines) ---"
    head -n 20 "$work/stderr" | cut -c1-400
    exit 1
fi
echo "ok: $label: {$got}"
