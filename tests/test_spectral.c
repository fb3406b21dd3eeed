/* The spectral reference (issue 32) against things that share none of its code:
 *  1. Rayleigh per wavelength: a pure-Rayleigh atmosphere with the column of Bodhaine et al. 1999's standard
 *     atmosphere (P 1013.25 hPa, 45 deg latitude, 360 ppm CO2) has the optical depth of their fit, eq. (30):
 *     tau(lambda) = 0.0021520 (1.0455996 - 341.29061 l^-2 - 0.90230850 l^2) / (1 + 0.0027059889 l^-2
 *     - 85.968563 l^2), l in micrometres (Bodhaine, Wood, Dutton & Slusser, J. Atmos. Oceanic Technol. 16 (1999)
 *     1854-1861). Our optical depth is -ln of the reference's transmittance straight up.
 *  2. Wavelength count: 48 -> 96 wavelengths changes the luminance < 0.1 % (noon, sunset, twilight; the model's
 *     single scattering, for time).
 *  3. Closed form: single scattering with the sun and the view both at the zenith. Both rays are the same
 *     vertical, so the two transmittances multiply to the whole column's, and
 *     L(lambda) = E(lambda) e^-tau(lambda) [beta_R P_R(0) H_R (1 - e^-top/H_R) + beta_M P_HG(0) H_M (...)].
 *     The path tracer with max_bounces 1 and a point sun, spectral, must match it in X, Y, Z (within 4 sigma).
 *  4. The Earth's shadow: single scattering at the zenith with the sun at -6 deg counts only the air above the
 *     shadow height Rb (1 / cos 6 deg - 1) = 35 km; a quadrature from there (its own slant transmittance) against
 *     the spectral path tracer with max_bounces 1.
 *  5. A second tracer, written here and nothing else's: analog Monte Carlo, one wavelength drawn uniformly per
 *     path (hero-less), delta tracking against one global majorant, next-event estimation to the sun with ratio
 *     tracking, Henyey-Greenstein / Rayleigh phase sampling by rejection, all orders. The spectral path tracer's
 *     XYZ in daylight, at sunset and in twilight (the Earth's shadow) must agree with it. */
#include "model/spectrum.h"
#include "reference/spectral.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

static int failures;

static void check(int ok, const char *what)
{
    printf("%s %s\n", ok ? "ok  " : "FAIL", what);
    if (!ok)
        ++failures;
}

static double tau_bodhaine_fit(double nm)
{
    double l = nm * 1e-3, l2 = l * l;
    return 0.0021520 * (1.0455996 - 341.29061 / l2 - 0.90230850 * l2) / (1.0 + 0.0027059889 / l2 - 85.968563 * l2);
}

static void test_rayleigh_optical_depth(void)
{
    /* Bodhaine's column: P A / (m_a g) molecules per cm^2, eq. (3), g at the column's mass-weighted altitude
     * z_c = 0.73737 z + 5517.56 m at 45 deg, eqs. (10), (11); the exponential with that column at sea-level number
     * density N_s has the scale height H = column / N_s. */
    double zc = 5517.56, ma = 15.0556 * 360e-6 + 28.9595;
    double g = 980.6160 - 3.085462e-4 * zc + 7.254e-11 * zc * zc - 1.517e-17 * zc * zc * zc, column = 1013.25e3 * 6.0221367e23 / (ma * g);
    double H = column / 2.546899e19 * 1e-5; /* km */
    model_atmosphere a;
    model_atmosphere_earth(&a);
    a.top_radius = a.bottom_radius + 200.0;
    a.rayleigh_density = model_profile_exponential(H);
    spectral_medium m = {.rayleigh_scattering = {.kind = SPECTRAL_LAW_RAYLEIGH, .scale = 1.0}};
    double worst = 0.0;
    for (double nm = 360.0; nm <= 830.0; nm += 10.0) {
        double l[3] = {nm, nm, nm}, one[3] = {1, 1, 1}, T[3];
        model_atmosphere p;
        spectral_medium_pack(&m, &a, l, one, &p);
        ref_transmittance(&p, 0.0, 1.0, 20000, T);
        double tau = -log(T[0]), want = tau_bodhaine_fit(nm), e = tau / want - 1.0;
        if (fabs(e) > fabs(worst))
            worst = e;
        if ((int)nm % 100 == 0)
            printf("     Rayleigh tau(%3.0f nm) = %.5f, Bodhaine eq. 30 %.5f (%+.3f %%)\n", nm, tau, want, 100 * e);
    }
    char msg[160];
    snprintf(msg, sizeof msg, "Rayleigh optical depth 360-830 nm within 0.05 %% of Bodhaine et al. 1999 eq. 30 "
             "(worst %+.3f %%)", 100 * worst);
    check(fabs(worst) < 5e-4, msg);
}

