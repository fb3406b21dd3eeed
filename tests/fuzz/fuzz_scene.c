/* libFuzzer harness for the scene loader (issue 15 item 4): the input is a scene file's bytes, loaded as
 * `vksky --scene FILE` loads it (options_parse, so the flag table's ranges and the preset order are the real ones).
 * An input that starts like an OpenEXR file is loaded as `--scene FRAME.exr`: the scene an EXR made by vksky carries
 * in its header (the EXR header reader, then the same JSON loader). The properties (app_fuzz_common.h): status 0 or
 * 2; one "vksky: " line on 2; on 0 a silent load whose dump round-trips. Seed corpus (tests/fuzz/scene_corpus): the
 * shipped scenes, the malformed ones of tests/scenes_bad, 1x1 EXRs vksky rendered from each shipped scene, and an
 * EXR without a scene. */
#include "app_fuzz_common.h"

#include <stdlib.h>

static char exr_link[64];

static void remove_exr_link(void)
{
    unlink(exr_link);
    *strrchr(exr_link, '/') = '\0';
    rmdir(exr_link);
}

/* A path ending in ".exr" (the loader picks the reader by the name) for the memory file: a symlink in a directory of
 * our own to /proc/self/fd/N, made once. */
static const char *exr_path(const char *memfile)
{
    if (!exr_link[0]) {
        char dir[] = "/tmp/vksky-fuzz-XXXXXX";
        if (!mkdtemp(dir)) fuzz_fail("mkdtemp", NULL);
        snprintf(exr_link, sizeof exr_link, "%s/scene.exr", dir);
        if (symlink(memfile, exr_link) != 0) fuzz_fail("symlink", exr_link);
        atexit(remove_exr_link);
    }
    return exr_link;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > (1 << 16)) return 0;   /* the loader's 1 MiB limit is tested elsewhere; keep executions fast */
    const char *path = fuzz_memfile(0, (const char *)data, size);
    static const uint8_t exr_magic[4] = {0x76, 0x2f, 0x31, 0x01};
    if (size >= 4 && !memcmp(data, exr_magic, 4)) path = exr_path(path);
    char *argv[] = {"vksky", "--scene", (char *)path, NULL};
    fuzz_check_command_line(3, argv);
    return 0;
}
