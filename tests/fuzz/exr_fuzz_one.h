/* One fuzz input through the whole EXR input side, from memory: the header (io_exr_read_info), then every channel
 * of the file at once (io_exr_read_channels), then a name that is not there. Shared by the libFuzzer harness
 * (fuzz_exr_read.c) and the mutation runner that stands in for it without clang (exr_mutate_run.c). Header-only:
 * each includes it once. Returns 0 when the input read cleanly, 1 when it was refused (both are fine: only a
 * crash, a sanitizer report, a leak or a message that is not one line is a finding), 2 for a broken message. */
#ifndef VKSKY_TESTS_EXR_FUZZ_ONE_H
#define VKSKY_TESTS_EXR_FUZZ_ONE_H

#include "io/exr_read_internal.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Keep one input's output buffer small (4 Mi floats): the reader's own limits are tested by test_exr_read. */
#define EXR_FUZZ_MAX_VALUES (1ll << 22)

static int exr_fuzz_line_ok(const char *err) { return err[0] && !strchr(err, '\n'); }

static int exr_fuzz_one(const uint8_t *data, size_t size)
{
    io_exr_src src = io_exr_src_memory(data, size);
    io_exr_info info;
    char err[512] = "";
    if (io_exr_read_info_src(&src, &info, err, sizeof err) != 0) return exr_fuzz_line_ok(err) ? 1 : 2;
    int r = 0;
    long long values = (long long)info.width * info.height * info.channel_count;
    if (info.channel_count > 0 && info.channel_count <= 64 && values <= EXR_FUZZ_MAX_VALUES) {
        /* 300 characters: longer than any channel name a file can hold (255), so it is never found. */
        static char missing[301];
        if (!missing[0]) memset(missing, 'x', 300);
        const char *names[65];
        for (int c = 0; c < info.channel_count; ++c) names[c] = info.channels[c].name;
        names[info.channel_count] = missing;
        float *out = (float *)malloc((size_t)values * sizeof(float));
        if (out) {
            if (io_exr_read_channels_src(&src, names, info.channel_count, out, err, sizeof err) != 0)
                r = exr_fuzz_line_ok(err) ? 1 : 2;
            /* The missing name must always be refused, with the list of what is there. */
            if (io_exr_read_channels_src(&src, names + info.channel_count, 1, out, err, sizeof err) == 0 ||
                !exr_fuzz_line_ok(err))
                r = 2;
            free(out);
        }
    }
    io_exr_info_free(&info);
    return r;
}

#endif /* VKSKY_TESTS_EXR_FUZZ_ONE_H */