static double lum_of(const ref_spectral *s, double h, const double v[3], const double sun[3])
{
    double xyz[3];
    ref_spectral_radiance(s, h, v, sun, xyz, NULL, NULL);
    return xyz[1];
}

static void test_wavelength_convergence(void)
{
    model_atmosphere a;
    model_atmosphere_earth(&a);
    ref_spectral s48, s96;
    ref_spectral_init(&s48, &a, 48);
    ref_spectral_init(&s96, &a, 96);
    /* The view march coarser than converged and single scattering only (the same for both counts): what is
     * compared is the wavelength quadrature, and a Psi table per packed atmosphere would cost 2 s each (with it,
     * measured once: +0.008 %, +0.001 %, +0.000 %, -0.018 % on these rows; docs/spectral.md). */
    ref_quality q = {.view_steps = 128, .sun_steps = 64, .ms_sqrt_dirs = 4, .ms_steps = 8, .ms_off = 1};
    s48.q = s96.q = q;
    static const struct { double sun_el, view_az, view_el; const char *name; } rows[] = {
        {90.0, 0.0, 90.0, "noon, zenith"}, {2.0, 0.0, 2.0, "sun +2, horizon toward the sun"},
        {-4.0, 0.0, 90.0, "sun -4, zenith"}, {-4.0, 0.0, 5.0, "sun -4, 5 deg up toward the sun"}};
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; ++i) {
        double sun[3], v[3];
        ref_dir(0.0, rows[i].sun_el * PI / 180.0, sun);
        ref_dir(rows[i].view_az * PI / 180.0, rows[i].view_el * PI / 180.0, v);
        double y48 = lum_of(&s48, 0.001, v, sun), y96 = lum_of(&s96, 0.001, v, sun), e = y48 / y96 - 1.0;
        char msg[160];
        snprintf(msg, sizeof msg, "48 -> 96 wavelengths, %s: luminance %.6g -> %.6g cd/m^2 (%+.4f %%) < 0.1 %%",
                 rows[i].name, y48, y96, 100 * e);
        check(fabs(e) < 1e-3 && y96 > 0.0, msg);
    }
}

