/* ASTM G-173-03 against vksky's spectral reference (issue 32, docs/spectral.md).
 *
 *   astm_g173_check ASTMG173.CSV VKSKY_IRRADIANCE_OUTPUT
 *
 * The standard's direct normal (its "direct" column: direct + circumsolar) and global tilted (37 deg, facing the
 * sun) spectra are integrated here, on their own 0.5 / 1 nm grid (trapezoid), into illuminance with the CIE 1931
 * ybar and 683 lm/W, and into W/m^2 over the band vksky computes (360-830 nm); vksky's output (`vksky --scene
 * astm-g173 --reference --irradiance --tilt 37`) is read back. Asserts direct normal illuminance within 3 % and
 * global tilted within 5 % (the bounds); prints 10 nm bands over 400-700 nm when vksky's bins are 10 nm
 * wide (--spectral 47). Exit 0 pass, 1 fail, 2 unreadable input. */
#include "model/spectrum.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXROWS 2100

static double wl[MAXROWS], dn[MAXROWS], gt[MAXROWS];
static int rows;

static int read_standard(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    char line[256];
    while (fgets(line, sizeof line, f) && rows < MAXROWS) {
        double w, e, g, d;
        if (sscanf(line, "%lf,%lf,%lf,%lf", &w, &e, &g, &d) == 4) {
            wl[rows] = w, gt[rows] = g, dn[rows] = d;
            ++rows;
        }
    }
    fclose(f);
    return rows > 1000 ? 0 : -1;
}

/* Integral over [a, b] of column v times ybar (lux: x 683) or times 1 (W/m^2), trapezoid on the table's grid. */
static double integrate(const double *v, double a, double b, int lux)
{
    double s = 0.0;
    for (int i = 0; i + 1 < rows; ++i) {
        double x0 = wl[i], x1 = wl[i + 1];
        if (x1 <= a || x0 >= b)
            continue;
        double c[3], y0, y1;
        spectrum_cie1931(x0, c);
        y0 = lux ? 683.0 * c[1] : 1.0;
        spectrum_cie1931(x1, c);
        y1 = lux ? 683.0 * c[1] : 1.0;
        /* clip the interval to [a, b] by linear interpolation of the product */
        double f0 = v[i] * y0, f1 = v[i + 1] * y1, lo = fmax(x0, a), hi = fmin(x1, b);
        double g0 = f0 + (f1 - f0) * (lo - x0) / (x1 - x0), g1 = f0 + (f1 - f0) * (hi - x0) / (x1 - x0);
        s += 0.5 * (g0 + g1) * (hi - lo);
    }
    return s;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: astm_g173_check ASTMG173.csv VKSKY_OUTPUT\n");
        return 2;
    }
    if (read_standard(argv[1])) {
        fprintf(stderr, "astm_g173_check: %s: cannot read the standard's table\n", argv[1]);
        return 2;
    }
    FILE *f = fopen(argv[2], "r");
    if (!f) {
        fprintf(stderr, "astm_g173_check: %s: cannot read\n", argv[2]);
        return 2;
    }
    char line[512];
    double lux_dn = -1, lux_gt = -1, w_dn = -1, w_gt = -1, d, e;
    static double nm[200], sdn[200], sgt[200];
    int n = 0;
    while (fgets(line, sizeof line, f)) {
        double a, b, c;
        if (sscanf(line, "lx direct_normal %lf diffuse_horizontal %lf global_horizontal %lf diffuse_tilted %lf "
                         "global_tilted %lf", &lux_dn, &a, &b, &c, &lux_gt) == 5)
            continue;
        if (sscanf(line, "W/m^2 (360-830 nm) direct_normal %lf diffuse_horizontal %lf global_horizontal %lf "
                         "diffuse_tilted %lf global_tilted %lf", &w_dn, &a, &b, &c, &w_gt) == 5)
            continue;
        double v[6];
        if (n < 200 && line[0] != '#' && sscanf(line, "%lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]) == 6)
            nm[n] = v[0], sdn[n] = v[1], sgt[n] = v[5], ++n;
    }
    fclose(f);
    if (lux_dn < 0 || lux_gt < 0 || w_dn < 0) {
        fprintf(stderr, "astm_g173_check: %s: no irradiance lines (vksky --reference --irradiance output?)\n", argv[2]);
        return 2;
    }
    double s_lux_dn = integrate(dn, 360, 830, 1), s_lux_gt = integrate(gt, 360, 830, 1);
    double s_w_dn = integrate(dn, 360, 830, 0), s_w_gt = integrate(gt, 360, 830, 0);
    if (n > 1 && fabs((nm[1] - nm[0]) - 10.0) < 1e-6) {
        printf("band (nm)   direct normal: G-173  vksky  diff  | global tilted 37: G-173  vksky  diff  (W m^-2 nm^-1)\n");
        for (int i = 0; i < n; ++i) {
            double a = nm[i] - 5.0, b = nm[i] + 5.0;
            if (a < 400.0 - 1e-9 || b > 700.0 + 1e-9)
                continue;
            d = integrate(dn, a, b, 0) / 10.0, e = integrate(gt, a, b, 0) / 10.0;
            printf("%3.0f-%3.0f   %.4f %.4f %+6.2f %%  |  %.4f %.4f %+6.2f %%\n", a, b, d, sdn[i], 100 * (sdn[i] / d - 1),
                   e, sgt[i], 100 * (sgt[i] / e - 1));
        }
    }
    printf("360-830 nm W/m^2: direct normal G-173 %.2f vksky %.2f (%+.2f %%); global tilted G-173 %.2f vksky %.2f "
           "(%+.2f %%)\n", s_w_dn, w_dn, 100 * (w_dn / s_w_dn - 1), s_w_gt, w_gt, 100 * (w_gt / s_w_gt - 1));
    double edn = lux_dn / s_lux_dn - 1, egt = lux_gt / s_lux_gt - 1;
    printf("illuminance: direct normal G-173 %.0f lx vksky %.0f lx (%+.2f %%, bound 3 %%); global tilted G-173 %.0f lx "
           "vksky %.0f lx (%+.2f %%, bound 5 %%)\n", s_lux_dn, lux_dn, 100 * edn, s_lux_gt, lux_gt, 100 * egt);
    int ok = fabs(edn) < 0.03 && fabs(egt) < 0.05;
    printf("%s\n", ok ? "ok" : "FAIL");
    return ok ? 0 : 1;
}
