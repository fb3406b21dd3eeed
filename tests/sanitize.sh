#!/usr/bin/env bash
# tests/sanitize.sh [BUILD_DIR]: build vksky with AddressSanitizer + UndefinedBehaviorSanitizer (VKSKY_SANITIZE)
# and run the unit tests and the headless renders that cover every input path under them: the command line (cli:
# every bad flag), scene files (scenes, and a short scene_fuzz), the EXR/PNG writers and readers (io), the CPU
# reference and path tracer, GPU renders under validation (test_luts, test_paths, test_features), and the
# composite's readers, layers and bad inputs (composite). Any
# sanitizer report aborts that run, so the test that made it fails.
#
# LeakSanitizer is on, with suppressions (tests/lsan.supp) only for the Vulkan driver and the validation layer,
# each justified there. .ci/run runs this after the main suite; budget about 3 minutes on 2 cores.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build-sanitize}
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVKSKY_SANITIZE=ON >/dev/null
cmake --build "$BUILD" -j"$(nproc)" >/dev/null
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$ROOT/tests/lsan.supp:print_suppressions=0
# scene_fuzz: fewer mutants than the main suite (each run is slower under the sanitizers).
export VKSKY_SCENE_FUZZ_MUTANTS=150
cd "$BUILD"
ctest -j"$(nproc)" --output-on-failure \
  -R '^(io|exr_read|solar_position|metrics|camera|barrier_table|reference|path_tracer|cli|scenes|scene_fuzz|test_luts|test_paths|test_features|composite|sun_place|sequences)$'