static void test_closed_form_zenith(void)
{
    model_atmosphere a;
    model_atmosphere_earth(&a);
    a.sun_angular_radius = 0.0;
    ref_spectral s;
    ref_spectral_init(&s, &a, 48);
    pt_settings pt = {.samples = 20000, .seed = 5, .max_bounces = 1, .threads = 2};
    s.pt = &pt;
    double up[3] = {0, 1, 0}, xyz[3], se[3];
    ref_spectral_radiance(&s, 0.0, up, up, xyz, se, NULL);
    /* The closed form, integrated over wavelength here on a 1 nm grid (trapezoid), not with the reference's
     * bins; medium from the same laws (the input, not the integrator). */
    const double top = a.top_radius - a.bottom_radius, HR = 8.0, HM = 1.2, g = a.mie_g;
    const double pR = 3.0 / (16.0 * PI) * 2.0, pM = (1 - g * g) / (4 * PI * pow(1 - g, 3.0));
    double want[3] = {0, 0, 0};
    for (double nm = 360.0; nm <= 830.0; nm += 1.0) {
        spectral_coefficients k;
        spectral_medium_eval(&s.medium, nm, &k);
        double fR = HR * (1 - exp(-top / HR)), fM = HM * (1 - exp(-top / HM)), fO = 15.0; /* tent: half width */
        double tau = k.rayleigh_scattering * fR + (k.mie_scattering + k.mie_absorption) * fM + k.ozone_absorption * fO;
        double L = spectrum_solar_irradiance(nm) * exp(-tau) * (k.rayleigh_scattering * pR * fR + k.mie_scattering * pM * fM);
        double cmf[3], w = (nm == 360.0 || nm == 830.0) ? 0.5 : 1.0;
        spectrum_cie1931(nm, cmf);
        for (int c = 0; c < 3; ++c)
            want[c] += 683.0 * L * cmf[c] * w;
    }
    for (int c = 0; c < 3; ++c) {
        char msg[200];
        double e = xyz[c] / want[c] - 1.0;
        snprintf(msg, sizeof msg, "single scattering, sun and view at the zenith: path tracer %c %.5g +- %.2g vs closed "
                 "form %.5g (%+.2f %%) within 4 sigma + 0.3 %%", "XYZ"[c], xyz[c], se[c], want[c], 100 * e);
        check(fabs(xyz[c] - want[c]) < 4.0 * se[c] + 3e-3 * want[c], msg);
    }
}

/* Single scattering at the zenith in twilight, the Earth's shadow in closed form: with the sun at elevation -e a
 * point at height h on the vertical sees the sun's centre only above the shadow height h_s = Rb (1 / cos e - 1), so
 * L = E int_{h_s}^{top} sigma_s(h) P(nu) T_view(0, h) T_sun(h) dh, nu = sin(-e). The sun's slant transmittance is
 * integrated here on a fine grid (its own geometry: plain 3D points, |p + t d| - Rb). */
static void test_shadow_single_scattering(void)
{
    model_atmosphere a;
    model_atmosphere_earth(&a);
    a.sun_angular_radius = 0.0;
    ref_spectral s;
    ref_spectral_init(&s, &a, 48);
    pt_settings pt = {.samples = 120000, .seed = 3, .max_bounces = 1, .threads = 2};
    s.pt = &pt;
    const double el = -6.0 * PI / 180.0, Rb = a.bottom_radius, Rt = a.top_radius, g = a.mie_g;
    const double hs = Rb * (1.0 / cos(el) - 1.0), nu = sin(el);
    double up[3] = {0, 1, 0}, sun[3] = {cos(el), sin(el), 0.0}, xyz[3], se[3], want[3] = {0, 0, 0};
    ref_spectral_radiance(&s, 0.0, up, sun, xyz, se, NULL);
    const double pR = 3.0 / (16.0 * PI) * (1 + nu * nu), pM = (1 - g * g) / (4 * PI * pow(1 + g * g - 2 * g * nu, 1.5));
    for (double nm = 365.0; nm < 830.0; nm += 10.0) {
        spectral_coefficients k;
        spectral_medium_eval(&s.medium, nm, &k);
        double L = 0.0, tau_v = 0.0, prev = 0.0;
        const int nh = 600;
        const double dh = (Rt - Rb) / nh;
        for (int i = 0; i < nh; ++i) {
            double h = (i + 0.5) * dh;
            double dR = model_density(&a.rayleigh_density, h), dM = model_density(&a.mie_density, h);
            double ext = k.rayleigh_scattering * dR + (k.mie_scattering + k.mie_absorption) * dM +
                         k.ozone_absorption * model_density(&a.ozone_density, h);
            tau_v += i ? 0.5 * (prev + ext) * dh : ext * 0.5 * dh; /* trapezoid from midpoint to midpoint */
            prev = ext;
            if (h <= hs)
                continue;
            /* the sun's slant path from (0, Rb + h, 0) to the top */
            double p[3] = {0.0, Rb + h, 0.0}, b = p[1] * sun[1], c = p[1] * p[1] - Rt * Rt;
            double tx = -b + sqrt(b * b - c), tau_s = 0.0;
            const int nt = 1500;
            for (int j = 0; j < nt; ++j) {
                double t = (j + 0.5) * tx / nt, q0 = t * sun[0], q1 = p[1] + t * sun[1];
                double hh = sqrt(q0 * q0 + q1 * q1) - Rb;
                tau_s += (k.rayleigh_scattering * model_density(&a.rayleigh_density, hh) +
                          (k.mie_scattering + k.mie_absorption) * model_density(&a.mie_density, hh) +
                          k.ozone_absorption * model_density(&a.ozone_density, hh)) * tx / nt;
            }
            L += (k.rayleigh_scattering * dR * pR + k.mie_scattering * dM * pM) * exp(-tau_v - tau_s) * dh;
        }
        double cmf[3];
        spectrum_cie1931(nm, cmf);
        for (int c = 0; c < 3; ++c)
            want[c] += 683.0 * spectrum_solar_irradiance(nm) * L * cmf[c] * 10.0;
    }
    printf("     shadow height at sun -6 deg: %.2f km\n", hs);
    for (int c = 0; c < 3; ++c) {
        char msg[200];
        snprintf(msg, sizeof msg, "single scattering, sun -6 deg, zenith (Earth's shadow below %.1f km): path tracer "
                 "%c %.5g +- %.2g vs quadrature %.5g (%+.2f %%) within 4 sigma + 1 %%", hs, "XYZ"[c], xyz[c], se[c],
                 want[c], 100 * (xyz[c] / want[c] - 1));
        check(fabs(xyz[c] - want[c]) < 4.0 * se[c] + 0.01 * want[c], msg);
    }
}

