/* vksky path tracer, one path of one channel (path_tracer.h says what it computes; path_tracer.c drives it).
 *
 * Estimator, per colour channel c (traced monochromatically: sigma_t, sigma_s of channel c only):
 *
 *   L(x, d) = int_0^tend T(x, x_t) sigma_s(x_t) [ E p(d.s) T_sun(x_t) V(x_t) + int p L(x_t, d') dd' ] dt
 *             + T(x, x_tend) L_ground            (when the ray ends on the ground)
 *
 * Every ray is sampled with a null-collision (majorant) process of rate sigma_bar(t) >= sigma_t(t) (piecewise
 * constant, see "Segments"). Its tentative points x_i (i = 1, 2, ...) serve two unbiased estimators at once:
 *  - direct term (next-event estimation toward the sun): sum_i Tr_i sigma_s p E T_sun(x_i) V(x_i) / sigma_bar_i,
 *    with Tr_i = prod_{j<i} (1 - sigma_t(x_j) / sigma_bar_j) the ratio-tracking estimate of T(x, x_i). For a
 *    Poisson process E[sum_i f(x_i, past)] = int E[f(t, past)] sigma_bar dt and E[Tr(t)] = T(t), so this is
 *    unbiased. T_sun is itself a ratio-tracking estimate along the sun ray; V is the binary earth shadow
 *    (inclusive ground test, docs/model.md). No horizon fade.
 *  - indirect term: the first tentative point accepted with probability sigma_t / sigma_bar is the first real
 *    collision of delta tracking (pdf sigma_t T); the path continues from it with weight sigma_s / sigma_t and a
 *    direction sampled from the phase mixture (Rayleigh with probability sigma_sR / sigma_s, else HG), whose
 *    sampling pdf cancels the phase function. If no real collision happens and the ray ends on the ground, the
 *    path continues from the ground (probability T) with weight albedo and a cosine-weighted direction; the
 *    ground's direct term (albedo / pi) E cos T_sun is the last term of the ratio-tracking sum (weight Tr_end).
 * The running Tr is Russian-rouletted below 0.02 (survivors reset to 0.02), which is unbiased and stops the
 * direct-term pass early on optically thick rays; the sun transmittance likewise.
 *
 * Segments: a ray [0, tend] is cut at its lowest point (the tangent point t = -r mu, clamped) into an altitude-
 * descending and an altitude-ascending part, and each part into segments of at most dh(h) = 1.5 km + 0.3 h of
 * altitude change (so ~12 segments from the ground to the top, ~140 km long near a tangent point). Altitude is
 * monotone on a segment, and its majorant is the sum of each species' exact density maximum over the segment's
 * altitude range (model_density_max: any Bruneton layer pair), so it is tight where the density is.
 * On a ray whose total majorant optical depth is below PT_MIN_EVENTS all its majorants are scaled up so that it
 * gets PT_MIN_EVENTS tentative points on average (still unbiased; it keeps the direct term's variance bounded in
 * the optically thin limit).
 *
 * Geometry: every vertex carries p (planet-centred, km), rho^2 = r^2 - Rb^2 and h; along a ray
 * rho^2_t = rho^2 + t (t + 2 r mu) and h_t = rho^2_t / (r_t + Rb) (docs/model.md, no cancellation); the ground
 * and top roots are the cancellation-free ones of docs/model.md.
 */
#include "reference/pt_internal.h"
#include "reference/ref_internal.h" /* the phase functions */

#include <math.h>
#include <string.h>

#define PT_PI 3.14159265358979323846
#define PT_MAX_SEGS 256       /* segments per ray (a ray needs < 60) */
#define PT_MIN_EVENTS 2.0     /* minimum expected tentative points per ray (majorant scaling) */
#define PT_RR_T 0.02          /* Russian roulette threshold of the ratio-tracking transmittance */
#define PT_MAX_DEPTH 100000   /* safety cap on path length (never reached in practice) */

/* ---------------------------------------------------------------------------------------------------------- */
/* RNG: xoshiro256** seeded by splitmix64, one stream per chunk                                               */

