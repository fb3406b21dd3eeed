/* exr_probe FILE.exr X Y [X Y ...]: print "R G B" (scene-linear, %.6g) of each pixel (x, y), y = 0 at the top, one
 * line per pixel. A helper of tests/scene_test.sh. Exit 0 ok, 1 unreadable file, 2 bad arguments or a pixel out
 * of the image. */
#include "io/exr_read.h"
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    if (argc < 4 || (argc - 2) % 2 != 0) {
        fprintf(stderr, "usage: exr_probe FILE.exr X Y [X Y ...]\n");
        return 2;
    }
    int w = 0, h = 0;
    float *rgba = NULL;
    char err[512];
    if (io_read_exr(argv[1], "", &w, &h, &rgba, err, sizeof err) != 0) {
        fprintf(stderr, "exr_probe: %s\n", err);
        return 1;
    }
    int rc = 0;
    for (int i = 2; i + 1 < argc; i += 2) {
        char *end_x = NULL, *end_y = NULL;
        long x = strtol(argv[i], &end_x, 10), y = strtol(argv[i + 1], &end_y, 10);
        if (*end_x || *end_y || x < 0 || y < 0 || x >= w || y >= h) {
            fprintf(stderr, "exr_probe: pixel (%s, %s) is not in the %dx%d image\n", argv[i], argv[i + 1], w, h);
            rc = 2;
            break;
        }
        const float *p = rgba + 4 * ((size_t)y * (size_t)w + (size_t)x);
        printf("%.6g %.6g %.6g\n", p[0], p[1], p[2]);
    }
    free(rgba);
    return rc;
}