/* ---- The second tracer: nothing from src/reference, only the medium's laws and the spectral tables. ---- */

static uint64_t mt_state;
static double rnd(void)
{
    /* splitmix64: small and good enough for a test */
    uint64_t z = (mt_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (z >> 11) * (1.0 / 9007199254740992.0);
}

typedef struct mini { double Rb, Rt, bR, bMs, bMt, bO, g, major; const model_atmosphere *a; } mini;

static double len3(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/* Distance along d from p to the sphere of radius R (the far root; -1 if none). */
static double to_sphere(const double p[3], const double d[3], double R, int nearest)
{
    double b = p[0] * d[0] + p[1] * d[1] + p[2] * d[2], c = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - R * R;
    double disc = b * b - c;
    if (disc < 0.0)
        return -1.0;
    double s = sqrt(disc), t0 = -b - s, t1 = -b + s;
    if (nearest)
        return t0 > 1e-9 ? t0 : (t1 > 1e-9 ? t1 : -1.0);
    return t1;
}

static void mini_coeffs(const mini *m, const double p[3], double *sR, double *sM, double *st)
{
    double h = len3(p) - m->Rb;
    double rr = model_density(&m->a->rayleigh_density, h), rm = model_density(&m->a->mie_density, h);
    double ro = model_density(&m->a->ozone_density, h);
    *sR = m->bR * rr;
    *sM = m->bMs * rm;
    *st = *sR + m->bMt * rm + m->bO * ro;
}

/* Where the ray leaves the atmosphere or meets the ground (ground: *hit = 1). */
static double mini_exit(const mini *m, const double p[3], const double d[3], int *hit)
{
    double tg = to_sphere(p, d, m->Rb, 1);
    *hit = tg > 0.0;
    return *hit ? tg : to_sphere(p, d, m->Rt, 0);
}

static double mini_transmittance(const mini *m, const double p[3], const double d[3])
{
    int hit;
    double tmax = mini_exit(m, p, d, &hit), T = 1.0, t = 0.0;
    if (hit)
        return 0.0;
    for (;;) { /* ratio tracking */
        t -= log(1.0 - rnd()) / m->major;
        if (t >= tmax)
            return T;
        double q[3] = {p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2]}, sR, sM, st;
        mini_coeffs(m, q, &sR, &sM, &st);
        T *= 1.0 - st / m->major;
    }
}

static void frame_of(const double w[3], double u[3], double v[3])
{
    double a[3] = {fabs(w[0]) < 0.9 ? 1.0 : 0.0, fabs(w[0]) < 0.9 ? 0.0 : 1.0, 0.0};
    u[0] = a[1] * w[2] - a[2] * w[1], u[1] = a[2] * w[0] - a[0] * w[2], u[2] = a[0] * w[1] - a[1] * w[0];
    double l = len3(u);
    for (int i = 0; i < 3; ++i)
        u[i] /= l;
    v[0] = w[1] * u[2] - w[2] * u[1], v[1] = w[2] * u[0] - w[0] * u[2], v[2] = w[0] * u[1] - w[1] * u[0];
}

/* A new direction around w with cos theta drawn from the Rayleigh or HG phase (rejection against isotropic). */
static void mini_scatter(const mini *m, int mie, double w[3])
{
    double ct;
    for (;;) {
        ct = 2.0 * rnd() - 1.0;
        double p, pmax;
        if (mie) {
            double g = m->g, den = 1 + g * g - 2 * g * ct;
            p = (1 - g * g) / pow(den, 1.5), pmax = (1 - g * g) / pow(1 - g, 3.0);
        } else {
            p = 1 + ct * ct, pmax = 2.0;
        }
        if (rnd() * pmax < p)
            break;
    }
    double st = sqrt(fmax(0.0, 1 - ct * ct)), ph = 2 * PI * rnd(), u[3], v[3], n[3];
    frame_of(w, u, v);
    for (int i = 0; i < 3; ++i)
        n[i] = ct * w[i] + st * (cos(ph) * u[i] + sin(ph) * v[i]);
    memcpy(w, n, sizeof n);
}

static double phase_value(const mini *m, int mie, double ct)
{
    if (mie) {
        double g = m->g;
        return (1 - g * g) / (4 * PI * pow(1 + g * g - 2 * g * ct, 1.5));
    }
    return 3.0 / (16.0 * PI) * (1 + ct * ct);
}

/* One path at one wavelength from the camera p along d: radiance per unit sun irradiance. */
static double mini_path(const mini *m, const double p0[3], const double d0[3], const double sun[3])
{
    double p[3], d[3], L = 0.0, beta = 1.0;
    memcpy(p, p0, sizeof p);
    memcpy(d, d0, sizeof d);
    for (int bounce = 0; bounce < 200; ++bounce) {
        int hit;
        double tmax = mini_exit(m, p, d, &hit), t = 0.0, sR = 0, sM = 0, st = 0;
        for (;;) { /* delta tracking to the first real collision */
            t -= log(1.0 - rnd()) / m->major;
            if (t >= tmax)
                return L; /* left the atmosphere or reached the (black) ground */
            double q[3] = {p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2]};
            mini_coeffs(m, q, &sR, &sM, &st);
            if (rnd() * m->major < st)
                break;
        }
        for (int i = 0; i < 3; ++i)
            p[i] += t * d[i];
        /* a real collision: scattering with probability (sR + sM) / st, else absorbed */
        beta *= (sR + sM) / st;
        double ct = d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2];
        double ph = (sR * phase_value(m, 0, ct) + sM * phase_value(m, 1, ct)) / (sR + sM);
        L += beta * ph * mini_transmittance(m, p, sun);
        mini_scatter(m, rnd() * (sR + sM) < sM, d);
        if (beta < 0.05) { /* Russian roulette */
            if (rnd() > 0.5)
                return L;
            beta *= 2.0;
        }
    }
    return L;
}

