/* libFuzzer harness for the EXR input side (issue 15 item 4): built with clang -fsanitize=fuzzer,address,undefined
 * (CMake option VKSKY_FUZZ; ctest exr_fuzz runs it for a bounded time over tests/fuzz/corpus). A message that is
 * not one line aborts, so libFuzzer keeps the input as a finding like any crash. */
#include "exr_fuzz_one.h"

#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (exr_fuzz_one(data, size) == 2) abort();
    return 0;
}
