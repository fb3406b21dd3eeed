/* The spectral CPU reference (spectral.h): wavelength bins, their colour weights, three wavelengths per packed
 * atmosphere through the model or the path tracer, XYZ. */
#include "reference/spectral.h"
#include "model/spectrum.h"

#include <math.h>
#include <string.h>

void ref_spectral_init(ref_spectral *s, const model_atmosphere *a, int wavelengths)
{
    memset(s, 0, sizeof *s);
    s->atmosphere = *a;
    spectral_medium_from_rgb(a, &s->medium);
    s->wavelengths = wavelengths < REF_SPECTRAL_MIN ? REF_SPECTRAL_MIN
                   : wavelengths > REF_SPECTRAL_MAX ? REF_SPECTRAL_MAX : wavelengths;
    s->sun_scale = 1.0;
    s->q = ref_quality_converged();
}

double ref_spectral_nm(int n, int i)
{
    double w = (SPECTRUM_NM_MAX - SPECTRUM_NM_MIN) / n;
    return SPECTRUM_NM_MIN + (i + 0.5) * w;
}

void ref_spectral_weights(int n, int i, double w_xyz[3])
{
    /* Both tables are piecewise linear with knots every 5 nm (spectrum.c); Simpson on pieces of <= 0.25 nm leaves
     * an error far below the 0.1 % that the wavelength count is asked to meet. */
    double w = (SPECTRUM_NM_MAX - SPECTRUM_NM_MIN) / n, a = SPECTRUM_NM_MIN + i * w;
    int pieces = (int)ceil(w / 0.25);
    double h = w / pieces;
    w_xyz[0] = w_xyz[1] = w_xyz[2] = 0.0;
    for (int k = 0; k < pieces; ++k) {
        double x[3] = {a + k * h, a + (k + 0.5) * h, a + (k + 1) * h}, c[3] = {1.0, 4.0, 1.0};
        for (int j = 0; j < 3; ++j) {
            double cmf[3], e = spectrum_solar_irradiance(x[j]);
            spectrum_cie1931(x[j], cmf);
            for (int m = 0; m < 3; ++m)
                w_xyz[m] += SPECTRUM_LUMINOUS_EFFICACY * e * cmf[m] * c[j] * h / 6.0;
        }
    }
}

int ref_spectral_group(const ref_spectral *s, int g, model_atmosphere *out, int idx[3])
{
    int n = s->wavelengths, real = 0;
    double nm[3], one[3] = {1.0, 1.0, 1.0};
    for (int c = 0; c < 3; ++c) {
        int i = 3 * g + c;
        if (i < n)
            ++real;
        else
            i = n - 1;
        idx[c] = i;
        nm[c] = ref_spectral_nm(n, i);
    }
    spectral_medium_pack(&s->medium, &s->atmosphere, nm, one, out);
    return real;
}

void ref_spectral_radiance(const ref_spectral *s, double altitude, const double view_dir[3], const double sun_dir[3],
                           double xyz[3], double xyz_stderr[3], double *spectrum)
{
    double var[3] = {0.0, 0.0, 0.0};
    xyz[0] = xyz[1] = xyz[2] = 0.0;
    int n = s->wavelengths, groups = (n + 2) / 3;
    for (int g = 0; g < groups; ++g) {
        model_atmosphere a;
        int idx[3];
        int real = ref_spectral_group(s, g, &a, idx);
        double r[3], se[3] = {0.0, 0.0, 0.0};
        if (s->pt) {
            pt_settings p = *s->pt;
            p.seed = s->pt->seed + 7919ull * (unsigned long long)g; /* a stream per group */
            pt_radiance(&a, altitude, view_dir, sun_dir, &p, r, se);
        } else {
            ref_sky_radiance(&a, altitude, view_dir, sun_dir, s->q, r);
        }
        for (int c = 0; c < real; ++c) {
            double w[3];
            ref_spectral_weights(n, idx[c], w);
            for (int m = 0; m < 3; ++m) {
                xyz[m] += s->sun_scale * r[c] * w[m];
                var[m] += s->sun_scale * s->sun_scale * se[c] * se[c] * w[m] * w[m];
            }
            if (spectrum)
                spectrum[idx[c]] = s->sun_scale * r[c] * spectrum_solar_irradiance(ref_spectral_nm(n, idx[c]));
        }
    }
    if (xyz_stderr)
        for (int m = 0; m < 3; ++m)
            xyz_stderr[m] = sqrt(var[m]);
}
