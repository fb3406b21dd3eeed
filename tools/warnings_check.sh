#!/usr/bin/env bash
# tools/warnings_check.sh [BUILD_ROOT]: build-only check that the code is warning-free with the compilers and
# optimisation levels users and distributions build with: gcc Release (-O3, where -Wmaybe-uninitialized sees the
# most) and clang Release (-O3), both with -DVKSKY_WERROR=ON so that any warning fails. The main CI build
# (RelWithDebInfo, -O2) covers gcc -O2. Nothing runs: compiling is the check. .ci/run calls it after the tests.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=${1:-$ROOT/build-warnings}
jobs=$(nproc)
check() {   # check NAME C_COMPILER
    local dir=$OUT/$1
    if ! command -v "$2" >/dev/null; then echo "warnings_check: $2 not found (tools/debian-packages.txt lists it)" >&2; exit 2; fi
    # VKSKY_FUZZ=OFF: the fuzz harnesses are built (clang, -O1 + sanitizers) and run by the main build already.
    CC=$2 cmake -S "$ROOT" -B "$dir" -DCMAKE_BUILD_TYPE=Release -DVKSKY_WERROR=ON -DVKSKY_FUZZ=OFF >/dev/null
    if ! cmake --build "$dir" -j"$jobs" >"$dir/build.log" 2>&1; then
        grep -E -A4 'warning|error' "$dir/build.log" | head -60 >&2
        echo "warnings_check: $1 build ($2 -O3, -Werror) failed; log: $dir/build.log" >&2
        exit 1
    fi
    echo "warnings_check: $1 ($2 -O3 -Wall -Wextra -Werror): clean"
}
check gcc-O3 gcc
check clang clang-14
