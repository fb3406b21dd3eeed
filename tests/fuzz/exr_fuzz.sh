#!/usr/bin/env bash
# ctest exr_fuzz: fuzz the EXR input side for a bounded time over the committed seed corpus (tests/fuzz/corpus).
# With the libFuzzer harness (built by clang when the CMake option VKSKY_FUZZ is on and clang's fuzzer runtime is
# installed: Debian clang + libclang-rt-14-dev) it runs that, under AddressSanitizer and UBSan; without it, the
# mutation runner (tests/fuzz/exr_mutate_run.c, any compiler) over the same corpus. A finding fails the test and
# names the saved input: minimise it, add it to tests/exr_regressions/ (ctest exr_regressions reads them all).
# Usage: exr_fuzz.sh FUZZER|- MUTATE_RUN CORPUS_DIR SECONDS
set -u
FUZZER=${1:?usage: exr_fuzz.sh FUZZER|- MUTATE_RUN CORPUS_DIR SECONDS}
MUTATE=${2:?}
CORPUS=${3:?}
SECONDS_=${VKSKY_EXR_FUZZ_SECONDS:-${4:-40}}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ "$FUZZER" != "-" ] && [ -x "$FUZZER" ]; then
    mkdir -p "$work/corpus" "$work/findings"
    # Inputs grown in the run go to a scratch copy: the committed corpus stays as it is.
    "$FUZZER" -max_total_time="$SECONDS_" -rss_limit_mb=2048 -max_len=16384 -timeout=10 \
        -dict="$here/exr.dict" -artifact_prefix="$work/findings/" -print_final_stats=1 \
        "$work/corpus" "$CORPUS" >"$work/log" 2>&1
    rc=$?
    grep -E '^(Done|stat::(number_of_executed_units|average_exec_per_sec|new_units_added|peak_rss_mb))' "$work/log"
    if [ $rc -ne 0 ]; then
        tail -n 40 "$work/log" >&2
        mkdir -p exr_fuzz_findings && cp "$work"/findings/* exr_fuzz_findings/ 2>/dev/null
        echo "FAIL: libFuzzer finding, saved in $(pwd)/exr_fuzz_findings/ (add it to tests/exr_regressions/)" >&2
        exit 1
    fi
    echo "exr_fuzz: libFuzzer, $SECONDS_ s, no findings"
else
    mkdir -p exr_fuzz_findings
    "$MUTATE" "$CORPUS" "$SECONDS_" "${VKSKY_EXR_FUZZ_SEED:-$(date +%s)}" "$(pwd)/exr_fuzz_findings" || {
        echo "FAIL: mutation runner finding, saved in $(pwd)/exr_fuzz_findings/ (add it to tests/exr_regressions/)" >&2
        exit 1
    }
    echo "exr_fuzz: mutation runner (no libFuzzer build), $SECONDS_ s, no findings"
fi
