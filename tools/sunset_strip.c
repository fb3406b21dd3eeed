/* tools/sunset_strip.c: the README's picture of issue 17 — the same sunset and twilight skies from the lesson's model
 * (binary shadow x horizon fade, isotropic Psi), the new model (penumbra, Psi's shadowed first bounce with the real
 * phases) and the path tracer (all orders, the sun a disc), side by side.
 *
 * For each sun elevation (+2, 0, -2, -4 deg) three bands, each a panorama from 1 m: azimuth 0 (toward the sun) to
 * 360 across W pixels, elevation 1 to 40 deg over H rows (quadratic, dense at the horizon). The CPU reference
 * renders both models (converged); the path tracer --samples paths per pixel. One exposure per sun elevation (from
 * the path tracer's mean luminance), ACES, sRGB, 2 px black rule between the sun elevations; written as PNG.
 * --threads T forks T worker processes, each taking every T-th row (the reference's tables are per-process caches,
 * so processes rather than threads keep them private: the parent builds them once per sun and the workers inherit
 * them); the bands live in shared memory.
 *
 *   sunset_strip OUT.png [--width W] [--height H] [--samples N] [--threads T] [--suns E1,E2,...]
 *
 * --suns picks the sun elevations (degrees, at most 8; default 2,0,-2,-4), so the strip can be rendered in parts.
 */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS */
#include "io/png_io.h"
#include "reference/metrics.h"
#include "reference/path_tracer.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

int main(int argc, char **argv)
{
    int W = 72, H = 12, threads = 2;
    long long samples = 8000;
    if (argc < 2) {
        fprintf(stderr, "usage: sunset_strip OUT.png [--width W] [--height H] [--samples N] [--threads T] "
                        "[--suns E1,E2,...]\n");
        return 2;
    }
    double suns[8] = {2.0, 0.0, -2.0, -4.0};
    int n_sun = 4;
    for (int i = 2; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--width")) W = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--height")) H = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--samples")) samples = atoll(argv[i + 1]);
        else if (!strcmp(argv[i], "--threads")) threads = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--suns")) {
            char *p = argv[i + 1], *end;
            for (n_sun = 0; n_sun < 8 && *p; p = *end == ',' ? end + 1 : end) {
                suns[n_sun++] = strtod(p, &end);
                if (end == p || (*end && *end != ',') || fabs(suns[n_sun - 1]) > 90.0) {
                    fprintf(stderr, "sunset_strip: --suns wants up to 8 elevations in degrees, e.g. 2,0,-2,-4\n");
                    return 2;
                }
            }
        }
        else {
            fprintf(stderr, "sunset_strip: unknown argument %s\n", argv[i]);
            return 2;
        }
    }
    if (W < 2 || H < 2 || samples < 1 || threads < 1) {
        fprintf(stderr, "sunset_strip: bad size, samples or threads\n");
        return 2;
    }
    const int bands = 3, rule = 2;
    const int out_h = n_sun * (bands * H) + (n_sun - 1) * rule;
    unsigned char *img = calloc((size_t)W * out_h * 4, 1);
    float *band[3];
    for (int b = 0; b < bands; ++b) {
        band[b] = mmap(NULL, sizeof(float) * 4 * (size_t)W * H, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS,
                       -1, 0);
        if (band[b] == MAP_FAILED) {
            perror("sunset_strip: mmap");
            return 1;
        }
    }
    model_atmosphere pen, fade;
    model_atmosphere_earth(&pen);
    fade = pen;
    fade.sun_visibility = MODEL_SUN_VISIBILITY_LESSON_FADE;
    unsigned char *b8 = malloc((size_t)W * H * 4);
    for (int k = 0; k < n_sun; ++k) {
        double s[3], lum_sum = 0.0;
        ref_dir(0.0, suns[k] * DEG, s);
        { /* build the reference's tables for this sun here, once: the workers inherit them */
            double v[3], c[3];
            ref_dir(0.0, 10.0 * DEG, v);
            ref_sky_radiance(&fade, 0.001, v, s, ref_quality_converged(), c);
            ref_sky_radiance(&pen, 0.001, v, s, ref_quality_converged(), c);
        }
        for (int worker = 0; worker < threads; ++worker) {
            pid_t pid = fork();
            if (pid < 0) {
                perror("sunset_strip: fork");
                return 1;
            }
            if (pid > 0)
                continue;
            for (int y = worker; y < H; y += threads) {
                double u = 1.0 - (double)y / (H - 1), el = (1.0 + 39.0 * u * u) * DEG;
                for (int x = 0; x < W; ++x) {
                    double az = 2.0 * PI * (x + 0.5) / W, v[3], c[3][3], se[3];
                    ref_dir(az, el, v);
                    ref_sky_radiance(&fade, 0.001, v, s, ref_quality_converged(), c[0]);
                    ref_sky_radiance(&pen, 0.001, v, s, ref_quality_converged(), c[1]);
                    pt_settings ps = {samples, 99ull + 7919ull * (unsigned long long)(k * W * H + y * W + x), 0.0, 0,
                                      1};
                    pt_radiance(&pen, 0.001, v, s, &ps, c[2], se);
                    for (int b = 0; b < bands; ++b) {
                        float *p = band[b] + 4 * ((size_t)y * W + x);
                        for (int ch = 0; ch < 3; ++ch)
                            p[ch] = (float)c[b][ch];
                        p[3] = 1.0f;
                    }
                }
            }
            _exit(0);
        }
        int status, failed = 0;
        while (wait(&status) > 0)
            failed |= !WIFEXITED(status) || WEXITSTATUS(status) != 0;
        if (failed) {
            fprintf(stderr, "sunset_strip: a worker failed\n");
            return 1;
        }
        for (size_t i = 0; i < (size_t)W * H; ++i) {
            const float *p = band[2] + 4 * i;
            lum_sum += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
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
