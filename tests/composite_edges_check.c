/* composite_edges_check OUT.exr HI_OUT.exr INPUT.exr LAYER [MIN_RATIO MEAN_TOL]: the composite of an anti-aliased
 * render (OUT.exr, from INPUT.exr's view layer LAYER: alpha in [0, 1], the position from one sample) against the
 * coverage-correct answer computed without vksky's edge handling: HI_OUT.exr, the composite of the same scene at
 * 4x the size with no anti-aliasing (every pixel fully covered or empty), box-filtered 4x4 (the atmosphere is
 * linear in the light: averaging the composited samples is compositing the average). On the edge pixels
 * (0 < alpha < 1) the luminance of each must be at least MIN_RATIO (default 0.5) of the answer and their mean
 * within MEAN_TOL (default 0.05); on every pixel the mean within MEAN_TOL too. A helper of tests/composite_test.sh
 * and tests/blender/; exit 0 ok, 1 a failed check or an unreadable file. */
#include "io/exr_read.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static float *read_all(const char *path, const char *const *names, int count, int *w, int *h)
{
    io_exr_info info;
    char err[512];
    if (io_exr_read_info(path, &info, err, sizeof err) != 0) {
        fprintf(stderr, "composite_edges_check: %s\n", err);
        return NULL;
    }
    *w = info.width, *h = info.height;
    io_exr_info_free(&info);
    float *out = malloc((size_t)*w * *h * count * sizeof(float));
    if (!out || io_exr_read_channels(path, names, count, out, err, sizeof err) != 0) {
        fprintf(stderr, "composite_edges_check: %s\n", out ? err : "out of memory");
        free(out);
        return NULL;
    }
    return out;
}

static double luminance(const float *rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

int main(int argc, char **argv)
{
    if (argc != 5 && argc != 7) {
        fprintf(stderr, "usage: composite_edges_check OUT.exr HI_OUT.exr INPUT.exr LAYER [MIN_RATIO MEAN_TOL]\n");
        return 1;
    }
    double min_ratio = argc == 7 ? atof(argv[5]) : 0.5, mean_tol = argc == 7 ? atof(argv[6]) : 0.05;
    static const char *const rgb[] = {"R", "G", "B"};
    char alpha_name[300];
    snprintf(alpha_name, sizeof alpha_name, "%s.Combined.A", argv[4]);
    const char *alpha_names[] = {alpha_name};
    int w, h, wh, hh, wa, ha;
    float *o = read_all(argv[1], rgb, 3, &w, &h), *hi = read_all(argv[2], rgb, 3, &wh, &hh);
    float *a = read_all(argv[3], alpha_names, 1, &wa, &ha);
    if (!o || !hi || !a) return 1;
    int ss = wh / w;
    if (ss < 1 || wh != ss * w || hh != ss * h || wa != w || ha != h) {
        fprintf(stderr, "composite_edges_check: sizes %dx%d (out), %dx%d (hi), %dx%d (input) do not match\n", w, h,
                wh, hh, wa, ha);
        return 1;
    }
    long edges = 0, dark = 0;
    double worst = INFINITY, sum_out = 0.0, sum_truth = 0.0, all_out = 0.0, all_truth = 0.0;
    long worst_at = -1;
    for (long i = 0; i < (long)w * h; ++i) {
        int x = (int)(i % w), y = (int)(i / w);
        float truth[3] = {0, 0, 0};
        for (int sy = 0; sy < ss; ++sy)
            for (int sx = 0; sx < ss; ++sx)
                for (int c = 0; c < 3; ++c)
                    truth[c] += hi[3 * ((size_t)(y * ss + sy) * wh + (size_t)(x * ss + sx)) + c] / (float)(ss * ss);
        double lo = luminance(o + 3 * i), lt = luminance(truth);
        all_out += lo, all_truth += lt;
        if (!(a[i] > 0.0f && a[i] < 1.0f)) continue;
        ++edges;
        sum_out += lo, sum_truth += lt;
        double ratio = lt > 0.0 ? lo / lt : 1.0;
        if (ratio < worst) worst = ratio, worst_at = i;
        if (!(ratio >= min_ratio)) {
            if (dark < 5)
                fprintf(stderr, "composite_edges_check: edge pixel (%d, %d), alpha %.3f: luminance %.4g, "
                        "coverage-correct %.4g (%.2fx)\n", x, y, a[i], lo, lt, ratio);
            ++dark;
        }
    }
    double mean_ratio = sum_truth > 0.0 ? sum_out / sum_truth : 1.0, all_ratio = all_truth > 0.0 ? all_out / all_truth : 1.0;
    printf("composite_edges_check: %ld edge pixels: darkest %.3fx the coverage-correct value (at %ld, %ld), mean "
           "%.4fx; every pixel: mean %.4fx; %ld darker than %.2fx\n", edges, worst, worst_at % w, worst_at / w,
           mean_ratio, all_ratio, dark, min_ratio);
    int bad = dark > 0 || edges == 0 || fabs(mean_ratio - 1.0) > mean_tol || fabs(all_ratio - 1.0) > mean_tol;
    free(o);
    free(hi);
    free(a);
    return bad;
}
