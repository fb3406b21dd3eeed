/* Internals of the CPU reference (src/reference/), shared by its files and by nothing outside it.
 *
 * Which file holds what:
 *   medium_eval.c  the medium at a point, optical depth, ref_transmittance
 *   geometry.c     ray/sphere geometry: ground hits, shadow and fade crossings, the graded ray steps
 *   mappings.c     directions, the Bruneton transmittance-LUT mapping, the Ms LUT texel parameters
 *   multiscatter.c the Psi quadratures (ref_multiscatter, ref_multiscatter_converged) and their polar rules
 *   sun_table.c    the bicubic taps, the sun transmittance table, the cancellation flag (used by the two below)
 *   psi_table.c    the Psi table and its cache (filled by multiscatter.c's quadrature)
 *   radiance.c     ref_sky_radiance (the view march), ref_quality_converged, ref_pixel_dir
 *
 * Everything is double precision. Geometry never forms Rb + h and subtracts Rb again: altitudes along a ray come
 * from h_t = (h (2 Rb + h) + t^2 + 2 r mu t) / (r_t + Rb), and every root is taken in its cancellation-free form.
 * The small helpers that the integrators' inner loops call per sample are static inline here, so that they stay
 * inlined there as they were when all of this was one file. */
#ifndef VKSKY_REF_INTERNAL_H
#define VKSKY_REF_INTERNAL_H

#include "reference/ref_atmosphere.h"

#include <math.h>
#include <stddef.h>

#define REF_PI 3.14159265358979323846

static inline double clampd(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }

/* ---------------------------------------------------------------------------------------------------------- */
/* Medium (medium_eval.c)                                                                                     */

typedef struct medium {
    double sr[3], sm[3]; /* scattering with the Rayleigh phase (Rayleigh and the extra species), with Mie's */
    double scat[3], ext[3];
} medium;

void medium_at(const model_atmosphere *a, double h, medium *m);

static inline double phase_rayleigh(double nu) { return 3.0 / (16.0 * REF_PI) * (1.0 + nu * nu); }

static inline double phase_hg(double g, double nu)
{
    double den = 1.0 + g * g - 2.0 * g * nu;
    if (den < 1e-300)
        den = 1e-300;
    return (1.0 - g * g) / (4.0 * REF_PI * den * sqrt(den));
}

/* (1 - exp(-sigma dt)) / sigma, -> dt as sigma -> 0. */
static inline double step_integral(double sigma, double dt)
{
    double x = sigma * dt;
    if (x < 1e-12)
        return dt * (1.0 - 0.5 * x);
    return -expm1(-x) / sigma;
}

/* Optical depth to the top (no ground test), `steps` uniform midpoint steps. */
void optical_depth(const model_atmosphere *a, double h, double mu, int steps, double tau[3]);

/* ---------------------------------------------------------------------------------------------------------- */
/* Geometry (docs/model.md "Numerics"; geometry.c)                                                            */

static inline double atmo_height(const model_atmosphere *a) { return a->top_radius - a->bottom_radius; }

/* r^2 - Rb^2 = h (2 Rb + h) */
static inline double rho2_of(const model_atmosphere *a, double h) { return h * (2.0 * a->bottom_radius + h); }

/* Distance to the top from inside, -r mu + sqrt(r^2 (mu^2 - 1) + Rt^2), with Rt^2 - r^2 = c = (top - h)(Rt + r)
 * and, for mu > 0, the root rationalised (c / (r mu + sqrt(..))) so that nothing cancels near mu = 1. */
static inline double dist_top_rc(double r, double c, double mu)
{
    double disc = c + r * r * mu * mu;
    double s = sqrt(disc > 0.0 ? disc : 0.0), d;
    if (mu > 0.0) {
        double den = r * mu + s;
        d = den > 0.0 ? c / den : 0.0;
    } else {
        d = -r * mu + s;
    }
    return d > 0.0 ? d : 0.0;
}

static inline double dist_to_top(const model_atmosphere *a, double h, double mu)
{
    double r = a->bottom_radius + h;
    return dist_top_rc(r, (atmo_height(a) - h) * (a->top_radius + r), mu);
}

/* Inclusive ground test (mu < 0 and h (2 Rb + h) <= r^2 mu^2) and its near root. */
int hit_ground(const model_atmosphere *a, double h, double mu, double *t);

