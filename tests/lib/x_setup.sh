# Sourced by the tests that run the window under Xvfb (window_test.sh, window_reload_test.sh, window_soak.sh): their
# set-up outside the server. `x_setup NAME TOOL...` skips the test (exit 77, ctest's "skipped") when a tool is not
# installed, then makes $work (a folder removed at exit), $fails (0) and $t0 (the start, in seconds); fail() counts a
# failure and says it on stderr.
x_setup() {
    local name=$1 tool
    shift
    for tool in "$@"; do
        command -v "$tool" >/dev/null || { echo "$name: $tool not installed; skipped"; exit 77; }
    done
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
    fails=0
    t0=$(date +%s)
}

fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