static uint64_t splitmix64(uint64_t *x)
{
    uint64_t z = (*x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

void rng_seed(pt_rng *g, uint64_t seed, uint64_t stream)
{
    uint64_t x = seed;
    uint64_t k = splitmix64(&x) ^ (stream * 0xD1B54A32D192ED03ull);
    for (int i = 0; i < 4; ++i)
        g->s[i] = splitmix64(&k);
}

static uint64_t rotl64(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

static uint64_t rng_next(pt_rng *g)
{
    uint64_t *s = g->s;
    uint64_t r = rotl64(s[1] * 5, 7) * 9;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl64(s[3], 45);
    return r;
}

/* Uniform in [0, 1). */
static double u01(pt_rng *g) { return (double)(rng_next(g) >> 11) * (1.0 / 9007199254740992.0); }

/* Exponential free path of unit rate: -log(1 - u), u in [0, 1). */
static double exp1(pt_rng *g) { return -log(1.0 - u01(g)); }

/* ---------------------------------------------------------------------------------------------------------- */
/* Medium of one channel                                                                                      */

static void pt_medium_at(const pt_ctx *C, double h, double *sR, double *sM, double *st)
{
    const model_atmosphere *a = C->atmo;
    double rm = model_density(&a->mie_density, h);
    *sR = C->bR * model_density(&a->rayleigh_density, h);
    *sM = C->bMs * rm;
    double absorbed = C->bO * model_density(&a->ozone_density, h);
    for (int i = 0; i < a->extra_count; ++i) { /* extra species scatter with the Rayleigh phase */
        double re = model_density(&a->extra[i].density, h);
        *sR += C->bEs[i] * re;
        absorbed += C->bEa[i] * re;
    }
    *st = *sR + C->bMt * rm + absorbed;
}

/* Max of sigma_t over the altitude range [hmin, hmax]: the sum of each species' exact maximum (with a hair of
 * margin for rounding). */
static double majorant(const pt_ctx *C, double hmin, double hmax)
{
    const model_atmosphere *a = C->atmo;
    double m = C->bR * model_density_max(&a->rayleigh_density, hmin, hmax) +
               C->bMt * model_density_max(&a->mie_density, hmin, hmax) +
               C->bO * model_density_max(&a->ozone_density, hmin, hmax);
    for (int i = 0; i < a->extra_count; ++i)
        m += (C->bEs[i] + C->bEa[i]) * model_density_max(&a->extra[i].density, hmin, hmax);
    return m * (1.0 + 1e-9);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Rays                                                                                                       */

void ray_set(const pt_ctx *C, pt_ray *R, const double p[3], double rho2, const double d[3])
{
    if (!(rho2 > 0.0))
        rho2 = 0.0;
    memcpy(R->p, p, sizeof R->p);
    memcpy(R->d, d, sizeof R->d);
    R->rho2 = rho2;
    R->r = sqrt(C->Rb * C->Rb + rho2);
    R->h = rho2 / (R->r + C->Rb);
    R->b = dot3(p, d);
}

/* Altitude at distance t (and rho^2, r there). */
static double ray_alt(const pt_ctx *C, const pt_ray *R, double t, double *rho2, double *r)
{
    double q = R->rho2 + t * (t + 2.0 * R->b);
    if (q < 0.0)
        q = 0.0;
    double rt = sqrt(C->Rb * C->Rb + q);
    if (rho2)
        *rho2 = q;
    if (r)
        *r = rt;
    return q / (rt + C->Rb);
}

/* Length of the ray inside the atmosphere: to the ground (inclusive test, *ground = 1) or to the top. */
static double ray_end(const pt_ctx *C, const pt_ray *R, int *ground)
{
    const double b = R->b;
    if (b < 0.0 && R->rho2 <= b * b) {
        double den = -b + sqrt(b * b - R->rho2);
        *ground = 1;
        return den > 0.0 ? R->rho2 / den : 0.0;
    }
    *ground = 0;
    double c = (C->top - R->h) * (C->Rt + R->r); /* Rt^2 - r^2 */
    if (c < 0.0)
        c = 0.0;
    double s = sqrt(c + b * b), t;
    if (b > 0.0)
        t = c / (b + s);
    else
        t = -b + s;
    return t > 0.0 ? t : 0.0;
}

/* The segment that starts at t: monotone in altitude (it never crosses tlow, the lowest point of the ray) and at
 * most dh of altitude change; returns its end and its altitude range. */
static double seg_next(const pt_ctx *C, const pt_ray *R, double t, double tlow, double tend, double *hmin,
                       double *hmax)
{
    double rt, t1;
    double ht = ray_alt(C, R, t, NULL, &rt);
    double m = R->b + t; /* r_t mu_t */
    if (t < tlow) {
        /* descending by dh: L^2 + 2 m L + dh (2 r_t - dh) = 0, smaller root */
        double dh = (1.5 + 0.3 * ht) / 1.3;
        double c = dh * (2.0 * rt - dh), disc = m * m - c;
        t1 = (dh < rt && disc > 0.0) ? t + c / (-m + sqrt(disc)) : tlow;
        if (t1 > tlow)
            t1 = tlow;
    } else {
        /* ascending by dh: L^2 + 2 m L - dh (2 r_t + dh) = 0 */
        double dh = 1.5 + 0.3 * ht;
        double c = dh * (2.0 * rt + dh);
        t1 = t + c / (m + sqrt(m * m + c));
    }
    if (t1 > tend || !(t1 > t))
        t1 = tend;
    double h1 = ray_alt(C, R, t1, NULL, NULL);
    *hmin = ht < h1 ? ht : h1;
    *hmax = ht < h1 ? h1 : ht;
    return t1;
}

static double ray_tlow(const pt_ray *R, double tend)
{
    double tl = -R->b;
    return tl < 0.0 ? 0.0 : (tl > tend ? tend : tl);
}

/* Ratio-tracking estimate of the transmittance along R to the top (R must not hit the ground). */
static double transmittance_rt(const pt_ctx *C, const pt_ray *R, pt_rng *g)
{
    int ground;
    double tend = ray_end(C, R, &ground);
    if (ground)
        return 0.0;
    double tlow = ray_tlow(R, tend), T = 1.0, t = 0.0;
    while (t < tend) {
        double hmin, hmax;
        double t1 = seg_next(C, R, t, tlow, tend, &hmin, &hmax);
        double maj = majorant(C, hmin, hmax);
        if (maj > 0.0) {
            for (;;) {
                t += exp1(g) / maj;
                if (t >= t1)
                    break;
                double sR, sM, st;
                pt_medium_at(C, ray_alt(C, R, t, NULL, NULL), &sR, &sM, &st);
                T *= 1.0 - st / maj;
                if (T < PT_RR_T) {
                    if (u01(g) * PT_RR_T >= T)
                        return 0.0;
                    T = PT_RR_T;
                }
            }
        }
        t = t1;
    }
    return T;
}

static void dir_around(const double n[3], double cos_t, double phi, double out[3]);

/* A direction toward the sun: uniform over its disc (the cone of angular radius R, by solid angle), so that the
 * planet hides the disc gradually (the penumbra) as it does in nature; the centre when the sun is a point. */
static void sun_sample(const pt_ctx *C, pt_rng *g, double d[3])
{
    if (C->sun_cap > 0.0) {
        double u = u01(g), v = u01(g);
        dir_around(C->sun, 1.0 - u * C->sun_cap, 2.0 * PT_PI * v, d);
    } else {
        memcpy(d, C->sun, 3 * sizeof *d);
    }
}

/* Sun visibility times (an estimate of) the sun transmittance at distance t along R, toward a point of the sun's
 * disc. */
static double sun_term(const pt_ctx *C, const pt_ray *R, double t, pt_rng *g)
{
    double q, rt;
    double h = ray_alt(C, R, t, &q, &rt);
    double p[3] = {R->p[0] + t * R->d[0], R->p[1] + t * R->d[1], R->p[2] + t * R->d[2]};
    double sd[3];
    sun_sample(C, g, sd);
    double bs = dot3(p, sd);
    if (bs < 0.0 && q <= bs * bs)
        return 0.0; /* the planet blocks this point of the sun (inclusive test) */
    pt_ray S;
    memcpy(S.p, p, sizeof p);
    memcpy(S.d, sd, sizeof S.d);
    S.rho2 = q;
    S.r = rt;
    S.h = h;
    S.b = bs;
    return transmittance_rt(C, &S, g);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Direction sampling                                                                                         */

/* Orthonormal basis around unit n (Duff et al. 2017). */
static void onb(const double n[3], double b1[3], double b2[3])
{
    double sign = n[2] >= 0.0 ? 1.0 : -1.0;
    double a = -1.0 / (sign + n[2]);
    double b = n[0] * n[1] * a;
    b1[0] = 1.0 + sign * n[0] * n[0] * a;
    b1[1] = sign * b;
    b1[2] = -sign * n[0];
    b2[0] = b;
    b2[1] = sign + n[1] * n[1] * a;
    b2[2] = -n[1];
}

static void dir_around(const double n[3], double cos_t, double phi, double out[3])
{
    double b1[3], b2[3];
    if (cos_t > 1.0)
        cos_t = 1.0;
    if (cos_t < -1.0)
        cos_t = -1.0;
    double sin_t = sqrt((1.0 - cos_t) * (1.0 + cos_t)), cp = cos(phi), sp = sin(phi), len = 0.0;
    onb(n, b1, b2);
    for (int i = 0; i < 3; ++i) {
        out[i] = sin_t * (cp * b1[i] + sp * b2[i]) + cos_t * n[i];
        len += out[i] * out[i];
    }
    len = sqrt(len);
    for (int i = 0; i < 3; ++i)
        out[i] /= len;
}

/* cos theta with pdf 3/8 (1 + cos^2) on [-1, 1]: the real root of c^3 + 3c = 8u - 4 (Cardano, sign-symmetric). */
static double sample_rayleigh_cos(double u)
{
    double z = 4.0 * u - 2.0, az = fabs(z);
    double A = cbrt(az + sqrt(az * az + 1.0));
    double c = A - 1.0 / A;
    return z < 0.0 ? -c : c;
}

/* cos theta distributed as Henyey-Greenstein(g) about the propagation direction. */
static double sample_hg_cos(double g, double u)
{
    if (fabs(g) < 1e-4)
        return 2.0 * u - 1.0;
    double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    return (1.0 + g * g - s * s) / (2.0 * g);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* One path of one channel                                                                                    */

typedef struct pt_seg {
    double t1, maj;
} pt_seg;

/* Cuts [0, tend] into segments with their majorants; returns the count and the total majorant optical depth. */
static int build_segments(const pt_ctx *C, const pt_ray *R, double tend, pt_seg *segs, double *tau)
{
    double tlow = ray_tlow(R, tend), t = 0.0, hmin, hmax;
    int n = 0;
    *tau = 0.0;
    while (t < tend) {
        double t1;
        if (n < PT_MAX_SEGS - 1) {
            t1 = seg_next(C, R, t, tlow, tend, &hmin, &hmax);
        } else { /* safety: one last segment with the exact range of the rest */
            double tm = tlow > t ? tlow : t;
            double h0 = ray_alt(C, R, t, NULL, NULL), h1 = ray_alt(C, R, tend, NULL, NULL);
            t1 = tend;
            hmin = ray_alt(C, R, tm, NULL, NULL);
            hmax = h0 > h1 ? h0 : h1;
        }
        segs[n].t1 = t1;
        segs[n].maj = majorant(C, hmin, hmax);
        *tau += segs[n].maj * (t1 - t);
        ++n;
        t = t1;
    }
    return n;
}

double trace_path(const pt_ctx *C, const pt_ray *start, pt_rng *g)
{
    pt_ray R = *start;
    pt_seg segs[PT_MAX_SEGS];
    double L = 0.0, w = 1.0;
    for (int depth = 0; depth < PT_MAX_DEPTH; ++depth) {
        const int cont = C->max_bounces <= 0 || depth + 1 < C->max_bounces;
        int ground;
        double tend = ray_end(C, &R, &ground), tau;
        double nu = dot3(R.d, C->sun), pR = phase_rayleigh(nu), pM = phase_hg(C->g, nu);
        int ns = build_segments(C, &R, tend, segs, &tau);
        double scale = (tau > 0.0 && tau < PT_MIN_EVENTS) ? PT_MIN_EVENTS / tau : 1.0;
        double Tr = 1.0, t = 0.0, ty = 0.0, ysR = 0.0, ysM = 0.0, yst = 0.0;
        int nee = 1, found = 0;
        for (int k = 0; k < ns && (nee || (cont && !found)); ++k) {
            const double maj = segs[k].maj * scale, t1 = segs[k].t1;
            if (maj > 0.0) {
                for (;;) {
                    t += exp1(g) / maj;
                    if (t >= t1)
                        break;
                    double sR, sM, st;
                    pt_medium_at(C, ray_alt(C, &R, t, NULL, NULL), &sR, &sM, &st);
                    if (nee) {
                        double f = sR * pR + sM * pM;
                        if (f > 0.0) {
                            double Ts = sun_term(C, &R, t, g);
                            if (Ts > 0.0)
                                L += w * Tr * C->E * f * Ts / maj;
                        }
                        Tr *= 1.0 - st / maj;
                        if (Tr < PT_RR_T) {
                            if (u01(g) * PT_RR_T >= Tr)
                                nee = 0;
                            else
                                Tr = PT_RR_T;
                        }
                    }
                    if (cont && !found && u01(g) * maj < st) {
                        found = 1;
                        ty = t;
                        ysR = sR;
                        ysM = sM;
                        yst = st;
                    }
                    if (!nee && (found || !cont))
                        break;
                }
            }
            t = t1;
        }
        /* Ground: direct term (last term of the ratio-tracking sum). */
        double pg[3] = {0.0, 0.0, 0.0}, ng[3] = {0.0, 0.0, 0.0};
        if (ground && C->albedo > 0.0) {
            double len = 0.0;
            for (int i = 0; i < 3; ++i) {
                pg[i] = R.p[i] + tend * R.d[i];
                len += pg[i] * pg[i];
            }
            len = sqrt(len);
            for (int i = 0; i < 3; ++i) {
                ng[i] = pg[i] / len;
                pg[i] = ng[i] * C->Rb;
            }
            double sd[3];
            sun_sample(C, g, sd);
            double cs = dot3(ng, sd);
            if (nee && cs > 0.0) {
                pt_ray S;
                ray_set(C, &S, pg, 0.0, sd);
                double Ts = transmittance_rt(C, &S, g);
                L += w * Tr * C->albedo / PT_PI * C->E * cs * Ts;
            }
        }
        if (!cont)
            break;
        /* Continuation. */
        double nd[3], np[3];
        if (found) {
            double ss = ysR + ysM;
            if (!(ss > 0.0))
                break;
            w *= ss / yst;
            double cos_t = u01(g) * ss < ysR ? sample_rayleigh_cos(u01(g)) : sample_hg_cos(C->g, u01(g));
            dir_around(R.d, cos_t, 2.0 * PT_PI * u01(g), nd);
            for (int i = 0; i < 3; ++i)
                np[i] = R.p[i] + ty * R.d[i];
            double q = R.rho2 + ty * (ty + 2.0 * R.b);
            ray_set(C, &R, np, q, nd);
        } else if (ground && C->albedo > 0.0) {
            w *= C->albedo;
            double u = u01(g);
            dir_around(ng, sqrt(u), 2.0 * PT_PI * u01(g), nd);
            ray_set(C, &R, pg, 0.0, nd);
        } else {
            break; /* escaped to space (the sun disc is excluded) or absorbed by a black ground */
        }
        if (C->max_bounces <= 0 && depth >= 3 && w < 0.5) {
            double ps = w / 0.5;
            if (u01(g) >= ps)
                break;
            w /= ps;
        }
    }
    return L;
}
