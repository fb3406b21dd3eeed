/* tools/sunset_strip.c: the README's picture of issue 17 — the same sunset and twilight skies from the lesson's model
 * (binary shadow x horizon fade, isotropic Psi), the new model (penumbra, Psi's shadowed first bounce with the real
 * phases) and the path tracer (all orders, the sun a disc), side by side.
 *
 * For each sun elevation (+2, 0, -2, -4 deg) three bands, each a panorama from 1 m: azimuth 0 (toward the sun) to
 * 360 across W pixels, elevation 1 to 40 deg over H rows (quadratic, dense at the horizon). The CPU reference
 * renders both models (converged); the path tracer --samples paths per pixel. One exposure per sun elevation (from
 * the path tracer's mean luminance), ACES, sRGB, 2 px black rule between the sun elevations; written as PNG.
 *
 *   sunset_strip OUT.png [--width W] [--height H] [--samples N] [--threads T]
 */
#include "io/png_io.h"
#include "reference/metrics.h"
#include "reference/path_tracer.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

int main(int argc, char **argv)
{
    int W = 72, H = 12, threads = 2;
    long long samples = 8000;
    if (argc < 2) {
        fprintf(stderr, "usage: sunset_strip OUT.png [--width W] [--height H] [--samples N] [--threads T]\n");
        return 2;
    }
    for (int i = 2; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--width")) W = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--height")) H = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--samples")) samples = atoll(argv[i + 1]);
        else if (!strcmp(argv[i], "--threads")) threads = atoi(argv[i + 1]);
        else {
            fprintf(stderr, "sunset_strip: unknown argument %s\n", argv[i]);
            return 2;
        }
    }
    if (W < 2 || H < 2 || samples < 1 || threads < 1) {
        fprintf(stderr, "sunset_strip: bad size, samples or threads\n");
        return 2;
    }
    static const double suns[] = {2.0, 0.0, -2.0, -4.0};
    const int n_sun = 4, bands = 3, rule = 2;
    const int out_h = n_sun * (bands * H) + (n_sun - 1) * rule;
    unsigned char *img = calloc((size_t)W * out_h * 4, 1);
    float *band[3];
    for (int b = 0; b < bands; ++b)
        band[b] = malloc(sizeof(float) * 4 * (size_t)W * H);
    model_atmosphere pen, fade;
    model_atmosphere_earth(&pen);
    fade = pen;
    fade.sun_visibility = MODEL_SUN_VISIBILITY_LESSON_FADE;
    unsigned char *b8 = malloc((size_t)W * H * 4);
    for (int k = 0; k < n_sun; ++k) {
        double s[3], lum_sum = 0.0;
        ref_dir(0.0, suns[k] * DEG, s);
        for (int y = 0; y < H; ++y) {
            double u = 1.0 - (double)y / (H - 1), el = (1.0 + 39.0 * u * u) * DEG;
            for (int x = 0; x < W; ++x) {
                double az = 2.0 * PI * (x + 0.5) / W, v[3], c[3][3], se[3];
                ref_dir(az, el, v);
                ref_sky_radiance(&fade, 0.001, v, s, ref_quality_converged(), c[0]);
                ref_sky_radiance(&pen, 0.001, v, s, ref_quality_converged(), c[1]);
                pt_settings ps = {samples, 99ull + 7919ull * (unsigned long long)(k * W * H + y * W + x), 0.0, 0,
                                  threads};
                pt_radiance(&pen, 0.001, v, s, &ps, c[2], se);
                for (int b = 0; b < bands; ++b) {
                    float *p = band[b] + 4 * ((size_t)y * W + x);
                    for (int ch = 0; ch < 3; ++ch)
                        p[ch] = (float)c[b][ch];
                    p[3] = 1.0f;
                }
                lum_sum += 0.2126 * c[2][0] + 0.7152 * c[2][1] + 0.0722 * c[2][2];
            }
        }
        /* Exposure: the path tracer's mean luminance to 0.18 (mid grey). */
        double mean = lum_sum / (W * H), ev = mean > 0.0 ? log2(0.18 / mean) : 0.0;
        fprintf(stderr, "sun %+.0f deg: path tracer mean luminance %.4g, exposure %+.2f EV\n", suns[k], mean, ev);
        for (int b = 0; b < bands; ++b) {
            metrics_tonemap_srgb8(band[b], W, H, ev, 2 /* ACES */, b8);
            size_t row0 = (size_t)k * (bands * H + rule) + (size_t)b * H;
            memcpy(img + row0 * W * 4, b8, (size_t)W * H * 4);
        }
    }
    for (size_t i = 3; i < (size_t)W * out_h * 4; i += 4)
        img[i] = 255;
    char err[256];
    int rc = io_write_png(argv[1], W, out_h, img, 1, err, sizeof err);
    if (rc != 0)
        fprintf(stderr, "sunset_strip: %s\n", err);
    return rc != 0;
}
