/* vksky error metrics: see metrics.h. */
#include "reference/metrics.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#define M_PI_ 3.14159265358979323846

double metrics_luminance_rgb(const double rgb[3]) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

static double lum_f(const float *p) { return 0.2126 * (double)p[0] + 0.7152 * (double)p[1] + 0.0722 * (double)p[2]; }

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

metrics_luminance metrics_relative_luminance(const float *test_rgba, const float *ref_rgba, const unsigned char *mask,
                                             int w, int h, double floor_lum)
{
    metrics_luminance m = {0.0, 0.0, 0.0, 0};
    if (!test_rgba || !ref_rgba || w <= 0 || h <= 0)
        return m;
    const size_t n = (size_t)w * (size_t)h;
    if (!(floor_lum > 0.0)) {
        double mx = 0.0;
        for (size_t i = 0; i < n; ++i) {
            double lr = lum_f(ref_rgba + 4 * i);
            if ((!mask || mask[i]) && isfinite(lr) && lr > mx)
                mx = lr;
        }
        floor_lum = mx > 0.0 ? 1e-4 * mx : DBL_MIN;
    }
    double *e = malloc(n * sizeof *e);
    if (!e)
        return m;
    size_t k = 0;
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        if (mask && !mask[i])
            continue;
        double lt = lum_f(test_rgba + 4 * i), lr = lum_f(ref_rgba + 4 * i);
        double v = fabs(lt - lr) / (lr > floor_lum ? lr : floor_lum);
        if (!isfinite(v))
            v = INFINITY;
        e[k++] = v;
        sum += v;
    }
    if (k > 0) {
        qsort(e, k, sizeof *e, cmp_double);
        size_t rank = (size_t)ceil(0.95 * (double)k); /* nearest rank, 1-based */
        if (rank < 1)
            rank = 1;
        if (rank > k)
            rank = k;
        m.mean = sum / (double)k;
        m.p95 = e[rank - 1];
        m.max = e[k - 1];
        m.count = (int)k;
    }
    free(e);
    return m;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* CIEDE2000                                                                                                  */

static double deg2rad(double d) { return d * (M_PI_ / 180.0); }

/* Hue angle in degrees, [0, 360); 0 for the achromatic a = b = 0. */
static double hue_deg(double b, double a)
{
    if (a == 0.0 && b == 0.0)
        return 0.0;
    double hd = atan2(b, a) * (180.0 / M_PI_);
    return hd < 0.0 ? hd + 360.0 : hd;
}

