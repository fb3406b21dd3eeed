/* composite_check OUT.exr RENDER.exr [SKY.exr]: the layers of a `vksky --composite` output against its input (a multilayer
 * render with ViewLayer.Combined and ViewLayer.Position, as gen_composite_scene writes it), read back through the
 * EXR reader: on every pixel the coverage identity composite = beauty T + alpha (rayleigh + mie) + sky + sun_disk
 * to fp16 precision and alpha 1; 0 < T <= 1 where alpha > 0; sky and sun_disk 0 where alpha = 1. With SKY.exr (a
 * plain `vksky --render` of the same camera, no bloom): sky + sun_disk = (1 - alpha) x that render to fp16 (vksky's
 * sky along each pixel's ray, behind the uncovered part). A helper of tests/composite_test.sh; exit 0 ok, 1 a
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
        double alpha = fmin(fmax(b[3], 0.0), 1.0);
        bool geo = alpha > 0.0;
        geometry += geo, sky += !geo;
        for (int c = 0; c < 3; ++c) {
            /* The coverage identity (docs/aerial_perspective.md): on every pixel
             * composite = beauty T + alpha (rayleigh + mie) + sky + sun_disk. */
            double T = p[10 + c], R = p[13 + c], M = p[16 + c], S = p[4 + c], D = p[7 + c];
            double expect = b[c] * T + alpha * (R + M) + S + D;
            /* Six half roundings (composite, T, R, M, sky, sun), each within 2^-11 relative: 2e-3 of the terms. */
            double tol = 2e-3 * (fabs(b[c] * T) + alpha * (R + M) + S + D) + 1e-6;
            if (geo && !(T > 0.0 && T <= 1.0)) ++bad;
            if (alpha == 1.0 && (S != 0.0 || D != 0.0)) ++bad;   /* nothing uncovered: no sky */
            double e = fabs(p[c] - expect);
            worst = fmax(worst, e / tol);
            if (!(e <= tol)) {
                if (bad < 5)
                    fprintf(stderr, "composite_check: pixel (%ld, %ld) channel %d: composite %g, layers give %g "
                            "(alpha %g)\n", i % w, i / w, c, p[c], expect, alpha);
                ++bad;
            }
        }
        if (p[3] != 1.0f) ++bad;   /* the uncovered part is filled with sky */
        for (int c = 0; sky_render && alpha < 1.0 && c < 3; ++c) {
            /* The uncovered part is the sky along the pixel's ray: (1 - alpha) x a plain render of it. The same
             * march, rounded to fp16 on both sides; float differences between the sky pass (fragment on lavapipe)
             * and this compute pass move it by up to 2 fp16 ulps (1.1e-3): 3e-3 allows 3. */
            double ref = (1.0 - alpha) * sky_render[3 * i + c], tol = 3e-3 * ref + 1e-6;
            double e = fabs(p[4 + c] + p[7 + c] - ref);
            worst_sky = fmax(worst_sky, e / tol);
            if (!(e <= tol)) {
                if (bad < 5)
                    fprintf(stderr, "composite_check: pixel (%ld, %ld) channel %d: sky + sun_disk %g, (1 - alpha) x "
                            "the sky render %g\n", i % w, i / w, c, p[4 + c] + p[7 + c], ref);
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
