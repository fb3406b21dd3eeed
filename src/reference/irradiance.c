/* Irradiance at the camera from the spectral reference (spectral.h, ref_spectral_irradiance): the sun's beam by
 * direct transmittance, the sky by a quadrature over the sphere in coordinates centred on the sun (the aerosol's
 * forward peak is there, so the nodes crowd there), the ground on a tilted surface as a Lambertian reflector. */
#include "reference/spectral.h"
#include "model/spectrum.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross3(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static void normalize3(double v[3])
{
    double l = sqrt(dot3(v, v));
    for (int i = 0; i < 3; ++i)
        v[i] = l > 0.0 ? v[i] / l : 0.0;
}

static void band_add(ref_irradiance_band *acc, const ref_irradiance_band *v, double k)
{
    acc->direct_normal += k * v->direct_normal;
    acc->diffuse_horizontal += k * v->diffuse_horizontal;
    acc->global_horizontal += k * v->global_horizontal;
    acc->diffuse_tilted += k * v->diffuse_tilted;
    acc->global_tilted += k * v->global_tilted;
}

/* The sun's transmittance per bin from the camera (0 where the planet hides the sun's centre). */
static void beam(const ref_spectral *s, double altitude, const double sun[3], double *T)
{
    double Rb = s->atmosphere.bottom_radius, h = altitude > 0.0 ? altitude : 0.0, r = Rb + h;
    /* mu at the geometric horizon: -sqrt(1 - (Rb/r)^2) = -sqrt(h (2 Rb + h)) / r, cancellation-free. */
    double mu_h = -sqrt(h * (2.0 * Rb + h)) / r;
    int n = s->wavelengths;
    for (int g = 0; g < (n + 2) / 3; ++g) {
        model_atmosphere a;
        int idx[3];
        int real = ref_spectral_group(s, g, &a, idx);
        double t[3] = {0.0, 0.0, 0.0};
        if (sun[1] > mu_h)
            ref_transmittance(&a, h, sun[1], 4000, t);
        for (int c = 0; c < real; ++c)
            T[idx[c]] = t[c];
    }
}

int ref_spectral_irradiance(const ref_spectral *s, double altitude, const double sun_dir[3], double tilt_deg,
                            double tilt_azimuth_deg, const double ground_albedo[3], int n_dirs, ref_irradiance *out)
{
    const int n = s->wavelengths;
    memset(out, 0, sizeof *out);
    out->count = n;
    double sun[3] = {sun_dir[0], sun_dir[1], sun_dir[2]}, up[3] = {0.0, 1.0, 0.0}, nt[3];
    normalize3(sun);
    ref_dir(tilt_azimuth_deg * PI / 180.0, (90.0 - tilt_deg) * PI / 180.0, nt);
    out->cos_incidence_tilted = dot3(nt, sun);

    double *T = calloc((size_t)n, sizeof *T), *L = calloc((size_t)n, sizeof *L);
    double *Dh = calloc((size_t)n, sizeof *Dh), *Dt = calloc((size_t)n, sizeof *Dt);
    if (!T || !L || !Dh || !Dt) {
        free(T), free(L), free(Dh), free(Dt);
        return -1;
    }
    beam(s, altitude, sun, T);

    /* Sky: theta' from the sun = pi u^2 (nodes crowd toward the sun), u and the azimuth at midpoints; a direction
     * counts where it is above the horizontal plane (below it is the ground, the albedo term). */
    double e1[3], e2[3], ref_axis[3] = {fabs(sun[1]) < 0.9 ? 0.0 : 1.0, fabs(sun[1]) < 0.9 ? 1.0 : 0.0, 0.0};
    cross3(sun, ref_axis, e1);
    normalize3(e1);
    cross3(sun, e1, e2);
    int nu = n_dirs > 2 ? n_dirs : 2, nphi = 2 * nu;
    for (int i = 0; i < nu; ++i) {
        double u = (i + 0.5) / nu, th = PI * u * u, dth = 2.0 * PI * u / nu;
        for (int j = 0; j < nphi; ++j) {
            double ph = 2.0 * PI * (j + 0.5) / nphi, w = sin(th) * dth * (2.0 * PI / nphi), d[3];
            for (int k = 0; k < 3; ++k)
                d[k] = cos(th) * sun[k] + sin(th) * (cos(ph) * e1[k] + sin(ph) * e2[k]);
            double ch = dot3(d, up), ct = dot3(d, nt);
            if (ch <= 0.0)
                continue;
            double xyz[3];
            ref_spectral_radiance(s, altitude, d, sun, xyz, NULL, L);
            for (int b = 0; b < n; ++b) {
                Dh[b] += L[b] * ch * w;
                if (ct > 0.0)
                    Dt[b] += L[b] * ct * w;
            }
        }
    }

    const double ci = out->cos_incidence_tilted > 0.0 ? out->cos_incidence_tilted : 0.0;
    const double cz = sun[1] > 0.0 ? sun[1] : 0.0, view_factor = 0.5 * (1.0 - cos(tilt_deg * PI / 180.0));
    const double dnm = (SPECTRUM_NM_MAX - SPECTRUM_NM_MIN) / n;
    spectral_law albedo = {.kind = SPECTRAL_LAW_RGB};
    memcpy(albedo.rgb, ground_albedo, sizeof albedo.rgb);
    for (int b = 0; b < n; ++b) {
        double nm = ref_spectral_nm(n, b), e0 = s->sun_scale * spectrum_solar_irradiance(nm);
        ref_irradiance_band *o = &out->spectral[b];
        out->nm[b] = nm;
        o->direct_normal = e0 * T[b];
        o->diffuse_horizontal = Dh[b];
        o->global_horizontal = o->direct_normal * cz + Dh[b];
        o->diffuse_tilted = Dt[b] + spectral_law_eval(&albedo, nm) * o->global_horizontal * view_factor;
        o->global_tilted = o->direct_normal * ci + o->diffuse_tilted;
        /* The bin's illuminance: its response per unit sun times its exact colour weight (spectral.c). */
        double wxyz[3], k = e0 > 0.0 ? s->sun_scale / e0 : 0.0;
        ref_spectral_weights(n, b, wxyz);
        band_add(&out->watts, o, dnm);
        band_add(&out->lux, o, k * wxyz[1]);
    }
    free(T), free(L), free(Dh), free(Dt);
    return 0;
}
