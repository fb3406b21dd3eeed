/* exr_inflate_check FILE...: each EXR read through io_read_exr twice, once with vksky's ZIP/ZIPS inflate (libdeflate)
 * and once with OpenEXRCore's own decompress step (VKSKY_EXR_ZLIB_INFLATE=1); exit 0 when every file's pixels are
 * bit-identical between the two (and non-empty), else 1 naming the file. The first read decodes chunks on 3 threads,
 * the second on 1: the pixels must not depend on the thread count either. Issue 28. */
#include "io/encode_settings.h"
#include "io/exr_read.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    int bad = 0;
    for (int i = 1; i < argc; ++i) {
        char err[512];
        int w[2] = {0, 0}, h[2] = {0, 0};
        float *px[2] = {NULL, NULL};
        for (int pass = 0; pass < 2; ++pass) {
            setenv("VKSKY_EXR_ZLIB_INFLATE", pass ? "1" : "0", 1);
            io_encode_settings settings = io_encode_settings_get();
            settings.threads = pass ? 1 : 3;
            io_encode_settings_set(&settings);
            if (io_read_exr(argv[i], "", &w[pass], &h[pass], &px[pass], err, sizeof err) != 0) {
                fprintf(stderr, "exr_inflate_check: %s\n", err);
                return 1;
            }
        }
        size_t n = (size_t)w[0] * (size_t)h[0] * 4;
        if (w[0] != w[1] || h[0] != h[1] || n == 0 || memcmp(px[0], px[1], n * sizeof(float)) != 0) {
            fprintf(stderr, "exr_inflate_check: %s: libdeflate's pixels differ from OpenEXRCore's\n", argv[i]);
            bad = 1;
        } else {
            printf("%s: %dx%d identical\n", argv[i], w[0], h[0]);
        }
        free(px[0]), free(px[1]);
    }
    return bad;
}
