# Sourced by tests/async_luts_test.sh and tools/async_bench.sh: the --async-luts pixel comparison they share.
# The LUT variants whose LUT set or first LUT reader differs, one "NAME EXTRA-FLAGS" a line (async_variants), and
# one variant's pair of renders (async_pair): two frames each rebuilding the LUTs (VKSKY_FRAMES=2), on one queue and
# with --async-luts (its trace kept), compared by EXR pixels (exr_pixels same) and PNG bytes.
# The caller sets VKSKY (the binary), PIX (exr_pixels), work (a temporary folder) and the array A (the common flags,
# --validate among them).

async_variants() {
    cat <<'LIST'
default
skyview --sky-mode skyview
compute --sky-pass compute
noms --no-multiscatter
ground --ground-albedo 0.3,0.3,0.3 --pitch -20
LIST
}

# async_pair I NAME EXTRA...: $work/s$I.{exr,png} on one queue, $work/a$I.{exr,png} and $work/a$I.trace with
# --async-luts. Prints why on stdout and returns 1 when a run fails or writes anything on stderr (any validation
# message), 2 when the pixels differ; 0 when they are identical.
async_pair() {
    local i=$1 name=$2 rc
    shift 2
    VKSKY_FRAMES=2 "$VKSKY" --render "$work/s$i.exr" --render "$work/s$i.png" "${A[@]}" "$@" 2>"$work/s$i.err" \
        || { echo "$name: single-queue frames failed: $(head -c 300 "$work/s$i.err")"; return 1; }
    VKSKY_FRAMES=2 "$VKSKY" --render "$work/a$i.exr" --render "$work/a$i.png" "${A[@]}" "$@" --async-luts \
        --trace-barriers >"$work/a$i.trace" 2>"$work/a$i.err"
    rc=$?
    if [ $rc -ne 0 ] || [ -s "$work/a$i.err" ]; then
        echo "$name: --async-luts: exit $rc: $(head -c 600 "$work/a$i.err")"; return 1
    fi
    "$PIX" same "$work/s$i.exr" "$work/a$i.exr" || { echo "$name: EXR pixels differ from the single-queue frames"; return 2; }
    cmp -s "$work/s$i.png" "$work/a$i.png" || { echo "$name: PNG differs from the single-queue frames"; return 2; }
    return 0
}
