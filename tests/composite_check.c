/* composite_check OUT.exr RENDER.exr [SKY.exr]: the layers of a `vksky --composite` output against its input (a multilayer
 * render with ViewLayer.Combined and ViewLayer.Position, as gen_composite_scene writes it), read back through the
 * EXR reader: on every geometry pixel composite = beauty * transmittance + rayleigh + mie to fp16 precision and
 * alpha = the beauty's, with 0 < T <= 1 and the sky layers 0; on every sky pixel composite = sky + sun_disk and
 * alpha 1. With SKY.exr (a plain `vksky --render` of the same camera, no bloom): on sky pixels the composite is
 * that render to fp16 (vksky's sky along each pixel's ray). A helper of tests/composite_test.sh; exit 0 ok, 1 a
 * failed check or an unreadable file. */
#include "io/exr_read.h"
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>

static float *read_all(const char *path, const char *const *names, int count, int *w, int *h)
{
    io_exr_info info;
    char err[512];
    if (io_exr_read_info(path, &info, err, sizeof err) != 0) {
        fprintf(stderr, "composite_check: %s\n", err);
        return NULL;
    }
    *w = info.width, *h = info.height;
    io_exr_info_free(&info);
    float *out = malloc((size_t)*w * *h * count * sizeof(float));
    if (!out || io_exr_read_channels(path, names, count, out, err, sizeof err) != 0) {
        fprintf(stderr, "composite_check: %s\n", out ? err : "out of memory");
        free(out);
        return NULL;
    }
    return out;
}

int main(int argc, char **argv)
{
    if (argc != 3 && argc != 4) {
        fprintf(stderr, "usage: composite_check OUT.exr RENDER.exr [SKY.exr]\n");
        return 1;
    }
    static const char *const out_names[] = {"R", "G", "B", "A", "sky.R", "sky.G", "sky.B", "sun_disk.R", "sun_disk.G",
                                            "sun_disk.B", "transmittance.R", "transmittance.G", "transmittance.B",
                                            "rayleigh.R", "rayleigh.G", "rayleigh.B", "mie.R", "mie.G", "mie.B"};
    static const char *const in_names[] = {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B",
                                           "ViewLayer.Combined.A", "ViewLayer.Position.X", "ViewLayer.Position.Y",
                                           "ViewLayer.Position.Z"};
    int w, h, wi, hi;
    float *o = read_all(argv[1], out_names, 19, &w, &h), *in = read_all(argv[2], in_names, 7, &wi, &hi);
    if (!o || !in || w != wi || h != hi) {
        if (o && in) fprintf(stderr, "composite_check: %dx%d output for a %dx%d input\n", w, h, wi, hi);
        return 1;
    }
    static const char *const sky_names[] = {"R", "G", "B"};
    int ws = w, hs = h;
    float *sky_render = argc == 4 ? read_all(argv[3], sky_names, 3, &ws, &hs) : NULL;
    if (argc == 4 && (!sky_render || ws != w || hs != h)) {
        if (sky_render) fprintf(stderr, "composite_check: the sky render is %dx%d, the output %dx%d\n", ws, hs, w, h);
        return 1;
    }
    long geometry = 0, sky = 0, bad = 0;
    double worst_sky = 0.0;
    double worst = 0.0;
    for (long i = 0; i < (long)w * h; ++i) {
        const float *p = o + 19 * i, *b = in + 7 * i;
        bool geo = b[3] > 0.0f && isfinite(b[4]) && isfinite(b[5]) && isfinite(b[6]);
        geometry += geo, sky += !geo;
        for (int c = 0; c < 3; ++c) {
            double T = p[10 + c], R = p[13 + c], M = p[16 + c], expect, tol;
            if (geo) {
                expect = b[c] * T + R + M;
                /* Four half roundings (composite, T, R, M), each within 2^-11 relative: 2e-3 of the terms. */
                tol = 2e-3 * (fabs(b[c] * T) + R + M) + 1e-6;
                if (!(T > 0.0 && T <= 1.0) || p[4 + c] != 0.0f || p[7 + c] != 0.0f) ++bad;
            } else {
                expect = p[4 + c] + p[7 + c];
                tol = 2e-3 * expect + 1e-6;
            }
            double e = fabs(p[c] - expect);
            worst = fmax(worst, e / tol);
            if (!(e <= tol)) {
                if (bad < 5)
                    fprintf(stderr, "composite_check: pixel (%ld, %ld) channel %d: composite %g, layers give %g (%s)\n",
                            i % w, i / w, c, p[c], expect, geo ? "geometry" : "sky");
                ++bad;
            }
        }
        if (p[3] != (geo ? b[3] : 1.0f)) ++bad;
        for (int c = 0; sky_render && !geo && c < 3; ++c) {
            /* The same march, rounded to fp16 on both sides; float differences between the sky pass (fragment on
             * lavapipe) and this compute pass move it by up to 2 fp16 ulps (1.1e-3): 3e-3 allows 3. */
            double ref = sky_render[3 * i + c], tol = 3e-3 * ref + 1e-6, e = fabs(p[c] - ref);
            worst_sky = fmax(worst_sky, e / tol);
            if (!(e <= tol)) {
                if (bad < 5)
                    fprintf(stderr, "composite_check: sky pixel (%ld, %ld) channel %d: composite %g, sky render %g\n",
                            i % w, i / w, c, p[c], ref);
                ++bad;
            }
        }
    }
    printf("composite_check: %ld geometry and %ld sky pixels, worst mismatch %.2f of the fp16 tolerance%s, %ld bad\n",
           geometry, sky, worst, sky_render ? "" : " (no sky render given)", bad);
    if (sky_render) printf("composite_check: sky pixels vs the plain sky render: worst %.2f of the tolerance\n", worst_sky);
    free(sky_render);
    free(o);
    free(in);
    return bad || geometry == 0 ? 1 : 0;
}
