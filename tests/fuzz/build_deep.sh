#!/usr/bin/env bash
# tests/fuzz/build_deep.sh OPENEXR_SRC OUT: the EXR fuzzer with OpenEXRCore itself instrumented (coverage, ASan,
# UBSan), for longer runs than ctest's: Debian's libOpenEXRCore is not instrumented, so the regular harness steers
# only by vksky's reader. OPENEXR_SRC is an OpenEXR 3.1.5 source tree (`apt-get source openexr` with deb-src, or the
# v3.1.5 tag); its src/lib/OpenEXRCore/*.c are compiled with clang beside our reader. The library's signed overflows
# are not checked (one is known, in chunk-table reconstruction: tests/exr_regressions/fuzz_core_leader_y_overflow.exr;
# it wraps and the chunk is refused, our reader gives its one line). Then run, e.g.:
#   OUT -max_total_time=600 -dict=tests/fuzz/exr.dict -rss_limit_mb=2048 -max_len=16384 CORPUS tests/fuzz/corpus
set -euo pipefail
SRC=${1:?usage: build_deep.sh OPENEXR_SRC OUT}
OUT=${2:?}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
CORE=$SRC/src/lib/OpenEXRCore
obj=$(mktemp -d)
trap 'rm -rf "$obj"' EXIT
san="-fsanitize=address,undefined -fno-sanitize=signed-integer-overflow -fno-sanitize-recover=all"
for f in "$CORE"/*.c; do
    clang -c -g -O1 -fsanitize=fuzzer-no-link $san -I"$CORE" -I/usr/include/OpenEXR -I/usr/include/Imath "$f" \
        -o "$obj/$(basename "$f" .c).o"
done
clang -g -O1 -std=c11 -D_POSIX_C_SOURCE=200809L -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
    -I"$CORE" -I/usr/include/OpenEXR -I"$ROOT/src" -I"$ROOT/tests/fuzz" "$ROOT/tests/fuzz/fuzz_exr_read.c" \
    "$ROOT/src/io/exr_read_info.c" "$ROOT/src/io/exr_read_pixels.c" "$obj"/*.o -lz -lm -lpthread -o "$OUT"
echo "built $OUT"
