/* spectral_compare TEST.exr REF.exr [MAX_LUM_P95 MAX_DE_P95]: the colour axis of an image against a reference
 * (issue 32): the relative luminance error (metrics_relative_luminance, its default floor) and CIEDE2000 per pixel in
 * CIELAB with the D65 white at the reference pixel's own luminance (the reference is L* = 100, so a luminance error
 * shows as lightness too; tools/color_error's convention), over pixels at least 1e-4 of the reference's brightest.
 * Also the sRGB PSNR (srgb_psnr, below). Prints one line; with limits, exits 1 when the 95th percentile of either is
 * over its limit. */
#include "io/exr_read.h"
#include "io/png_io.h"
#include "reference/metrics.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void rec709_to_xyz(const float *c, double o[3])
{
    o[0] = 0.4124 * c[0] + 0.3576 * c[1] + 0.1805 * c[2];
    o[1] = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    o[2] = 0.0193 * c[0] + 0.1192 * c[1] + 0.9505 * c[2];
}

static double lab_f(double t) { return t > 216.0 / 24389.0 ? cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0; }

static void xyz_to_lab(const double xyz[3], double yn, double lab[3])
{
    double fx = lab_f(xyz[0] / (0.95047 * yn)), fy = lab_f(xyz[1] / yn), fz = lab_f(xyz[2] / (1.08883 * yn));
    lab[0] = 116.0 * fy - 16.0;
    lab[1] = 500.0 * (fx - fy);
    lab[2] = 200.0 * (fy - fz);
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* spectral_compare --png TEST.png REF.exr EV100 [MAX_DE]: a PNG against a reference in cd/m2 (issue 32: the spectral
 * sum's PNG): the reference tone-mapped at EV100 (the multiplier 1 / (1.2 2^EV100), ACES, sRGB, 8 bits:
 * metrics_tonemap_srgb8, the renderer's law), then CIEDE2000 per pixel between the two 8-bit sRGB images (CIELAB, the
 * sRGB white), over every pixel. One line; with MAX_DE, exit 1 when the largest is over it. */
static int compare_png(int argc, char **argv)
{
    int w, h, rw, rh;
    uint8_t *t = NULL;
    float *r = NULL;
    char err[512];
    if (io_read_png(argv[2], &w, &h, &t, err, sizeof err) || io_read_exr(argv[3], "", &rw, &rh, &r, err, sizeof err)) {
        fprintf(stderr, "spectral_compare: %s\n", err);
        return 2;
    }
    if (w != rw || h != rh) {
        fprintf(stderr, "spectral_compare: sizes differ (%dx%d, %dx%d)\n", w, h, rw, rh);
        return 2;
    }
    size_t n = (size_t)w * h;
    unsigned char *ref = malloc(n * 4);
    metrics_tonemap_srgb8(r, w, h, -log2(1.2) - atof(argv[4]), 2 /* ACES */, ref);
    double sum = 0.0, worst = 0.0;
    for (size_t i = 0; i < n; ++i) {
        double lt[3], lr[3];
        metrics_srgb8_to_lab(t + 4 * i, lt);
        metrics_srgb8_to_lab(ref + 4 * i, lr);
        double d = metrics_ciede2000(lr, lt);
        d = isfinite(d) ? d : INFINITY;
        sum += d, worst = fmax(worst, d);
    }
    printf("png CIEDE2000 mean %.3f max %.3f (%zu pixels)\n", sum / n, worst, n);
    int status = argc == 6 && !(worst <= atof(argv[5])) ? 1 : 0;
    free(ref);
    free(r);
    free(t);
    return status;
}

/* Bruneton's image measure (precomputed_atmospheric_scattering's evaluation: sRGB PSNR against a many-wavelength
 * reference), our way: both images through one tone map (ACES fitted, at the exposure that puts the reference's
 * log-average luminance at the key 0.18) and the sRGB encode, in floats (no 8-bit step), then
 * 10 log10(1 / MSE) over every pixel and channel. */
static double srgb_encoded(double x)
{
    x = x < 0.0 ? 0.0 : x;
    x = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
    x = x > 1.0 ? 1.0 : x;
    return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

static double srgb_psnr(const float *t, const float *r, size_t n)
{
    double log_sum = 0.0, se = 0.0;
    for (size_t i = 0; i < n; ++i)
        log_sum += log(fmax(0.2126 * r[4 * i] + 0.7152 * r[4 * i + 1] + 0.0722 * r[4 * i + 2], 1e-9));
    double scale = 0.18 / exp(log_sum / (double)n);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            double d = srgb_encoded(scale * t[4 * i + c]) - srgb_encoded(scale * r[4 * i + c]);
            se += d * d;
        }
    double mse = se / (3.0 * (double)n);
    return mse > 0.0 ? 10.0 * log10(1.0 / mse) : INFINITY;
}

int main(int argc, char **argv)
{
    if (argc >= 5 && argc <= 6 && !strcmp(argv[1], "--png")) return compare_png(argc, argv);
    if (argc != 3 && argc != 5) {
        fprintf(stderr, "usage: spectral_compare TEST.exr REF.exr [MAX_LUM_P95 MAX_DE_P95]\n");
        return 2;
    }
    int w, h, rw, rh;
    float *t = NULL, *r = NULL;
    char err[512];
    if (io_read_exr(argv[1], "", &w, &h, &t, err, sizeof err) ||
        io_read_exr(argv[2], "", &rw, &rh, &r, err, sizeof err)) {
        fprintf(stderr, "spectral_compare: %s\n", err);
        return 2;
    }
    if (w != rw || h != rh) {
        fprintf(stderr, "spectral_compare: sizes differ (%dx%d, %dx%d)\n", w, h, rw, rh);
        return 2;
    }
    metrics_luminance lum = metrics_relative_luminance(t, r, NULL, w, h, 0.0);
    size_t n = (size_t)w * h, count = 0;
    double ymax = 0.0, sum = 0.0, *de = malloc(n * sizeof *de);
    for (size_t i = 0; i < n; ++i) {
        double x[3];
        rec709_to_xyz(r + 4 * i, x);
        ymax = fmax(ymax, x[1]);
    }
    for (size_t i = 0; i < n; ++i) {
        double xr[3], xt[3], lr[3], lt[3];
        rec709_to_xyz(r + 4 * i, xr);
        rec709_to_xyz(t + 4 * i, xt);
        if (!(xr[1] > 1e-4 * ymax)) continue;
        xyz_to_lab(xr, xr[1], lr);
        xyz_to_lab(xt, xr[1], lt);
        double d = metrics_ciede2000(lr, lt);
        de[count++] = isfinite(d) ? d : INFINITY;
        sum += de[count - 1];
    }
    qsort(de, count, sizeof *de, cmp);
    double psnr = srgb_psnr(t, r, n);
    double de_p95 = count ? de[(size_t)ceil(0.95 * count) - 1] : 0.0, de_max = count ? de[count - 1] : 0.0;
    printf("luminance error mean %.3f %% p95 %.3f %% max %.3f %%; CIEDE2000 mean %.3f p95 %.3f max %.3f (%zu pixels); "
           "sRGB PSNR %.1f dB\n", 100 * lum.mean, 100 * lum.p95, 100 * lum.max, count ? sum / count : 0.0, de_p95, de_max,
           count, psnr);
    int status = 0;
    if (argc == 5) {
        double max_lum = atof(argv[3]), max_de = atof(argv[4]);
        if (!(lum.p95 <= max_lum)) printf("FAIL: luminance error p95 %.4f over %.4f\n", lum.p95, max_lum), status = 1;
        if (!(de_p95 <= max_de)) printf("FAIL: CIEDE2000 p95 %.3f over %.3f\n", de_p95, max_de), status = 1;
    }
    free(de);
    free(t);
    free(r);
    return status;
}
