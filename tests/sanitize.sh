#!/usr/bin/env bash
# tests/sanitize.sh [BUILD_DIR]: build vksky with AddressSanitizer + UndefinedBehaviorSanitizer (VKSKY_SANITIZE)
# and run the unit tests and the headless renders that cover every input path under them: the command line (cli:
# every bad flag), scene files (scenes, and a short scene_fuzz), the EXR/PNG writers and readers (io), the CPU
# reference and path tracer, GPU renders under validation (test_luts, test_paths, test_features), and the
# composite's readers, layers and bad inputs (composite), the graceful stop of every mode (signals, atomic_cancel:
# LeakSanitizer then checks that a stopped run destroyed what it made), the window's resizes and reloads
# (window_soak, shortened) and the fuzzers' regression inputs against the binary (app_fuzz_regressions). Any
# sanitizer report aborts that run, so the test that made it fails.
#
# LeakSanitizer is on, with suppressions (tests/lsan.supp) only for the Vulkan driver and the validation layer,
# each justified there. .ci/run runs this after the main suite. Measured: the 21 tests take 6 min 8 s (-j2, on 2
# cores shared with other builds; scene_fuzz 162 s, sequences 130 s, scenes 116 s are the long ones), the build
# 1.5 to 3 minutes more.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build-sanitize}
# VKSKY_FUZZ=OFF: the libFuzzer harnesses carry their own ASan+UBSan and run from the main build (exr_fuzz, cli_fuzz,
# scene_fuzz_lib); building them again here would only cost CI time.
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVKSKY_SANITIZE=ON -DVKSKY_FUZZ=OFF >/dev/null
cmake --build "$BUILD" -j"$(nproc)" >/dev/null
# verify_asan_link_order=0: the signals and window tests start vksky under stdbuf -oL, whose LD_PRELOAD library
# (libstdbuf: one setvbuf in a constructor, no allocator or libc interposition) then comes before the ASan runtime.
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:verify_asan_link_order=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$ROOT/tests/lsan.supp:print_suppressions=0
# scene_fuzz: fewer mutants than the main suite (each run is slower under the sanitizers).
export VKSKY_SCENE_FUZZ_MUTANTS=150
# window_soak: 2 rounds of 40 resizes (tiny, thin, unmap/map, keys, F5), for ASan and LeakSanitizer on the
# window's resize and reload paths; the resident-memory bound is off: ASan's quarantine holds freed memory (up to
# 256 MB) in the process, so VmRSS grows with every free whether or not anything leaks (LeakSanitizer checks that).
export VKSKY_SOAK_ROUNDS=2 VKSKY_SOAK_RESIZES=40 VKSKY_SOAK_RSS_BOUND_KB=100000000
cd "$BUILD"
tests='io|exr_read|solar_position|metrics|camera|barrier_table|reference|path_tracer|cli|scenes|scene_fuzz|test_luts'
tests+='|test_paths|test_features|composite|sun_place|sequences|atomic_cancel|signals|window_soak|app_fuzz_regressions'
tests+='|api_errors|api_render|api_luts'   # libvksky (issue 25): every error path, Vulkan failures included, and the renders
ctest -j"$(nproc)" --output-on-failure --timeout 600 -R "^($tests)\$"   # 600 s: a test without its own TIMEOUT
