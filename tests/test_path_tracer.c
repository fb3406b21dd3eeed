/* tests/test_path_tracer.c: the Monte Carlo path tracer (src/reference/path_tracer.c) against an independent
 * single-scattering quadrature written here, plus physics and statistics checks. Standalone: prints every check,
 * returns non-zero on failure. ctest `path_tracer`.
 *
 *   a) max_bounces = 1 == brute-force single scattering (double integral along the view ray, transmittance to the
 *      sun and to the camera, binary earth shadow, no horizon fade) within 3 standard errors (+ a small floor
 *      covering the quadrature's own error);
 *   b) optically thin limit (all coefficients x 1e-3): the full path tracer == single scattering;
 *   c) all orders >= single scattering, noon zenith B > G > R, twilight (sun -6 deg) zenith darker than noon by a
 *      factor in 30..1e6 (printed: real physics gives ~4e3; the model, with its horizon fade, ~1.4e5 — see
 *      docs/model_error.md);
 *   d) standard error ~ 1/sqrt(N); determinism (same seed, 1 vs 2 threads: identical bits); camera in space;
 *   e) all orders (multiple scattering, ground bounce, twilight) == an independent analog path tracer written here
 *      (one global majorant, NEE at real collisions only, sun transmittance by quadrature, rejection-sampled phases).
 */
#include "reference/path_tracer.h"
#include "test_atmospheres.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

static int g_fail = 0;

