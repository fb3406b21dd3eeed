/* libFuzzer harness for the scene loader (issue 15 item 4): the input is a scene file's bytes, loaded as
 * `vksky --scene FILE` loads it (options_parse, so the flag table's ranges and the preset order are the real ones).
 * The properties (app_fuzz_common.h): status 0 or 2; one "vksky: " line on 2; on 0 a silent load whose dump
 * round-trips. Seed corpus: the shipped scenes and the malformed ones of tests/scenes_bad (tests/fuzz/scene_corpus). */
#include "app_fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > (1 << 16)) return 0;   /* the loader's 1 MiB limit is tested elsewhere; keep executions fast */
    char *argv[] = {"vksky", "--scene", (char *)fuzz_memfile(0, (const char *)data, size), NULL};
    fuzz_check_command_line(3, argv);
    return 0;
}