/* Point at distance t along a ray from (h, r = Rb + h, mu): its radius r_t and altitude h_t. */
static inline void ray_point(const model_atmosphere *a, double h, double r, double mu, double t, double *rt,
                             double *ht)
{
    double q = rho2_of(a, h) + t * t + 2.0 * r * mu * t; /* r_t^2 - Rb^2 */
    double r2 = r * r + t * t + 2.0 * r * mu * t;
    double s = sqrt(r2 > 0.0 ? r2 : 0.0);
    *rt = s;
    *ht = q / (s + a->bottom_radius);
}

/* Sun visibility of the atmosphere's model (model/sun_visibility.h) at a point (rho2 = h (2Rb + h), r = Rb + h) and
 * *mu_t, the sun zenith cosine at which to read the sun's transmittance. The lesson's fade: the earth shadow
 * (inclusive ground test toward the sun) times saturate(10 mu_s + 0.5). The penumbra: the visible fraction of the
 * disc, with two exact early outs that cost no trigonometry in the integrators' inner loops (asin(mu_s) >= mu_s for
 * mu_s >= 0, and asin(mu_s) <= mu_s, atan(rho / Rb) <= rho / Rb below). */
static inline double sun_visibility_at(const model_atmosphere *a, double rho2, double r, double mus, double *mu_t)
{
    *mu_t = mus;
    if (a->sun_visibility == MODEL_SUN_VISIBILITY_LESSON_FADE) {
        if (mus < 0.0 && rho2 <= r * r * mus * mus)
            return 0.0;
        return clampd(10.0 * mus + 0.5, 0.0, 1.0);
    }
    double R = a->sun_angular_radius;
    if (mus >= R && R > 0.0)
        return 1.0;
    double rho = sqrt(rho2 > 0.0 ? rho2 : 0.0);
    if (mus + rho / a->bottom_radius <= -R)
        return 0.0;
    return model_sun_visibility(MODEL_SUN_VISIBILITY_PENUMBRA, rho, r, a->bottom_radius, mus, R, mu_t);
}

/* Where the sun visibility of the lesson's model is not smooth along a ray: the earth's shadow boundary (a jump)
 * and mu_s = -0.05 / +0.05 (the kinks of the horizon fade). Up to 6 distances in (0, tend), sorted. Integrating each
 * piece separately keeps the midpoint rule second-order (a jump inside a step makes it first order, a kink
 * makes its error erratic). The penumbra is smooth (its width, 2R ~ 60 km of path at the ground, spans many
 * steps): no cuts. */
#define MAX_CUTS 6
int ray_cuts(const model_atmosphere *a, double h, double mu, double mus, double nu, double tend, double *cuts);

/* Step k of `steps` along a ray of length tend from (h, mu): its midpoint t and its length dt.
 * graded == 0: uniform steps (the model's march). graded != 0: steps graded quadratically in a uniform parameter
 * toward the lowest point of the ray, where the density changes fastest (the start for upward rays, the end for
 * ground hits, the tangent point t = -r mu otherwise). Same integral, 4-8x smaller error at equal counts. */
void ray_step(const model_atmosphere *a, double h, double mu, double tend, int ground, int graded, int steps,
              int k, double *t, double *dt);

/* ---------------------------------------------------------------------------------------------------------- */
/* LUT mappings (mappings.c)                                                                                  */

static inline double bruneton_H(const model_atmosphere *a)
{
    return sqrt((a->top_radius - a->bottom_radius) * (a->top_radius + a->bottom_radius));
}

/* (h, mu) -> (x_mu, x_r), both clamped to [0, 1]. */
void bruneton_x(const model_atmosphere *a, double h, double mu, double *x_mu, double *x_r);

/* (x_mu, x_r) -> (h, mu). */
void bruneton_params(const model_atmosphere *a, double x_mu, double x_r, double *h_out, double *mu_out);

/* ---------------------------------------------------------------------------------------------------------- */
/* Tables and their interpolation (sun_table.c)                                                               */

static inline void catmull_rom(double f, double w[4])
{
    double f2 = f * f, f3 = f2 * f;
    w[0] = 0.5 * (-f3 + 2.0 * f2 - f);
    w[1] = 0.5 * (3.0 * f3 - 5.0 * f2 + 2.0);
    w[2] = 0.5 * (-3.0 * f3 + 4.0 * f2 + f);
    w[3] = 0.5 * (f3 - f2);
}

