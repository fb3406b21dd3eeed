/* post_compare: the compute post chain against the fragment chain (a helper of tests/post_compare_test.sh).
 *
 *   post_compare FRAG.exr COMP.exr FRAG_NOBLOOM.exr COMP_NOBLOOM.exr FRAG.png COMP.png E_TOL SHAPE_TOL LEVELS MEAN
 *
 * The bloom of a path is its composite minus its own no-bloom composite (same sky, same tone map inputs), so the
 * sky cancels and only the bloom chain is compared:
 *  - energy: the luminance sums of the two blooms differ by at most E_TOL (relative) plus the two paths'
 *    rounding difference (measured on the no-bloom frames);
 *  - shape: per pixel, |bloom_comp - bloom_frag| <= SHAPE_TOL x the fragment bloom's largest luminance, beyond
 *    the half-float rounding of the four composites;
 *  - tone-mapped pixels: the 8-bit PNGs differ by at most LEVELS in any channel and MEAN on average.
 * Prints the measured figures; exit 0 within bounds, 1 outside, 2 unreadable input. */
#include "io/exr_read.h"
#include "io/png_io.h"
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>

static float *load(const char *path, int *w, int *h)
{
    char err[512];
    float *rgba = NULL;
    if (io_read_exr(path, "", w, h, &rgba, err, sizeof err) != 0) {
        fprintf(stderr, "post_compare: %s\n", err);
        exit(2);
    }
    return rgba;
}

/* The spacing of half floats at the largest channel of p (10 mantissa bits). */
static double half_ulp(const float *p)
{
    double m = fmax(fmax(fabs(p[0]), fabs(p[1])), fabs(p[2]));
    return m < 6.1e-5 ? ldexp(1.0, -24) : ldexp(1.0, (int)floor(log2(m)) - 10);
}

static double luma(const float *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

int main(int argc, char **argv)
{
    if (argc != 11) {
        fprintf(stderr, "usage: post_compare FRAG.exr COMP.exr FRAG_NB.exr COMP_NB.exr FRAG.png COMP.png E_TOL SHAPE_TOL LEVELS MEAN\n");
        return 2;
    }
    int w[4], h[4];
    float *img[4];
    for (int i = 0; i < 4; ++i) img[i] = load(argv[1 + i], &w[i], &h[i]);
    for (int i = 1; i < 4; ++i)
        if (w[i] != w[0] || h[i] != h[0]) {
            fprintf(stderr, "post_compare: %s is %dx%d, %s is %dx%d\n", argv[1 + i], w[i], h[i], argv[1], w[0], h[0]);
            return 2;
        }
    size_t n = (size_t)w[0] * (size_t)h[0];
    double e_frag = 0, e_comp = 0, peak = 0, worst = 0, base_diff = 0, base_abs = 0;
    size_t worst_at = 0, peak_at = 0;
    for (size_t i = 0; i < n; ++i) {
        double bf = luma(img[0] + 4 * i) - luma(img[2] + 4 * i), bc = luma(img[1] + 4 * i) - luma(img[3] + 4 * i);
        e_frag += bf, e_comp += bc;
        base_diff += luma(img[3] + 4 * i) - luma(img[2] + 4 * i);
        base_abs += fabs(luma(img[3] + 4 * i) - luma(img[2] + 4 * i));
        if (bf > peak) peak = bf, peak_at = i;
    }
    for (size_t i = 0; i < n; ++i) {
        double bf = luma(img[0] + 4 * i) - luma(img[2] + 4 * i), bc = luma(img[1] + 4 * i) - luma(img[3] + 4 * i);
        /* Each composite is stored as half floats, and the two paths may round a value differently (a fragment
         * output's conversion vs imageStore's): four composites, up to one half-float step (ulp) each. */
        double ulp = 4.0 * half_ulp(img[0] + 4 * i);
        double d = fmax(fabs(bc - bf) - ulp, 0.0) / (peak > 0 ? peak : 1);
        if (d > worst) worst = d, worst_at = i;
    }
    int pw, ph, qw, qh;
    uint8_t *pf = NULL, *pc = NULL;
    char err[512];
    if (io_read_png(argv[5], &pw, &ph, &pf, err, sizeof err) != 0 || io_read_png(argv[6], &qw, &qh, &pc, err, sizeof err) != 0) {
        fprintf(stderr, "post_compare: %s\n", err);
        return 2;
    }
    if (pw != qw || ph != qh) {
        fprintf(stderr, "post_compare: the PNGs differ in size\n");
        return 2;
    }
    int max_levels = 0;
    double sum_levels = 0;
    for (size_t i = 0; i < (size_t)pw * (size_t)ph; ++i)
        for (int c = 0; c < 3; ++c) {
            int d = abs((int)pf[4 * i + c] - (int)pc[4 * i + c]);
            if (d > max_levels) max_levels = d;
            sum_levels += d;
        }
    double mean_levels = sum_levels / (3.0 * (double)pw * (double)ph);
    double e_rel = e_frag > 0 ? fabs(e_comp - e_frag) / e_frag : (e_comp == 0 ? 0 : INFINITY);
    double e_tol = atof(argv[7]), shape_tol = atof(argv[8]), mean_tol = atof(argv[10]);
    int levels_tol = atoi(argv[9]);
    printf("bloom energy: fragment %.6g compute %.6g (relative difference %.3g)\n", e_frag, e_comp, e_rel);
    printf("no-bloom composites (same sky, rounding only): compute - fragment sums to %.4g (|.| %.4g)\n", base_diff, base_abs);
    printf("bloom shape: largest difference %.3g of the peak %.6g at (%d, %d) (bound %g; the peak is at (%d, %d))\n",
           worst, peak, (int)(worst_at % (size_t)w[0]), (int)(worst_at / (size_t)w[0]), shape_tol,
           (int)(peak_at % (size_t)w[0]), (int)(peak_at / (size_t)w[0]));
    printf("tone-mapped pixels: max %d levels (bound %d), mean %.4f levels (bound %g)\n", max_levels, levels_tol,
           mean_levels, mean_tol);
    /* The energy bound: E_TOL of the fragment bloom's energy, plus what rounding alone can move it by — the two
     * paths round a composite differently (lavapipe's fragment outputs truncate, imageStore rounds to nearest),
     * measured on the no-bloom frames as the summed per-pixel difference of two renders of the same sky. */
    bool energy_ok = e_frag > 0 && fabs(e_comp - e_frag) <= e_tol * e_frag + base_abs;
    printf("bloom energy bound: |difference| %.4g <= %g x %.4g + rounding %.4g: %s\n", fabs(e_comp - e_frag), e_tol,
           e_frag, base_abs, energy_ok ? "yes" : "NO");
    int ok = energy_ok && worst <= shape_tol && max_levels <= levels_tol && mean_levels <= mean_tol;
    for (int i = 0; i < 4; ++i) free(img[i]);
    free(pf);
    free(pc);
    return ok ? 0 : 1;
}
