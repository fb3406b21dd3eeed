#!/usr/bin/env bash
# Each barrier proven necessary: leave one barrier out (VKSKY_DROP_BARRIER=<name>) and check that the validation
# layer, with synchronization validation, reports exactly the hazard tests/barrier_drops.txt expects for it.
#
#   barrier_drop_test.sh VKSKY LIST BARRIER CONFIG    drop BARRIER in the frame of CONFIG (a line of LIST)
#   barrier_drop_test.sh VKSKY LIST - CONFIG          drop nothing: the frame must be clean
#   barrier_drop_test.sh VKSKY LIST NAME:FIELD[=MASK] CONFIG
#                                                     weaken one field of one barrier instead
#                                                     (VKSKY_WEAKEN_BARRIER; LIST is then tests/barrier_mutations.txt,
#                                                     the configs still come from barrier_drops.txt beside it)
#
# Headless configs record two frames into one command buffer (VKSKY_FRAMES=2): sync validation checks within a
# command buffer, so the second frame's first use of each image meets the first frame's last use, and the
# write-after-read barriers that only matter from the second frame on are checked too. Window configs run the
# GLFW window for two frames (under Xvfb (tests/xvfb_run.sh) when there is no DISPLAY; skipped, exit 77, if neither).
#
# Reported messages are sorted into RAW / WAR / WAW (SYNC-HAZARD-READ-AFTER-WRITE, -WRITE-AFTER-READ,
# -WRITE-AFTER-WRITE), "layout" (the core checks' image-layout errors) or other:<message id>; the set must equal
# the expected one exactly, so a change in what validation sees is noticed.
set -u
# No LUT cache (sky/lut_cache.h): a warm cache would upload the LUTs instead of running their passes, and the
# traced frame would depend on earlier runs. Its own frames are config lut_cache's probe, which turns it on.
export VKSKY_LUT_CACHE=0
VKSKY=${1:?usage: barrier_drop_test.sh VKSKY LIST BARRIER|- CONFIG}
LIST=${2:?}
NAME=${3:?}
CONFIG=${4:?}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The config line: "config ID KIND ARGS..." (from barrier_drops.txt beside LIST when LIST has none)
configs=$LIST
grep -q '^config ' "$LIST" || configs=$(dirname "$LIST")/barrier_drops.txt
read -r kind args < <(awk -v id="$CONFIG" '$1 == "config" && $2 == id { $1 = $2 = ""; sub(/^ +/, ""); print; exit }' "$configs")
[ -n "${kind:-}" ] || { echo "FAIL: no 'config $CONFIG' line in $LIST"; exit 1; }
args=${args//OUT/$work/out}
# A list whose frames need a compute queue of another family (tests/qfot_drops.txt, "requires
# other_compute_family": the LUTs' ownership transfer): the real queues, not the tests' one-queue mode; a device
# without such a queue skips below (exit 77, one line).
other_family=0
if grep -q '^requires other_compute_family' "$LIST"; then other_family=1; unset VKSKY_ASYNC_ONE_QUEUE; fi

# The barrier line: "NAME CONFIG EXPECTED [untraced] [NOTE]"
expected=none
untraced=0
# BARRIER_REPORT=1 (tools/mutation_matrix.sh): print what validation reports and stop; no expectation needed.
if [ "$NAME" != "-" ] && [ -z "${BARRIER_REPORT:-}" ]; then
    line=$(awk -v n="$NAME" -v c="$CONFIG" '$1 == n && $2 == c { print; exit }' "$LIST")
    [ -n "$line" ] || { echo "FAIL: no line '$NAME $CONFIG ...' in $LIST"; exit 1; }
    expected=$(awk '{ print $3 }' <<<"$line")
    [ "$(awk '{ print $4 }' <<<"$line")" = untraced ] && untraced=1
fi

run=("$VKSKY")
# NAME:FIELD[=MASK]: a mutation, else a drop.
barrier=${NAME%%:*}
if [ "$barrier" != "$NAME" ]; then
    env_vars=(VKSKY_DROP_BARRIER= VKSKY_WEAKEN_BARRIER="$NAME")
    field=${NAME#*:}
    mark="WEAKENED=${field%%=*}"
else
    env_vars=(VKSKY_DROP_BARRIER="$([ "$NAME" = - ] || echo "$NAME")" VKSKY_WEAKEN_BARRIER=)
    mark=DROPPED
fi
if [ "$kind" = probe ]; then
    # A test program in vksky's place (its path relative to vksky's directory is the first of ARGS).
    read -r probe args <<<"$args"
    run=("$(dirname "$VKSKY")/$probe")
    # A flat directory of programs (tools/qfot_drops.sh from the GPU bundle's .gpu/bin): the probe beside vksky.
    [ -x "${run[0]}" ] || [ ! -x "$(dirname "$VKSKY")/$(basename "$probe")" ] || run=("$(dirname "$VKSKY")/$(basename "$probe")")
elif [ "$kind" = render ]; then
    env_vars+=(VKSKY_FRAMES=2)
elif [ -z "${DISPLAY:-}" ]; then
    command -v Xvfb >/dev/null || { echo "SKIP: no DISPLAY and no Xvfb for the window"; exit 77; }
    run=("$(dirname "$0")/xvfb_run.sh" 640x480x24 "$VKSKY")
fi
# shellcheck disable=SC2086  # ARGS are words
env "${env_vars[@]}" "${run[@]}" $args --validate --trace-barriers >"$work/stdout" 2>"$work/stderr"
rc=$?
if [ $other_family -eq 1 ]; then
    # vksky refuses --async-luts without a second queue (exit 2, one line); a probe says so itself (exit 77).
    if [ $rc -eq 77 ] || { [ $rc -eq 2 ] && grep -q 'needs a second queue' "$work/stderr"; }; then
        echo "SKIP: needs a compute-only queue family: $(cat "$work/stdout" "$work/stderr" | grep -v '^queues ' | head -n 1 | cut -c1-200)"
        exit 77
    fi
    queues=$(grep -m1 '^queues ' "$work/stdout")
    if [ -n "$queues" ] && [[ $queues != *"another family"* ]]; then
        echo "SKIP: needs a compute-only queue family: the compute queue is of the graphics family (${queues%% (*}), so there is no ownership transfer to leave out"
        exit 77
    fi
fi

# What was reported, as a set: one token per distinct kind, sorted and joined by "+" like EXPECTED.
got=$(awk '
    /^vksky: validation (error|warning)/ {
        if (!match($0, /\[ [^] ]+ \]/)) { print "other:unparsed"; next }
        id = substr($0, RSTART + 2, RLENGTH - 4)
        if (id == "SYNC-HAZARD-READ-AFTER-WRITE") print "RAW"
        else if (id == "SYNC-HAZARD-WRITE-AFTER-READ") print "WAR"
        else if (id == "SYNC-HAZARD-WRITE-AFTER-WRITE") print "WAW"
        else if (id ~ /^SYNC-HAZARD-/) print substr(id, 13)
        # Core checks: an image used, transitioned or presented in a layout it is not in (the last three are the
        # names newer layers give them, docs/synchronization.md "What a newer layer sees").
        else if (id ~ /InvalidImageLayout|oldLayout-01197|imageLayout-00344|None-02699|srcImageLayout-00189|dstImageLayout-00180|pImageIndices-01296|None-09600|pRenderingInfo-09592|pImageIndices-01430/)
            print "layout"
        # Core checks of queue-family ownership transfers (tests/qfot_drops.txt), 1.3.239 names and newer ones: an
        # acquire whose release was never submitted; a release while the last one of the image is still unacquired.
        else if (id ~ /VkImageMemoryBarrier-image-00004|pSubmits-02207/) print "no_release"
        else if (id ~ /VkImageMemoryBarrier-image-00003/) print "pending_release"
        else print "other:" id
    }' "$work/stderr" | LC_ALL=C sort -u | paste -sd+ -)
got=${got:-none}
if [ -n "${BARRIER_REPORT:-}" ]; then
    # The report is only trusted when the barrier was really changed.
    awk -v n="$barrier" -v m="$mark" '$1 == "barrier" && $2 == n && $NF == m { found = 1 } END { exit !found }' "$work/stdout" \
        || { echo "error:untouched"; exit 0; }
    echo "$got"
    exit 0
fi
want=$(tr '+' '\n' <<<"$expected" | LC_ALL=C sort -u | paste -sd+ -)

fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
label=$([ "$NAME" = - ] && echo "clean frame ($CONFIG)" || echo "${mark%%=*} $NAME ($CONFIG)")
# The barrier must really have been left out or weakened (else "none" would pass for a renamed barrier).
if [ "$NAME" != - ] && [ $untraced -eq 0 ] && ! awk -v n="$barrier" -v m="$mark" '$1 == "barrier" && $2 == n && $NF == m { found = 1 } END { exit !found }' "$work/stdout"; then
    fail "$label: the trace shows no $mark '$barrier': was it renamed? (tools/sync_doc.sh --check-list)"
fi
[ "$got" = "$want" ] || fail "$label: validation reported {$got}, expected {$want}"
if [ "$want" = none ] && [ $rc -ne 0 ]; then fail "$label: exit status $rc, expected 0"; fi
if [ "$want" != none ] && [ $rc -ne 1 ]; then fail "$label: exit status $rc, expected 1 (validation messages)"; fi
# BARRIER_IDS=1 (tools/qfot_drops.sh): the message ids themselves, as the layer names them.
if [ -n "${BARRIER_IDS:-}" ]; then
    echo "ids: $(awk '/^vksky: validation (error|warning)/ && match($0, /\[ [^] ]+ \]/) { print substr($0, RSTART + 2, RLENGTH - 4) }' \
        "$work/stderr" | LC_ALL=C sort -u | paste -sd+ -)"
fi
if [ $fails -ne 0 ]; then
    echo "--- stderr (first 20 lines) ---"
    head -n 20 "$work/stderr" | cut -c1-400
    exit 1
fi
echo "ok: $label: {$got}"