double metrics_ciede2000(const double lab1[3], const double lab2[3])
{
    const double L1 = lab1[0], a1 = lab1[1], b1 = lab1[2];
    const double L2 = lab2[0], a2 = lab2[1], b2 = lab2[2];
    const double p25_7 = 6103515625.0; /* 25^7 */
    double C1 = sqrt(a1 * a1 + b1 * b1), C2 = sqrt(a2 * a2 + b2 * b2);
    double Cb = 0.5 * (C1 + C2), Cb7 = pow(Cb, 7.0);
    double G = 0.5 * (1.0 - sqrt(Cb7 / (Cb7 + p25_7)));
    double a1p = (1.0 + G) * a1, a2p = (1.0 + G) * a2;
    double C1p = sqrt(a1p * a1p + b1 * b1), C2p = sqrt(a2p * a2p + b2 * b2);
    double h1p = hue_deg(b1, a1p), h2p = hue_deg(b2, a2p);

    double dLp = L2 - L1, dCp = C2p - C1p, dhp = 0.0;
    double CC = C1p * C2p;
    if (CC != 0.0) {
        dhp = h2p - h1p;
        if (dhp > 180.0)
            dhp -= 360.0;
        else if (dhp < -180.0)
            dhp += 360.0;
    }
    double dHp = 2.0 * sqrt(CC) * sin(deg2rad(0.5 * dhp));

    double Lbp = 0.5 * (L1 + L2), Cbp = 0.5 * (C1p + C2p), hbp;
    if (CC == 0.0)
        hbp = h1p + h2p;
    else if (fabs(h1p - h2p) <= 180.0)
        hbp = 0.5 * (h1p + h2p);
    else if (h1p + h2p < 360.0)
        hbp = 0.5 * (h1p + h2p + 360.0);
    else
        hbp = 0.5 * (h1p + h2p - 360.0);

    double T = 1.0 - 0.17 * cos(deg2rad(hbp - 30.0)) + 0.24 * cos(deg2rad(2.0 * hbp)) +
               0.32 * cos(deg2rad(3.0 * hbp + 6.0)) - 0.20 * cos(deg2rad(4.0 * hbp - 63.0));
    double dtheta = 30.0 * exp(-((hbp - 275.0) / 25.0) * ((hbp - 275.0) / 25.0));
    double Cbp7 = pow(Cbp, 7.0);
    double RC = 2.0 * sqrt(Cbp7 / (Cbp7 + p25_7));
    double l50 = (Lbp - 50.0) * (Lbp - 50.0);
    double SL = 1.0 + 0.015 * l50 / sqrt(20.0 + l50);
    double SC = 1.0 + 0.045 * Cbp;
    double SH = 1.0 + 0.015 * Cbp * T;
    double RT = -sin(deg2rad(2.0 * dtheta)) * RC;
    double tl = dLp / SL, tc = dCp / SC, th = dHp / SH;
    double d2 = tl * tl + tc * tc + th * th + RT * tc * th;
    return sqrt(d2 > 0.0 ? d2 : 0.0);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* sRGB -> Lab                                                                                                */

static const double k_rgb2xyz[3][3] = {
    {0.4124564, 0.3575761, 0.1804375},
    {0.2126729, 0.7151522, 0.0721750},
    {0.0193339, 0.1191920, 0.9503041},
};

static double srgb_decode(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

static double lab_f(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

void metrics_srgb8_to_lab(const unsigned char rgb[3], double lab[3])
{
    double lin[3], xyz[3], f[3];
    for (int c = 0; c < 3; ++c)
        lin[c] = srgb_decode(rgb[c] / 255.0);
    for (int i = 0; i < 3; ++i) {
        double white = k_rgb2xyz[i][0] + k_rgb2xyz[i][1] + k_rgb2xyz[i][2]; /* D65 of this matrix */
        xyz[i] = k_rgb2xyz[i][0] * lin[0] + k_rgb2xyz[i][1] * lin[1] + k_rgb2xyz[i][2] * lin[2];
        f[i] = lab_f(xyz[i] / white);
    }
    lab[0] = 116.0 * f[1] - 16.0;
    lab[1] = 500.0 * (f[0] - f[1]);
    lab[2] = 200.0 * (f[1] - f[2]);
}

double metrics_ciede2000_mean(const unsigned char *a_rgba8, const unsigned char *b_rgba8, const unsigned char *mask,
                              int w, int h)
{
    if (!a_rgba8 || !b_rgba8 || w <= 0 || h <= 0)
        return 0.0;
    const size_t n = (size_t)w * (size_t)h;
    double sum = 0.0;
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
        if (mask && !mask[i])
            continue;
        double la[3], lb[3];
        metrics_srgb8_to_lab(a_rgba8 + 4 * i, la);
        metrics_srgb8_to_lab(b_rgba8 + 4 * i, lb);
        sum += metrics_ciede2000(la, lb);
        ++k;
    }
    return k ? sum / (double)k : 0.0;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Tone map (shaders/glsl/tonemap_common.glsl)                                                                */

static double clamp01(double x) { return x > 0.0 ? (x < 1.0 ? x : 1.0) : 0.0; } /* NaN -> 0 */

/* The channel's sRGB-encoded value in [0, 1], before quantisation. */
static double tonemap_channel(double c, double exposure, int op)
{
    if (!(c == c) || c < 0.0) /* NaN, or a spectral sum's out-of-gamut negative: a display shows none (clipped) */
        c = 0.0;
    if (c > 65504.0)
        c = 65504.0;
    double x = c * exposure, m;
    if (op == 2)
        m = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
    else if (op == 1)
        m = x / (1.0 + x);
    else
        m = x;
    m = clamp01(m);
    double e = m > 0.0031308 ? 1.055 * pow(m, 1.0 / 2.4) - 0.055 : 12.92 * m;
    return clamp01(e);
}

/* The GPU's dither (shaders/glsl/dither.glsl, issue 26), the same law: Jarzynski and Olano's pcg2d (JCGT 2020) of the
 * pixel's position in the whole image, two uniforms on [0, 1) of its top 24 bits, their sum less 1: triangular noise
 * on (-1, 1) LSB, added to the encoded value before quantisation, its amplitude shrunk near 0 and 1 to the distance
 * from the end (no clipping bias). The shader adds it and decodes, the display format encodes again; here the encoded
 * value is quantised directly: the same level up to the format's own rounding. */
static double dither_triangular(int x, int y)
{
    uint32_t v[2] = {(uint32_t)x, (uint32_t)y};
    for (int k = 0; k < 2; ++k) v[k] = v[k] * 1664525u + 1013904223u;
    v[0] += v[1] * 1664525u, v[1] += v[0] * 1664525u;
    v[0] ^= v[0] >> 16u, v[1] ^= v[1] >> 16u;
    v[0] += v[1] * 1664525u, v[1] += v[0] * 1664525u;
    v[0] ^= v[0] >> 16u, v[1] ^= v[1] >> 16u;
    return (double)(v[0] >> 8u) / 16777216.0 + (double)(v[1] >> 8u) / 16777216.0 - 1.0;
}

void metrics_tonemap_srgb8_dithered(const float *rgba, int w, int h, double exposure_ev, int op, bool dither, int x0,
                                    int y0, unsigned char *out_rgba8)
{
    if (!rgba || !out_rgba8 || w <= 0 || h <= 0)
        return;
    const double exposure = exp2(exposure_ev);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            double noise = dither ? dither_triangular(x0 + x, y0 + y) : 0.0;
            for (int c = 0; c < 3; ++c) {
                double e = tonemap_channel(rgba[4 * i + c], exposure, op);
                double amplitude = fmin(e, 1.0 - e) * 255.0;
                e = clamp01(e + noise * (amplitude < 1.0 ? amplitude : 1.0) / 255.0);
                out_rgba8[4 * i + c] = (unsigned char)floor(255.0 * e + 0.5);
            }
            out_rgba8[4 * i + 3] = 255;
        }
}

void metrics_tonemap_srgb8(const float *rgba, int w, int h, double exposure_ev, int op, unsigned char *out_rgba8)
{
    metrics_tonemap_srgb8_dithered(rgba, w, h, exposure_ev, op, false, 0, 0, out_rgba8);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Sky mask                                                                                                   */

void metrics_sky_mask(const model_atmosphere *a, double altitude, int w, int h, double yaw_rad, double pitch_rad,
                      double fov_y_rad, unsigned char *mask)
{
    if (!a || !mask || w <= 0 || h <= 0)
        return;
    const double alt = altitude > 0.0 ? altitude : 0.0;
    const double Rb = a->bottom_radius, r = Rb + alt, rho2 = alt * (2.0 * Rb + alt); /* r^2 - Rb^2 */
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double d[3];
            ref_pixel_dir(x, y, w, h, yaw_rad, pitch_rad, fov_y_rad, d);
            double rmu = r * d[1];
            int ground = d[1] < 0.0 && rho2 <= rmu * rmu; /* inclusive ground test */
            mask[(size_t)y * w + x] = ground ? 0 : 1;
        }
}