/* Catmull-Rom weights for continuous index f in [0, n-1] over n nodes, folded onto 4 in-range node indices.
 * Ghost nodes -1 and n: linear extrapolation (2 v0 - v1), which keeps the ends second-order accurate, or, where
 * the tabulated function is even about that end in the index variable (a grid quadratic in the physical variable
 * there, like h = h0 + c y^2), the mirror image (v1). */
void cubic_taps(double f, int n, int mirror_lo, int mirror_hi, int idx[4], double w[4]);

/* The sun transmittance table, only for filling the Psi table fast: T on a Bruneton grid (nodes at x = k/(N-1)),
 * integrated with SUN_TABLE_STEPS uniform midpoint steps and interpolated bicubically (Catmull-Rom). Measured
 * against direct integration (4000 steps) at 17k random points with the sun above the horizon and mu >= -0.05:
 * |dT| <= 9e-4, and > 1e-4 only on rays grazing the kinks of the ozone tent (tangent altitude ~ 10, 25, 40 km).
 * In Psi it averages out: Psi with this table vs Psi with direct transmittance (500 steps), same quadrature, 60
 * random (h, mu_s): max rel. difference 1.3e-5. */
#define SUN_TABLE_NX 256
#define SUN_TABLE_NY 128
#define SUN_TABLE_STEPS 500

typedef struct sun_table {
    double T[SUN_TABLE_NY][SUN_TABLE_NX][3];
} sun_table;

/* The table of atmosphere a (malloc'd; NULL when out of memory). */
sun_table *sun_table_build(const model_atmosphere *a);

/* Bicubic lookup of the sun table at (h, mu), clamped to [0, 1]. */
void sun_table_eval(const sun_table *t, const model_atmosphere *a, double h, double mu, double T[3]);

/* Whether the flag given to ref_set_cancel is raised (a table build stops between rows). */
int ref_cancelled(void);

/* ---------------------------------------------------------------------------------------------------------- */
/* Psi quadrature (multiscatter.c)                                                                            */

/* Polar quadrature over mu in [-1, 1]: nodes and weights (sum of weights = 2). */
typedef struct polar_rule {
    int count;
    double *mu, *w;
} polar_rule;

/* Horizon-split rule: n/2 Gauss-Legendre nodes above and n/2 below the horizon mu_h = -rho/r, each side in s with
 * mu = mu_h +- (1 -+ mu_h) s^2. The ground/sky jump sits on the split and the substitution removes the
 * sqrt(mu_h - mu) behaviour of the ground distance at grazing. */
int polar_horizon(const model_atmosphere *a, double h, int n, polar_rule *p);

/* The second bounce's angular moments at a point (docs/model.md "The second bounce's anisotropy"), in the point's
 * frame x toward the sun's azimuth, y across it, z up, of the second order's incoming light L2 (green), times the
 * share of Psi that keeps L2's distribution (the 2nd and 3rd orders: 1 - f_ms^2): D = E[w_x^2 - w_y^2],
 * Q_zz = E[w_z^2] - 1/3, Q_xz = E[w_x w_z] (the traceless second moment; y is a mirror plane, so the other
 * components vanish), m_x = E[w_x], m_z = E[w_z] (the first). */
enum { MS_D, MS_QZZ, MS_QXZ, MS_MX, MS_MZ, MS_Z3, MS_Z4, MS_Z5, MS_Z6, MS_MOMENTS };
/* ... and the zonal moments of degrees 3 to 6, MS_Z3 + (l - 3) = E[P_l(w_z)] likewise weighted: the part of L2
 * that is symmetric about the vertical (the bright band of long paths along the horizon) to a higher degree, for
 * Mie's forward lobe, whose Legendre coefficients g^l fall slowly (docs/model.md). */
#define MS_ZONAL_FIRST 3
#define MS_ZONAL_LAST 6

/* P_0(x) .. P_n(x) into p[0 .. n]. */
void legendre_upto(double x, int n, double *p);

/* The model's scheme averages the first bounce's phases over PHASE_CELL^2 points of each direction's cell (the GPU's
 * multiscatter_lut.comp has the same constant). */
#define MS_PHASE_CELL 4

