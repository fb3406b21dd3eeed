#!/usr/bin/env bash
# ctests cli_fuzz and scene_fuzz_lib (issue 15 item 4): a libFuzzer harness (fuzz_cli or fuzz_scene, built with clang
# when VKSKY_FUZZ is on) first replays every committed regression input, then fuzzes for a bounded time over the
# committed seed corpus (a scratch copy grows; the committed one stays as it is), with a dictionary of every flag name
# in the flag table (read from src/app/*.c, so new flags join by themselves) and the words the parser knows. A finding
# fails the test and is saved as ./app_fuzz_findings/NAME: minimise it (FUZZER -minimize_crash=1 FILE), add it to the
# regression directory, fix the bug.
# Usage: app_fuzz.sh FUZZER CORPUS_DIR REGRESSIONS_DIR SECONDS
set -u
FUZZER=${1:?usage: app_fuzz.sh FUZZER CORPUS_DIR REGRESSIONS_DIR SECONDS}
CORPUS=${2:?}
REGRESSIONS=${3:?}
SECONDS_=${VKSKY_APP_FUZZ_SECONDS:-${4:-25}}
here=$(cd "$(dirname "$0")" && pwd)
name=$(basename "$FUZZER")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# LeakSanitizer with the driver's and the validation layer's leaks suppressed by library (tests/lsan.supp, as
# tests/sanitize.sh): lavapipe (Mesa 22.3.6-1+deb12u2) leaks 128 B once in vkEnumeratePhysicalDevices, which the
# harness's device probe reaches; never a suppression for vksky's own code.
export LSAN_OPTIONS="suppressions=$here/../lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"

# 1. The regression inputs, each run once (libFuzzer runs the files it is given and exits).
regs=("$REGRESSIONS"/*)
if [ -e "${regs[0]}" ]; then
    "$FUZZER" -close_fd_mask=1 "${regs[@]}" >"$work/reg.log" 2>&1 || {
        tail -n 30 "$work/reg.log" >&2
        echo "FAIL: $name: a regression input fails again" >&2
        exit 1
    }
    echo "$name: ${#regs[@]} regression inputs pass"
fi

# 2. The dictionary: flag names (every "--name" string in src/app: the table's and the composite's), and the
#    value words and separators the parsers read.
{
    cat "$here/../../src/app/"*.c | grep -oE '"--[a-z0-9-]+"' | sort -u
    # the scene loader's field names and words, as JSON strings ("\"camera\"")
    cat "$here/../../src/app/"scene*.c | grep -oE '"[a-z][a-z0-9_]*"' | sort -u | sed 's/"/\\"/g; s/.*/"&"/'
    for w in low medium high ultra clamp reinhard aces march skyview auto fill fragment compute f16 f32 hg \
             cornette-shanks henyey-greenstein exponential tent layers true false null x , = .exr .png .json; do
        printf '"%s"\n' "$(printf '%s' "$w" | sed 's/\\/\\\\/g; s/"/\\"/g')"
    done
    # the scene harness reads EXR headers too (--scene FRAME.exr): the EXR fuzzer's dictionary, and the attribute
    [ "$name" = fuzz_scene ] && grep -v '^#' "$here/exr.dict" && echo '"vksky:scene"'
} >"$work/dict"

# 3. Fuzz (-max_len: the scene corpus's EXRs are up to 4 kB). -close_fd_mask=1: what a parse prints on stdout
#    (--max-error's choice) is not looked at.
mkdir -p "$work/corpus" "$work/findings"
"$FUZZER" -max_total_time="$SECONDS_" -rss_limit_mb=2048 -max_len=8192 -timeout=10 -close_fd_mask=1 \
    -dict="$work/dict" -artifact_prefix="$work/findings/" -print_final_stats=1 \
    "$work/corpus" "$CORPUS" >"$work/log" 2>&1
rc=$?
grep -E '^(Done|stat::(number_of_executed_units|average_exec_per_sec|new_units_added|peak_rss_mb))' "$work/log"
grep -E '^#[0-9]+.*(INITED|DONE)' "$work/log" | tail -2
if [ $rc -ne 0 ]; then
    tail -n 40 "$work/log" >&2
    mkdir -p app_fuzz_findings && cp "$work"/findings/* app_fuzz_findings/ 2>/dev/null
    echo "FAIL: $name: libFuzzer finding, saved in $(pwd)/app_fuzz_findings/ (add it to $REGRESSIONS)" >&2
    exit 1
fi
echo "$name: $SECONDS_ s, no findings"
