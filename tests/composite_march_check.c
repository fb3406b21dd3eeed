/* composite_march_check FAST.exr DENSE.exr RENDER.exr BOUND_T BOUND_S: two `vksky --composite` outputs of one render
 * (RENDER.exr, gen_composite_scene's multilayer file: its alpha and position say which pixels are geometry) compared
 * layer by layer, FAST the default composite (its march's steps chosen by each segment's length, the sky
 * interpolated across tiles where that is exact enough: docs/aerial_perspective.md "Cost") and DENSE the same render
 * composited with a dense fixed march (the truth, up to its own step error and fp16). Over the geometry pixels (alpha
 * > 0, a finite position) and the sky pixels (alpha 0) apart: mean and max of |T_fast - T_dense| (per channel) and of
 * the relative in-scattering difference |S_fast - S_dense| / S_dense, S = rayleigh + mie (per channel, where S_dense
 * is above 1e-4 of the frame's largest S: fp16 and the march's own rounding below that). Exit 1 when a max exceeds
 * BOUND_T (absolute) or BOUND_S (relative), or a file is unreadable; 0 otherwise. A helper of
 * tests/composite_speed_test.sh (issue 28 item 6). */
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
        fprintf(stderr, "composite_march_check: %s\n", err);
        return NULL;
    }
    *w = info.width, *h = info.height;
    io_exr_info_free(&info);
    float *out = malloc((size_t)*w * *h * count * sizeof(float));
    if (!out || io_exr_read_channels(path, names, count, out, err, sizeof err) != 0) {
        fprintf(stderr, "composite_march_check: %s\n", out ? err : "out of memory");
        free(out);
        return NULL;
    }
    return out;
}

typedef struct stats { double sum_t, max_t, sum_s, max_s; long n_t, n_s; } stats;

int main(int argc, char **argv)
{
    if (argc != 6) {
        fprintf(stderr, "usage: composite_march_check FAST.exr DENSE.exr RENDER.exr BOUND_T BOUND_S\n");
        return 1;
    }
    static const char *const names[] = {"transmittance.R", "transmittance.G", "transmittance.B", "rayleigh.R",
                                        "rayleigh.G", "rayleigh.B", "mie.R", "mie.G", "mie.B"};
    static const char *const in_names[] = {"ViewLayer.Combined.A", "ViewLayer.Position.X", "ViewLayer.Position.Y",
                                           "ViewLayer.Position.Z"};
    int w, h, wd, hd, wi, hi;
    float *f = read_all(argv[1], names, 9, &w, &h), *d = read_all(argv[2], names, 9, &wd, &hd);
    float *in = read_all(argv[3], in_names, 4, &wi, &hi);
    if (!f || !d || !in || w != wd || h != hd || w != wi || h != hi) {
        if (f && d && in) fprintf(stderr, "composite_march_check: the files differ in size\n");
        return 1;
    }
    double bound_t = atof(argv[4]), bound_s = atof(argv[5]);
    size_t n = (size_t)w * h;
    double s_max = 0.0;
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) s_max = fmax(s_max, (double)d[9 * i + 3 + c] + d[9 * i + 6 + c]);
    stats st[2] = {{0}};   /* 0: geometry, 1: sky */
    for (size_t i = 0; i < n; ++i) {
        const float *p = in + 4 * i;
        bool geo = p[0] > 0.0f && isfinite(p[1]) && isfinite(p[2]) && isfinite(p[3]) &&
                   !(p[1] == 0.0f && p[2] == 0.0f && p[3] == 0.0f);
        stats *s = &st[geo ? 0 : 1];
        for (int c = 0; c < 3; ++c) {
            double dt = fabs((double)f[9 * i + c] - d[9 * i + c]);
            s->sum_t += dt, s->max_t = fmax(s->max_t, dt), ++s->n_t;
            double sd = (double)d[9 * i + 3 + c] + d[9 * i + 6 + c], sf = (double)f[9 * i + 3 + c] + f[9 * i + 6 + c];
            if (!(sd > 1e-4 * s_max)) continue;
            double ds = fabs(sf - sd) / sd;
            s->sum_s += ds, s->max_s = fmax(s->max_s, ds), ++s->n_s;
        }
    }
    int fails = 0;
    static const char *const kind[2] = {"geometry", "sky"};
    for (int k = 0; k < 2; ++k) {
        const stats *s = &st[k];
        if (!s->n_t) continue;
        printf("composite_march_check: %s pixels: |dT| mean %.2e max %.2e (bound %.1e); S relative mean %.2e max "
               "%.2e (bound %.1e)\n", kind[k], s->sum_t / s->n_t, s->max_t, bound_t, s->n_s ? s->sum_s / s->n_s : 0.0,
               s->max_s, bound_s);
        if (!(s->max_t <= bound_t) || !(s->max_s <= bound_s)) {
            fprintf(stderr, "composite_march_check: FAIL: %s pixels beyond the bound\n", kind[k]);
            ++fails;
        }
    }
    free(f), free(d), free(in);
    return fails ? 1 : 0;
}