/* Psi(h, mu_s[q]) for `count` sun cosines at one (already clamped) altitude: n_az azimuths (midpoints in theta,
 * as the model) times the polar rule, `steps` steps per direction (uniform, or graded with the steps that
 * straddle the earth's shadow integrated piecewise). The nested sun transmittance is integrated directly with
 * sun_steps, or, when `st` is given, read from the sun table. The view geometry, the view transmittance and f_ms
 * do not depend on the sun, so they are computed once per (polar node, step) and shared by all azimuths and sun
 * cosines; azimuths theta and 2 pi - theta (i and n_az - 1 - i) are mirror images about the sun's plane and
 * contribute equally, so only half of them are evaluated. Returns 0 when out of memory (out = 0). */
int multiscatter_row(const model_atmosphere *a, double h, const double *mus, int count, int n_az,
                     const polar_rule *pr, int steps, int graded, int sun_steps, const sun_table *st,
                     double (*out)[3], double (*mom)[MS_MOMENTS]);

/* The 10 m altitude clamp of every Psi evaluation. */
static inline double ms_altitude(const model_atmosphere *a, double h) { return clampd(h, 0.01, atmo_height(a)); }

/* The converged quadrature's azimuth count for a given sqrt_dirs (the polar count): the periodic azimuth integral
 * converges faster than the polar one (spectrally in daylight; in twilight, where only azimuths toward the sun
 * reach lit air, still ~1e-4 at 24), so it gets half as many nodes. */
static inline int ms_azimuths(int sqrt_dirs) { return sqrt_dirs / 2 > 2 ? sqrt_dirs / 2 : 2; }

/* Steps per Psi ray of the converged quadrature: twice as many for a sun below mu_s = -0.05 (twilight: the
 * light then comes from lit air far along the rays, where the graded steps are longest). */
static inline int ms_steps_for(int steps, double mus) { return mus < -0.05 ? 2 * steps : steps; }

/* ---------------------------------------------------------------------------------------------------------- */
/* Psi table (psi_table.c)                                                                                    */

typedef struct psi_table psi_table;

/* The Psi table of (atmosphere, ms_sqrt_dirs, ms_steps), built on first use and cached (see psi_table.c); NULL when
 * out of memory. Building is not thread-safe; looking up an existing table is. */
const psi_table *psi_cache_get(const model_atmosphere *a_in, int sqrt_dirs, int steps);

/* A new Psi table, uncached, its rows filled on `threads` threads (0: the machine's cores, at most one per row); the
 * same bytes for any count (tests/test_psi_threads.c). psi_table_bytes: its size, for comparing two. Not thread-safe
 * (the sun table it reads is the cache's). */
psi_table *psi_table_build(const model_atmosphere *a, int sqrt_dirs, int steps, int threads);
size_t psi_table_bytes(void);
/* Psi tables on disk for the test suite (psi_disk.c; psi_cache_get uses them when VKSKY_PSI_CACHE names a directory):
 * the `bytes` of a table stored by an earlier process under key_atmosphere (psi_key_atmosphere's) and the counts, or
 * NULL (none, or not a good file of this key); and a table stored. They know nothing of the table's layout. */
void *psi_disk_load(const char *dir, const model_atmosphere *key_atmosphere, int sqrt_dirs, int steps, size_t bytes);
void psi_disk_store(const char *dir, const model_atmosphere *key_atmosphere, int sqrt_dirs, int steps, const void *t,
                    size_t bytes);
/* The atmosphere as a table's key holds it (the bytes that change Psi: E left out, g where it does not matter). */
void psi_key_atmosphere(const model_atmosphere *a, model_atmosphere *key);
/* Forgets every cached table (tests: the next psi_cache_get loads or builds again). */
void psi_cache_clear(void);

/* Psi(h, mu_s) interpolated from the table (h clamped as ms_altitude does), and mom, the second bounce's moments
 * (all 0 for the lesson's model); ms_phase_factor turns them into the factors on the Psi term. */
void psi_table_eval(const psi_table *t, const model_atmosphere *a, double h, double mus, double out[3],
                    double mom[MS_MOMENTS]);
/* k: the phase's Legendre coefficients k_1 .. k_6 (Rayleigh: 0, 1/10, 0, ...; Henyey-Greenstein: g^l). */
double ms_phase_factor(const double mom[MS_MOMENTS], double vx, double vz, const double k[MS_ZONAL_LAST]);

#endif /* VKSKY_REF_INTERNAL_H */
