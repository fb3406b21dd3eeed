/* upsample_edges: the tone map's class-aware upsample (shaders/glsl/hdr_upsample.glsl) adds no value that the
 * full-size frame does not have nearby (a helper of tests/upsample_edges_test.sh).
 *
 *   upsample_edges HALF.exr FULL.exr TOL
 *
 * HALF: a frame rendered at --render-scale 0.5, FULL: the same view at scale 1 (bloom off, the sun's disc off).
 * Every pixel of HALF must be within TOL (relative luminance, floored at 5 % of the peak) of some pixel of FULL's 3x3 neighbourhood around it:
 * the upsample may move an edge by a pixel, never blend across it. A bilinear upsample fails at the horizon, where
 * it averages sky and ground into a value neither has. Prints the worst pixel; exit 0 within TOL, 1 outside, 2
 * unreadable input. */
#include "io/exr_read.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static double luma(const float *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: upsample_edges HALF.exr FULL.exr TOL\n");
        return 2;
    }
    int w[2], h[2];
    float *img[2];
    char err[512];
    for (int i = 0; i < 2; ++i)
        if (io_read_exr(argv[1 + i], "", &w[i], &h[i], &img[i], err, sizeof err) != 0) {
            fprintf(stderr, "upsample_edges: %s\n", err);
            return 2;
        }
    if (w[0] != w[1] || h[0] != h[1]) {
        fprintf(stderr, "upsample_edges: %dx%d and %dx%d differ\n", w[0], h[0], w[1], h[1]);
        return 2;
    }
    double tol = atof(argv[3]), peak = 0.0;
    for (size_t i = 0; i < (size_t)w[1] * (size_t)h[1]; ++i) peak = fmax(peak, luma(img[1] + 4 * i));
    /* Relative to the pixel, or to 5 % of the frame's brightest where darker: near the horizon the dark ground
     * (a few thousandths of the sky) changes by tens of percent within a pixel, which no upsample can keep. */
    double floor = 0.05 * peak, worst = 0.0;
    int wx = 0, wy = 0;
    for (int y = 0; y < h[0]; ++y)
        for (int x = 0; x < w[0]; ++x) {
            double a = luma(img[0] + 4 * ((size_t)y * w[0] + x)), best = INFINITY;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= w[1] || ny >= h[1]) continue;
                    double b = luma(img[1] + 4 * ((size_t)ny * w[1] + nx));
                    best = fmin(best, fabs(a - b) / fmax(b, floor));
                }
            if (best > worst) worst = best, wx = x, wy = y;
        }
    printf("upsample: worst pixel (%d, %d) is %.3g (relative) from its nearest full-size neighbour (bound %g)\n", wx,
           wy, worst, tol);
    free(img[0]);
    free(img[1]);
    return worst <= tol ? 0 : 1;
}
