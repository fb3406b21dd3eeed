/* tools/color_error.c: the colour axis of the model's error (issue 32, docs/color_error.md).
 *
 * On the 57 rows of docs/model_error.md (ground, 10 km, 400 km; sun +90 .. -6 deg; the same rows as
 * tools/model_error.c), the RGB model (ref_sky_radiance, converged, Hillaire's Earth: three wavelengths 680, 550,
 * 440 nm, the sun the top-of-atmosphere spectrum's own Rec.709 colour at its own illuminance, 133 177 lx) against
 * the spectral reference (reference/spectral.h: the same integrator at N wavelengths over 360-830 nm of the medium
 * those RGB coefficients stand for, spectral_medium_from_rgb; radiance -> CIE 1931 XYZ). Both in cd/m^2.
 *
 * Per row: the luminance of each, the relative luminance error, the chromaticity (x, y) of each, and CIEDE2000
 * between them in CIELAB with the D65 white scaled to the reference's luminance (so the reference is L* = 100 and
 * a luminance error shows as a lightness difference too). metrics_ciede2000 is tested against Sharma et al. 2005.
 *
 *   color_error [--wavelengths N] [--test-wavelengths M] [--path-trace SAMPLES] [--threads T]
 *
 * --test-wavelengths M: the tested side is the same spectral integrator at M wavelengths instead of the RGB model
 * (the "L RGB" columns then hold it): the colour error of the GPU's --spectral M apart from the GPU's numerics.
 *
 * --path-trace: the reference is the spectral path tracer (all orders, no horizon fade) and the RGB side the RGB
 * path tracer, same samples: the colour error of three wavelengths in the physics itself, free of the model's
 * other approximations (slow: minutes per 10^4 samples on two cores).
 */
#include "model/spectrum.h"
#include "reference/metrics.h"
#include "reference/spectral.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

#include "model_rows.h"   /* the rows of tools/model_error, in its order */

/* Linear Rec.709 (D65) -> XYZ (IEC 61966-2-1). */
static void rec709_to_xyz(const double c[3], double o[3])
{
    o[0] = 0.4124 * c[0] + 0.3576 * c[1] + 0.1805 * c[2];
    o[1] = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    o[2] = 0.0193 * c[0] + 0.1192 * c[1] + 0.9505 * c[2];
}

static double lab_f(double t) { return t > 216.0 / 24389.0 ? cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0; }

/* CIELAB with the D65 white (0.95047, 1, 1.08883) x Yn. */
static void xyz_to_lab(const double xyz[3], double Yn, double lab[3])
{
    double fx = lab_f(xyz[0] / (0.95047 * Yn)), fy = lab_f(xyz[1] / Yn), fz = lab_f(xyz[2] / (1.08883 * Yn));
    lab[0] = 116.0 * fy - 16.0;
    lab[1] = 500.0 * (fx - fy);
    lab[2] = 200.0 * (fy - fz);
}

static void chroma(const double xyz[3], double *x, double *y)
{
    double s = xyz[0] + xyz[1] + xyz[2];
    *x = s > 0.0 ? xyz[0] / s : 0.0;
    *y = s > 0.0 ? xyz[1] / s : 0.0;
}

