/* --threads and --exr-compression (options_throughput.h). */
#include "app/cli/options_throughput.h"
#include "app/cli/bad_value.h"
#include "io/encode_settings.h"
#include <stdio.h>
#include <string.h>

int options_throughput_apply(options *o, const char *n, const char *value, double x)
{
    if (!strcmp(n, "--threads")) {
        o->threads = (int)x;
        return 0;
    }
    if (!strcmp(n, "--exr-compression")) {
        int level = 0;
        int c = io_exr_compression_parse(value, &level);
        /* OpenEXRCore 3.1 (Debian 12's) reads DWAA/DWAB files but cannot write them ("not yet implemented"). */
        const char *why = c < 0 ? "unknown" : !io_exr_compression_writable(c) ? "not written by OpenEXR 3.1's C library" : NULL;
        if (why) {
            fprintf(options_report_stream(),
                    "vksky: --exr-compression: '%s': %s; expected zip, zips (each with an optional zlib level "
                    ":1 to :9), piz, pxr24, b44, b44a, rle or none\n", value, why);
            return 2;
        }
        o->exr_compression = c + 1;   /* 0: not given (ZIP) */
        o->zip_level = level;
        return 0;
    }
    return -1;
}

void options_throughput_install(const options *o)
{
    io_encode_settings s = io_encode_settings_get();
    s.threads = o->threads;
    if (o->exr_compression > 0) s.exr_compression = o->exr_compression - 1, s.zip_level = o->zip_level;
    io_encode_settings_set(&s);
}