static void check(int ok, const char *what)
{
    printf("%s  %s\n", ok ? "ok  " : "FAIL", what);
    if (!ok)
        g_fail = 1;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Independent single-scattering quadrature (plain 3D geometry, altitude = |p| - Rb).                          */

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void coeffs(const model_atmosphere *a, double h, double sR[3], double sM[3], double st[3])
{
    double rr = model_density(&a->rayleigh_density, h), rm = model_density(&a->mie_density, h);
    double ro = model_density(&a->ozone_density, h);
    if (ro < 0.0)
        ro = 0.0;
    for (int c = 0; c < 3; ++c) {
        sR[c] = a->rayleigh_scattering[c] * rr;
        sM[c] = a->mie_scattering[c] * rm;
        st[c] = sR[c] + (a->mie_scattering[c] + a->mie_absorption[c]) * rm + a->ozone_absorption[c] * ro;
    }
}

static double altitude_of(const model_atmosphere *a, const double p[3]) { return sqrt(dot(p, p)) - a->bottom_radius; }

/* Distance to the exit of the atmosphere from inside along d; *ground = 1 if the ray hits the planet first. */
static double exit_distance(const model_atmosphere *a, const double p[3], const double d[3], int *ground)
{
    double b = dot(p, d), pp = dot(p, p);
    double dg = b * b - (pp - a->bottom_radius * a->bottom_radius);
    if (b < 0.0 && dg >= 0.0) {
        *ground = 1;
        return -b - sqrt(dg);
    }
    *ground = 0;
    double dt = b * b - (pp - a->top_radius * a->top_radius);
    return -b + sqrt(dt > 0.0 ? dt : 0.0);
}

/* Optical depth along p + t d, t in [0, tend], n midpoint steps in u on each side of the lowest point (t = u^2
 * grading toward it). */
static void optical_depth(const model_atmosphere *a, const double p[3], const double d[3], double tend, int n,
                          double tau[3])
{
    double tl = -dot(p, d);
    tl = tl < 0.0 ? 0.0 : (tl > tend ? tend : tl);
    tau[0] = tau[1] = tau[2] = 0.0;
    const double len[2] = {tl, tend - tl};
    for (int side = 0; side < 2; ++side) {
        if (len[side] <= 0.0)
            continue;
        for (int k = 0; k < n; ++k) {
            double u = (k + 0.5) / n, du = 1.0 / n;
            double t = side == 0 ? tl - len[0] * u * u : tl + len[1] * u * u;
            double dt = 2.0 * len[side] * u * du, x[3], sR[3], sM[3], st[3];
            for (int i = 0; i < 3; ++i)
                x[i] = p[i] + t * d[i];
            coeffs(a, altitude_of(a, x), sR, sM, st);
            for (int c = 0; c < 3; ++c)
                tau[c] += st[c] * dt;
        }
    }
}

/* Single scattering along the view ray of an UPWARD view from altitude h (camera inside the atmosphere):
 * n_out steps along the view ray (graded toward the camera), n_in per side for each sun transmittance. */
static void single_scattering(const model_atmosphere *a, double h, const double v[3], const double s[3], int n_out,
                              int n_in, double out[3])
{
    double cam[3] = {0.0, a->bottom_radius + h, 0.0};
    int ground;
    double tend = exit_distance(a, cam, v, &ground);
    double nu = dot(v, s), g = a->mie_g;
    double pR = 3.0 / (16.0 * PI) * (1.0 + nu * nu);
    double pM = (1.0 - g * g) / (4.0 * PI * pow(1.0 + g * g - 2.0 * g * nu, 1.5));
    double tau_v[3] = {0.0, 0.0, 0.0};
    out[0] = out[1] = out[2] = 0.0;
    for (int k = 0; k < n_out; ++k) {
        double u = (k + 0.5) / n_out, du = 1.0 / n_out;
        double t = tend * u * u, dt = 2.0 * tend * u * du, x[3], sR[3], sM[3], st[3];
        for (int i = 0; i < 3; ++i)
            x[i] = cam[i] + t * v[i];
        coeffs(a, altitude_of(a, x), sR, sM, st);
        double Ts[3] = {0.0, 0.0, 0.0};
        int gs;
        double ts = exit_distance(a, x, s, &gs);
        if (!gs) {
            double tau_s[3];
            optical_depth(a, x, s, ts, n_in, tau_s);
            for (int c = 0; c < 3; ++c)
                Ts[c] = exp(-tau_s[c]);
        }
        for (int c = 0; c < 3; ++c) {
            double Tv = exp(-(tau_v[c] + 0.5 * st[c] * dt));
            out[c] += Tv * a->sun_illuminance[c] * (sR[c] * pR + sM[c] * pM) * Ts[c] * dt;
            tau_v[c] += st[c] * dt;
        }
    }
}

/* ---------------------------------------------------------------------------------------------------------- */
/* An independent analog path tracer (all orders): classic delta tracking against ONE global majorant per channel,
 * NEE only at real collisions with the sun transmittance by quadrature, phase sampling by rejection, plain 3D
 * geometry. Slow but simple; it checks the higher orders, the phase sampling and the ground bounce of the real
 * tracer, whose estimators (ratio-tracking NEE along every ray, per-segment majorants) share nothing with it. */

typedef struct lcg {
    unsigned long long s;
} lcg;

static double lcg_u(lcg *g) /* [0, 1), 53 bits of a 64-bit LCG (Knuth MMIX) + output mix */
{
    g->s = g->s * 6364136223846793005ull + 1442695040888963407ull;
    unsigned long long z = g->s;
    z ^= z >> 33;
    z *= 0xff51afd7ed558ccdull;
    z ^= z >> 33;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

static double phase_r(double c) { return 3.0 / (16.0 * PI) * (1.0 + c * c); }
static double phase_m(double g, double c) { return (1.0 - g * g) / (4.0 * PI * pow(1.0 + g * g - 2.0 * g * c, 1.5)); }

/* Unit vector at cos_t from n, azimuth phi, basis from cross products. */
static void around(const double n[3], double cos_t, double phi, double out[3])
{
    double ax[3] = {1.0, 0.0, 0.0};
    if (fabs(n[0]) > 0.6) {
        ax[0] = 0.0;
        ax[1] = 1.0;
    }
    double u[3] = {n[1] * ax[2] - n[2] * ax[1], n[2] * ax[0] - n[0] * ax[2], n[0] * ax[1] - n[1] * ax[0]};
    double lu = sqrt(dot(u, u));
    for (int i = 0; i < 3; ++i)
        u[i] /= lu;
    double w[3] = {n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
    double st = sqrt(fmax(0.0, 1.0 - cos_t * cos_t));
    for (int i = 0; i < 3; ++i)
        out[i] = cos_t * n[i] + st * (cos(phi) * u[i] + sin(phi) * w[i]);
}

/* cos theta by rejection from a uniform cos against the phase function (max at cos = 1 for both). */
static double reject_cos(lcg *g, double gm, int mie)
{
    double pmax = mie ? phase_m(gm, 1.0) : phase_r(1.0);
    for (;;) {
        double c = 2.0 * lcg_u(g) - 1.0;
        if (lcg_u(g) * pmax < (mie ? phase_m(gm, c) : phase_r(c)))
            return c;
    }
}

static double sun_T_quad(const model_atmosphere *a, const double x[3], const double s[3], int c)
{
    int gs;
    double ts = exit_distance(a, x, s, &gs), tau[3];
    if (gs)
        return 0.0;
    optical_depth(a, x, s, ts, 96, tau);
    return exp(-tau[c]);
}

static double analog_path(const model_atmosphere *a, double h, const double v[3], const double s[3], double albedo,
                          int c, lcg *g)
{
    const double maj = a->rayleigh_scattering[c] + a->mie_scattering[c] + a->mie_absorption[c] +
                       a->ozone_absorption[c]; /* >= sigma_t everywhere (sum of the profiles' maxima) */
    double x[3] = {0.0, a->bottom_radius + h, 0.0}, d[3] = {v[0], v[1], v[2]}, w = 1.0, L = 0.0;
    for (int depth = 0; depth < 400; ++depth) {
        int ground;
        double tend = exit_distance(a, x, d, &ground), t = 0.0, sR[3], sM[3], st[3];
        int hit = 0;
        for (;;) {
            t += -log(1.0 - lcg_u(g)) / maj;
            if (t >= tend)
                break;
            double y[3] = {x[0] + t * d[0], x[1] + t * d[1], x[2] + t * d[2]};
            coeffs(a, altitude_of(a, y), sR, sM, st);
            if (lcg_u(g) * maj < st[c]) {
                hit = 1;
                break;
            }
        }
        if (hit) {
            for (int i = 0; i < 3; ++i)
                x[i] += t * d[i];
            double ss = sR[c] + sM[c];
            w *= ss / st[c];
            double nu = dot(d, s);
            L += w * a->sun_illuminance[c] * (sR[c] * phase_r(nu) + sM[c] * phase_m(a->mie_g, nu)) / ss *
                 sun_T_quad(a, x, s, c);
            double cos_t = lcg_u(g) * ss < sR[c] ? reject_cos(g, a->mie_g, 0) : reject_cos(g, a->mie_g, 1);
            double nd[3];
            around(d, cos_t, 2.0 * PI * lcg_u(g), nd);
            memcpy(d, nd, sizeof d);
        } else if (ground && albedo > 0.0) {
            double n[3];
            for (int i = 0; i < 3; ++i)
                x[i] += tend * d[i];
            double lx = sqrt(dot(x, x));
            for (int i = 0; i < 3; ++i) {
                n[i] = x[i] / lx;
                x[i] = n[i] * a->bottom_radius;
            }
            w *= albedo;
            double cs = dot(n, s);
            if (cs > 0.0)
                L += w * a->sun_illuminance[c] * cs / PI * sun_T_quad(a, x, s, c);
            double nd[3];
            around(n, sqrt(lcg_u(g)), 2.0 * PI * lcg_u(g), nd);
            memcpy(d, nd, sizeof d);
        } else {
            break;
        }
    }
    return L;
}

static void analog_radiance(const model_atmosphere *a, double h, const double v[3], const double s[3], double albedo,
                            long n, unsigned long long seed, double out[3], double se[3])
{
    lcg g = {seed * 0x9E3779B97F4A7C15ull + 1};
    for (int c = 0; c < 3; ++c) {
        double sum = 0.0, sum2 = 0.0;
        for (long i = 0; i < n; ++i) {
            double x = analog_path(a, h, v, s, albedo, c, &g);
            sum += x;
            sum2 += x * x;
        }
        out[c] = sum / n;
        se[c] = sqrt(fmax(0.0, sum2 / n - out[c] * out[c]) / (n - 1));
    }
}

/* ---------------------------------------------------------------------------------------------------------- */

static double lum(const double c[3]) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }
static double lum_se(const double s[3])
{
    return sqrt(0.2126 * 0.2126 * s[0] * s[0] + 0.7152 * 0.7152 * s[1] * s[1] + 0.0722 * 0.0722 * s[2] * s[2]);
}

typedef struct view_case {
    const char *name;
    double sun_el_deg, view_az_deg, view_el_deg;
} view_case;

static const view_case k_views[] = {
    {"zenith, sun 90 (noon)", 90.0, 0.0, 90.0},
    {"horizon (2 deg) toward the sun, sun 5", 5.0, 0.0, 2.0},
    {"horizon (2 deg) away from the sun, sun 5", 5.0, 180.0, 2.0},
};
#define N_VIEWS (int)(sizeof k_views / sizeof k_views[0])

static const double k_cam_alt = 0.001; /* 1 m */

/* Compares PT (with settings s) against the quadrature on atmosphere a; rel_floor covers the quadrature error
 * and (for the thin limit) the neglected higher orders. */
static void compare_to_quadrature(const model_atmosphere *a, const pt_settings *s, double rel_floor, const char *tag)
{
    for (int i = 0; i < N_VIEWS; ++i) {
        const view_case *vc = &k_views[i];
        double v[3], sd[3], q[3], q2[3], pt[3], se[3];
        ref_dir(vc->view_az_deg * DEG, vc->view_el_deg * DEG, v);
        ref_dir(0.0, vc->sun_el_deg * DEG, sd);
        single_scattering(a, k_cam_alt, v, sd, 2000, 200, q);
        single_scattering(a, k_cam_alt, v, sd, 4000, 400, q2);
        pt_radiance(a, k_cam_alt, v, sd, s, pt, se);
        int ok = 1;
        for (int c = 0; c < 3; ++c) {
            double qerr = fabs(q2[c] - q[c]);
            double tol = 3.0 * se[c] + 10.0 * qerr + rel_floor * q2[c] + 1e-12;
            if (!(fabs(pt[c] - q2[c]) <= tol))
                ok = 0;
        }
        char msg[512];
        snprintf(msg, sizeof msg,
                 "%s %-42s quad (%.6g %.6g %.6g) [quad conv %.1e]  PT (%.6g %.6g %.6g) +- (%.2g %.2g %.2g) "
                 "z = (%+.2f %+.2f %+.2f)",
                 tag, vc->name, q2[0], q2[1], q2[2], fabs(q2[2] - q[2]) / q2[2], pt[0], pt[1], pt[2], se[0], se[1],
                 se[2], (pt[0] - q2[0]) / se[0], (pt[1] - q2[1]) / se[1], (pt[2] - q2[2]) / se[2]);
        check(ok, msg);
    }
}

int main(void)
{
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    model_atmosphere earth;
    model_atmosphere_earth(&earth);

    /* a) single scattering */
    printf("-- a) max_bounces = 1 vs independent single-scattering quadrature\n");
    pt_settings ss = {80000, 1234, 0.0, 1, 2};
    compare_to_quadrature(&earth, &ss, 1e-5, "single:");

    /* a2) single scattering in a layered medium: Bruneton layer pairs the segment majorants must bound exactly
     * (model_density_max): a 2 km well-mixed haze layer under an exponential tail, an ozone layer with a flat top
     * and Rayleigh with a linear term. A majorant below the density would bias PT low. */
    printf("-- a2) max_bounces = 1 in a layered medium vs the quadrature\n");
    {
        model_atmosphere layered = test_layered_atmosphere();
        compare_to_quadrature(&layered, &ss, 1e-5, "layered:");
    }

    /* a3) extra species: copies of ozone and of Rayleigh (Rayleigh phase) as extra species trace the medium of
     * doubled ozone and Rayleigh: the two estimates agree within their standard errors (all orders). */
    printf("-- a3) extra species copying ozone and Rayleigh vs the doubled species (all orders)\n");
    {
        model_atmosphere extras, doubled;
        test_extra_species_pair(&earth, &extras, &doubled);
        double v[3], sd[3], A[3], sA[3], B[3], sB[3], P[3], sP[3];
        ref_dir(180.0 * DEG, 5.0 * DEG, v);
        ref_dir(0.0, 20.0 * DEG, sd);
        pt_settings pe = {40000, 11, 0.0, 0, 2}, pd = {40000, 12, 0.0, 0, 2};
        pt_radiance(&extras, k_cam_alt, v, sd, &pe, A, sA);
        pt_radiance(&doubled, k_cam_alt, v, sd, &pd, B, sB);
        pt_radiance(&earth, k_cam_alt, v, sd, &pd, P, sP);
        int ok = 1;
        for (int c = 0; c < 3; ++c)
            if (!(fabs(A[c] - B[c]) <= 3.0 * sqrt(sA[c] * sA[c] + sB[c] * sB[c])) ||
                !(fabs(B[c] - P[c]) > 3.0 * sqrt(sB[c] * sB[c] + sP[c] * sP[c])))
                ok = 0;
        char msg[512];
        snprintf(msg, sizeof msg,
                 "extras (%.5g %.5g %.5g) +- (%.2g %.2g %.2g)  doubled (%.5g %.5g %.5g) +- (%.2g %.2g %.2g)  "
                 "Earth (%.5g %.5g %.5g): extras = doubled, doubled != Earth",
                 A[0], A[1], A[2], sA[0], sA[1], sA[2], B[0], B[1], B[2], sB[0], sB[1], sB[2], P[0], P[1], P[2]);
        check(ok, msg);
    }

    /* b) optically thin limit */
    printf("-- b) optically thin limit (coefficients x 1e-3): all orders vs single-scattering quadrature\n");
    model_atmosphere thin = earth;
    for (int c = 0; c < 3; ++c) {
        thin.rayleigh_scattering[c] *= 1e-3;
        thin.mie_scattering[c] *= 1e-3;
        thin.mie_absorption[c] *= 1e-3;
        thin.ozone_absorption[c] *= 1e-3;
    }
    pt_settings full_thin = {80000, 99, 0.0, 0, 2};
    compare_to_quadrature(&thin, &full_thin, 2e-3, "thin:");

    /* c) physics */
    printf("-- c) physics\n");
    pt_settings full = {12000, 7, 0.0, 0, 2};
    double noon[3] = {0.0, 0.0, 0.0}, noon_se[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < N_VIEWS; ++i) {
        const view_case *vc = &k_views[i];
        double v[3], sd[3], L1[3], s1[3], La[3], sa[3];
        ref_dir(vc->view_az_deg * DEG, vc->view_el_deg * DEG, v);
        ref_dir(0.0, vc->sun_el_deg * DEG, sd);
        pt_radiance(&earth, k_cam_alt, v, sd, &ss, L1, s1);
        pt_radiance(&earth, k_cam_alt, v, sd, &full, La, sa);
        int ok = 1;
        for (int c = 0; c < 3; ++c)
            if (!(La[c] - L1[c] >= -3.0 * sqrt(s1[c] * s1[c] + sa[c] * sa[c])))
                ok = 0;
        char msg[512];
        snprintf(msg, sizeof msg,
                 "all orders >= single, %-42s all (%.5g %.5g %.5g) single (%.5g %.5g %.5g): multiple scattering "
                 "adds (%.1f%% %.1f%% %.1f%%)",
                 vc->name, La[0], La[1], La[2], L1[0], L1[1], L1[2], 100.0 * (La[0] / L1[0] - 1.0),
                 100.0 * (La[1] / L1[1] - 1.0), 100.0 * (La[2] / L1[2] - 1.0));
        check(ok, msg);
        if (i == 0) {
            memcpy(noon, La, sizeof noon);
            memcpy(noon_se, sa, sizeof noon_se);
        }
    }
    {
        char msg[256];
        snprintf(msg, sizeof msg, "noon zenith B > G > R: (%.5g %.5g %.5g) +- (%.2g %.2g %.2g)", noon[0], noon[1],
                 noon[2], noon_se[0], noon_se[1], noon_se[2]);
        check(noon[2] - 3.0 * noon_se[2] > noon[1] + 3.0 * noon_se[1] &&
                  noon[1] - 3.0 * noon_se[1] > noon[0] + 3.0 * noon_se[0],
              msg);
    }
    {
        double v[3] = {0.0, 1.0, 0.0}, sd[3], tw[3], tw_se[3];
        ref_dir(0.0, -6.0 * DEG, sd);
        pt_settings twi = {40000, 11, 0.0, 0, 2};
        pt_radiance(&earth, k_cam_alt, v, sd, &twi, tw, tw_se);
        double ratio = lum(noon) / lum(tw);
        char msg[256];
        snprintf(msg, sizeof msg,
                 "twilight (sun -6 deg) zenith luminance %.4g +- %.2g (%.1f%%), noon %.4g: noon/twilight = %.4g "
                 "(loose physical range 30..1e6)",
                 lum(tw), lum_se(tw_se), 100.0 * lum_se(tw_se) / lum(tw), lum(noon), ratio);
        check(ratio > 30.0 && ratio < 1e6, msg);
    }

    /* d) statistics, determinism, camera in space */
    printf("-- d) statistics\n");
    {
        double v[3] = {0.0, 1.0, 0.0}, sd[3] = {0.0, 1.0, 0.0}, La[3], sa[3], Lb[3], sb[3];
        pt_settings s1 = {4000, 21, 0.0, 0, 2}, s4 = {16000, 22, 0.0, 0, 2};
        pt_radiance(&earth, k_cam_alt, v, sd, &s1, La, sa);
        pt_radiance(&earth, k_cam_alt, v, sd, &s4, Lb, sb);
        int ok = 1;
        for (int c = 0; c < 3; ++c) {
            double r = sa[c] / sb[c];
            if (!(r > 1.6 && r < 2.5))
                ok = 0;
        }
        char msg[256];
        snprintf(msg, sizeof msg, "stderr(N) / stderr(4N) = (%.3f %.3f %.3f), expected ~2", sa[0] / sb[0],
                 sa[1] / sb[1], sa[2] / sb[2]);
        check(ok, msg);
    }
    {
        double v[3], sd[3], L1[3], L2[3], e1[3], e2[3];
        ref_dir(0.7, 0.3, v);
        ref_dir(0.0, 0.1, sd);
        pt_settings a1 = {3000, 5, 0.3, 0, 1}, a2 = {3000, 5, 0.3, 0, 2};
        pt_radiance(&earth, 2.0, v, sd, &a1, L1, e1);
        pt_radiance(&earth, 2.0, v, sd, &a2, L2, e2);
        check(memcmp(L1, L2, sizeof L1) == 0 && memcmp(e1, e2, sizeof e1) == 0,
              "deterministic: same seed, 1 vs 2 threads give identical bits (ground albedo 0.3)");
    }
    {
        /* Nadir from space (200 km) == nadir from the top (100 km): the same ray, entered first. */
        double v[3] = {0.0, -1.0, 0.0}, sd[3], Ls[3], es[3], Lt[3], et[3], Lm[3], em[3];
        ref_dir(0.0, 30.0 * DEG, sd);
        pt_settings sp = {6000, 8, 0.3, 0, 2}, st = {6000, 9, 0.3, 0, 2};
        pt_radiance(&earth, 200.0, v, sd, &sp, Ls, es);
        pt_radiance(&earth, 100.0, v, sd, &st, Lt, et);
        int ok = Ls[2] > 0.0;
        for (int c = 0; c < 3; ++c)
            if (!(fabs(Ls[c] - Lt[c]) <= 3.0 * sqrt(es[c] * es[c] + et[c] * et[c])))
                ok = 0;
        char msg[256];
        snprintf(msg, sizeof msg, "camera in space: nadir from 200 km (%.5g %.5g %.5g) == from 100 km (%.5g %.5g %.5g)",
                 Ls[0], Ls[1], Ls[2], Lt[0], Lt[1], Lt[2]);
        check(ok, msg);
        double up[3] = {0.0, 1.0, 0.0};
        pt_radiance(&earth, 200.0, up, sd, &sp, Lm, em);
        check(Lm[0] == 0.0 && Lm[1] == 0.0 && Lm[2] == 0.0, "camera in space looking away from the planet: 0");
    }

    /* e) higher orders against the independent analog tracer */
    printf("-- e) all orders vs an independent analog path tracer (global majorant, collision NEE)\n");
    {
        static const struct {
            const char *name;
            double sun_el, az, el, albedo;
        } cases[] = {
            {"zenith, sun 90, albedo 0", 90.0, 0.0, 90.0, 0.0},
            {"zenith, sun 30, albedo 0.3", 30.0, 0.0, 90.0, 0.3},
            {"horizon (2 deg) away from the sun, sun 5, albedo 0", 5.0, 180.0, 2.0, 0.0},
            {"horizon (2 deg) toward the sun, sun -2 (twilight)", -2.0, 0.0, 2.0, 0.0},
        };
        for (int i = 0; i < (int)(sizeof cases / sizeof cases[0]); ++i) {
            double v[3], sd[3], A[3], sA[3], P[3], sP[3];
            ref_dir(cases[i].az * DEG, cases[i].el * DEG, v);
            ref_dir(0.0, cases[i].sun_el * DEG, sd);
            analog_radiance(&earth, k_cam_alt, v, sd, cases[i].albedo, 60000, 100 + i, A, sA);
            pt_settings ps = {60000, 200 + i, cases[i].albedo, 0, 2};
            pt_radiance(&earth, k_cam_alt, v, sd, &ps, P, sP);
            int ok = 1;
            for (int c = 0; c < 3; ++c)
                if (!(fabs(P[c] - A[c]) <= 3.0 * sqrt(sA[c] * sA[c] + sP[c] * sP[c]) + 1e-3 * A[c]))
                    ok = 0;
            char msg[512];
            snprintf(msg, sizeof msg,
                     "%-50s analog (%.5g %.5g %.5g) +- (%.2g %.2g %.2g)  PT (%.5g %.5g %.5g) +- (%.2g %.2g %.2g)",
                     cases[i].name, A[0], A[1], A[2], sA[0], sA[1], sA[2], P[0], P[1], P[2], sP[0], sP[1], sP[2]);
            check(ok, msg);
        }
    }

    clock_gettime(CLOCK_MONOTONIC, &t1);
    printf("%s (%.1f s)\n", g_fail ? "FAILED" : "all passed",
           (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec));
    return g_fail;
}