int main(int argc, char **argv)
{
    int wavelengths = 48, threads = 2, test_wavelengths = 0;
    long long samples = 0;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--wavelengths") && i + 1 < argc)
            wavelengths = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--path-trace") && i + 1 < argc)
            samples = atoll(argv[++i]);
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc)
            threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--test-wavelengths") && i + 1 < argc)
            test_wavelengths = atoi(argv[++i]);   /* the GPU's --spectral N: the tested side at N wavelengths */
        else {
            fprintf(stderr, "usage: color_error [--wavelengths N (%d-%d)] [--test-wavelengths M] "
                            "[--path-trace SAMPLES] "
                            "[--threads T]\n",
                    REF_SPECTRAL_MIN, REF_SPECTRAL_MAX);
            return 2;
        }
    }
    if (wavelengths < REF_SPECTRAL_MIN || wavelengths > REF_SPECTRAL_MAX || samples < 0 || threads < 1 ||
        (test_wavelengths && (test_wavelengths < REF_SPECTRAL_MIN || test_wavelengths > REF_SPECTRAL_MAX))) {
        fprintf(stderr, "color_error: --wavelengths in %d..%d, --path-trace >= 1, --threads >= 1\n", REF_SPECTRAL_MIN,
                REF_SPECTRAL_MAX);
        return 2;
    }
    model_atmosphere rgb_atmo;
    model_atmosphere_earth(&rgb_atmo);
    spectrum_solar_rec709_toa(rgb_atmo.sun_illuminance);
    ref_spectral s;
    ref_spectral_init(&s, &rgb_atmo, wavelengths);
    pt_settings pt = {.samples = samples, .seed = 32, .threads = threads};
    if (samples)
        s.pt = &pt;
    /* --test-wavelengths N: the tested side is the same integrator at N wavelengths (what --spectral N computes),
     * not the RGB model. */
    ref_spectral t;
    ref_spectral_init(&t, &rgb_atmo, test_wavelengths);
    t.pt = s.pt;

    row rows[MAX_ROWS];
    int n = build_rows(rows);
    printf("| # | altitude | sun | view | L spectral (cd/m²) | L RGB | L error | x, y spectral | x, y RGB | ΔE2000 | "
           "ΔE2000 at equal L |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
    double sum_de = 0.0, max_de = 0.0, sum_le = 0.0, max_le = 0.0, sum_dc = 0.0, max_dc = 0.0;
    int counted = 0;
    for (int i = 0; i < n; ++i) {
        const row *w = &rows[i];
        double sun[3], v[3], xyz_s[3], se[3], rgb[3], rgb_se[3], xyz_r[3];
        ref_dir(0.0, w->sun_el * DEG, sun);
        ref_dir(w->az * DEG, w->el * DEG, v);
        ref_spectral_radiance(&s, w->altitude, v, sun, xyz_s, se, NULL);
        if (test_wavelengths)
            ref_spectral_radiance(&t, w->altitude, v, sun, xyz_r, rgb_se, NULL);
        else if (samples)
            pt_radiance(&rgb_atmo, w->altitude, v, sun, &pt, rgb, rgb_se);
        else
            ref_sky_radiance(&rgb_atmo, w->altitude, v, sun, ref_quality_converged(), rgb);
        if (!test_wavelengths)
            rec709_to_xyz(rgb, xyz_r);
        double Ls = xyz_s[1], Lr = xyz_r[1], le = Ls > 0.0 ? Lr / Ls - 1.0 : 0.0, lab_s[3], lab_r[3];
        xyz_to_lab(xyz_s, Ls, lab_s);
        xyz_to_lab(xyz_r, Ls, lab_r);
        double de = Ls > 0.0 ? metrics_ciede2000(lab_s, lab_r) : 0.0, xs, ys, xr, yr;
        /* the colour alone: the RGB result scaled to the reference's luminance */
        double xyz_c[3], lab_c[3], k = Lr > 0.0 ? Ls / Lr : 0.0;
        for (int c = 0; c < 3; ++c)
            xyz_c[c] = k * xyz_r[c];
        xyz_to_lab(xyz_c, Ls, lab_c);
        double dc = Ls > 0.0 ? metrics_ciede2000(lab_s, lab_c) : 0.0;
        chroma(xyz_s, &xs, &ys);
        chroma(xyz_r, &xr, &yr);
        printf("| %d | %g km | %+g | %s | %.4g | %.4g | %+.2f %% | %.4f, %.4f | %.4f, %.4f | %.2f | %.2f |\n", i + 1,
               w->altitude < 0.01 ? 0.0 : w->altitude, w->sun_el, w->name, Ls, Lr, 100 * le, xs, ys, xr, yr, de, dc);
        fflush(stdout);
        if (Ls > 0.0) {
            sum_de += de, sum_le += fabs(le), ++counted;
            max_de = fmax(max_de, de), max_le = fmax(max_le, fabs(le));
            sum_dc += dc, max_dc = fmax(max_dc, dc);
        }
    }
    printf("\n%d rows: mean |L error| %.2f %%, worst %.2f %%; mean ΔE2000 %.2f, worst %.2f; at equal luminance mean "
           "%.2f, worst %.2f (%d wavelengths, %s)\n", counted, 100 * sum_le / counted, 100 * max_le, sum_de / counted,
           max_de, sum_dc / counted, max_dc, wavelengths,
           samples ? "path tracers" : "the converged model");
    if (test_wavelengths)
        printf("tested side: the spectral integrator at %d wavelengths (--spectral %d), not the RGB model\n",
               test_wavelengths, test_wavelengths);
    return 0;
}
