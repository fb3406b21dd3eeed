/* tonemap_check (issue 31 item 2): the GPU's 8-bit PNG against the tone-map formula applied here, on the CPU, to the
 * same frame's EXR (the scene-linear pixels the tone map read: HDR + bloom, upsampled to the output's size).
 *   tonemap_check FRAME.exr FRAME.png relative|photometric EV aces|reinhard|clamp [dither]
 * The formulas are written here from their published definitions, not taken from the shaders or metrics.c:
 *   exposure: relative units, x = L * 2^EV; photometric (cd/m^2), ISO 12232's saturation-based exposure with
 *   K = 12.5 and q = 0.65, H = L / (1.2 * 2^EV100) of the saturation level (docs/units.md);
 *   operators: ACES by Narkowicz's fit (2015) x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14), Reinhard x / (1 + x),
 *   clamp; then IEC 61966-2-1 sRGB encoding, round to 8 bits.
 * Without the dither (--no-dither) every channel is within one level of the formula's (the EXR holds half floats, and
 * the device's sRGB conversion has its own rounding); any channel further off fails (exit 1). With the dither
 * ("dither": triangular noise of +-1 LSB before quantisation, issue 26) one more level is the noise's: within two
 * levels, and at most 1 % of the channels at two. Also: the mean signed difference over all channels is
 * within 0.05 level (the dither's mean is zero; a wrong exposure or curve shifts it), and the test has something to
 * see (at least 25 % of the channels between levels 16 and 239). */
#include "io/exr_read.h"
#include "io/png_io.h"
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double srgb(double c)
{
    c = c < 0.0 ? 0.0 : c > 1.0 ? 1.0 : c;
    return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

static double curve(double x, const char *op)
{
    if (!strcmp(op, "aces")) return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
    if (!strcmp(op, "reinhard")) return x / (1.0 + x);
    return x;
}

int main(int argc, char **argv)
{
    bool dither = argc == 7 && !strcmp(argv[6], "dither");
    if ((argc != 6 && !dither) || (strcmp(argv[3], "relative") && strcmp(argv[3], "photometric")) ||
        (strcmp(argv[5], "aces") && strcmp(argv[5], "reinhard") && strcmp(argv[5], "clamp"))) {
        fprintf(stderr, "usage: tonemap_check FRAME.exr FRAME.png relative|photometric EV aces|reinhard|clamp [dither]\n");
        return 2;
    }
    double ev = atof(argv[4]);
    double multiplier = !strcmp(argv[3], "relative") ? exp2(ev) : 1.0 / (1.2 * exp2(ev));
    char err[512];
    int w = 0, h = 0, pw = 0, ph = 0;
    float *hdr = NULL;
    unsigned char *png = NULL;
    if (io_read_exr(argv[1], "", &w, &h, &hdr, err, sizeof err) != 0) { fprintf(stderr, "tonemap_check: %s\n", err); return 1; }
    if (io_read_png(argv[2], &pw, &ph, &png, err, sizeof err) != 0) { fprintf(stderr, "tonemap_check: %s\n", err); return 1; }
    if (pw != w || ph != h) { fprintf(stderr, "tonemap_check: EXR %dx%d, PNG %dx%d\n", w, h, pw, ph); return 1; }
    long off = 0, two = 0, mid = 0, n = 0;
    int allowed = dither ? 2 : 1;
    double sum = 0.0;
    int worst = 0;
    for (long i = 0; i < (long)w * h; ++i)
        for (int c = 0; c < 3; ++c) {
            double x = fmin(hdr[4 * i + c], 65504.0) * multiplier;
            long want = lround(255.0 * srgb(curve(x, argv[5])));
            int got = png[4 * i + c];
            int d = abs(got - (int)want);
            if (d > worst) worst = d;
            two += d == 2;
            if (d > allowed && off++ < 5)
                fprintf(stderr, "tonemap_check: pixel (%ld, %ld) channel %d: PNG %d, formula %ld (linear %g)\n", i % w,
                        i / w, c, got, want, hdr[4 * i + c]);
            sum += got - (double)want;
            mid += want >= 16 && want <= 239;
            ++n;
        }
    double mean = sum / (double)n;
    printf("tonemap_check: %s %s EV %g%s: %dx%d, worst %d level(s), %ld at 2, %ld over %d, mean difference %+.4f, "
           "%.0f %% mid-range\n", argv[3], argv[5], ev, dither ? " dithered" : "", w, h, worst, two, off, allowed, mean,
           100.0 * mid / n);
    int bad = off > 0 || fabs(mean) > 0.05 || mid * 4 < n || (dither && two * 100 > n);
    if (dither && two * 100 > n) fprintf(stderr, "tonemap_check: %ld of %ld channels two levels off (over 1 %%)\n", two, n);
    if (fabs(mean) > 0.05) fprintf(stderr, "tonemap_check: mean difference %+.4f level, over 0.05\n", mean);
    if (mid * 4 < n) fprintf(stderr, "tonemap_check: only %ld of %ld channels mid-range: nothing to compare\n", mid, n);
    free(hdr);
    free(png);
    return bad;
}