static void mini_xyz(const model_atmosphere *a, const spectral_medium *sm, double h, const double v[3],
                     const double sun[3], long n, double xyz[3], double se[3])
{
    double s1[3] = {0}, s2[3] = {0};
    double p[3] = {0.0, a->bottom_radius + h, 0.0};
    mt_state = 12345;
    for (long i = 0; i < n; ++i) {
        double nm = 360.0 + 470.0 * rnd(), cmf[3];
        spectral_coefficients k;
        spectral_medium_eval(sm, nm, &k);
        mini m = {.Rb = a->bottom_radius, .Rt = a->top_radius, .bR = k.rayleigh_scattering, .bMs = k.mie_scattering,
                  .bMt = k.mie_scattering + k.mie_absorption, .bO = k.ozone_absorption, .g = a->mie_g, .a = a};
        m.major = m.bR + m.bMt + m.bO; /* every density is <= 1 */
        double L = mini_path(&m, p, v, sun) * spectrum_solar_irradiance(nm) * 470.0 * 683.0;
        spectrum_cie1931(nm, cmf);
        for (int c = 0; c < 3; ++c) {
            double x = L * cmf[c];
            s1[c] += x;
            s2[c] += x * x;
        }
    }
    for (int c = 0; c < 3; ++c) {
        xyz[c] = s1[c] / n;
        se[c] = sqrt(fmax(0.0, s2[c] / n - xyz[c] * xyz[c]) / (n - 1));
    }
}

static void test_second_tracer(void)
{
    model_atmosphere a;
    model_atmosphere_earth(&a);
    a.sun_angular_radius = 0.0; /* the second tracer's sun is a point */
    ref_spectral s;
    ref_spectral_init(&s, &a, 48);
    pt_settings pt = {.seed = 11, .threads = 2};
    s.pt = &pt;
    /* Twilight: most paths find no sunlit air, so both tracers need more of them there. */
    static const struct { double sun_el, view_az, view_el; long n, pt; const char *name; } rows[] = {
        {45.0, 90.0, 30.0, 60000, 6000, "sun +45, 30 deg up across"},
        {2.0, 0.0, 3.0, 60000, 6000, "sun +2, 3 deg up toward the sun"},
        {-4.0, 0.0, 90.0, 600000, 24000, "sun -4, zenith (in the Earth's shadow below ~16 km)"}};
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; ++i) {
        double sun[3], v[3], x1[3], e1[3], x2[3], e2[3];
        pt.samples = rows[i].pt;
        ref_dir(0.0, rows[i].sun_el * PI / 180.0, sun);
        ref_dir(rows[i].view_az * PI / 180.0, rows[i].view_el * PI / 180.0, v);
        ref_spectral_radiance(&s, 0.001, v, sun, x1, e1, NULL);
        mini_xyz(&a, &s.medium, 0.001, v, sun, rows[i].n, x2, e2);
        for (int c = 0; c < 3; ++c) {
            double sig = sqrt(e1[c] * e1[c] + e2[c] * e2[c]), d = x1[c] - x2[c];
            char msg[220];
            snprintf(msg, sizeof msg, "%s: %c path tracer %.5g +- %.2g, second tracer %.5g +- %.2g (%+.2f %%) "
                     "within 4 sigma + 1 %%", rows[i].name, "XYZ"[c], x1[c], e1[c], x2[c], e2[c], 100 * d / x2[c]);
            check(fabs(d) < 4.0 * sig + 0.01 * x2[c], msg);
        }
    }
}

int main(int argc, char **argv)
{
    const char *only = argc > 1 ? argv[1] : "";
    if (!*only || strstr(only, "rayleigh"))
        test_rayleigh_optical_depth();
    if (!*only || strstr(only, "converge"))
        test_wavelength_convergence();
    if (!*only || strstr(only, "closed"))
        test_closed_form_zenith();
    if (!*only || strstr(only, "shadow"))
        test_shadow_single_scattering();
    if (!*only || strstr(only, "tracer"))
        test_second_tracer();
    printf("%s\n", failures ? "FAILED" : "all passed");
    return failures ? 1 : 0;
}
