/* Ray/sphere geometry of the reference in cancellation-free form (docs/model.md "Numerics"): the ground hit, where
 * a ray crosses the earth's shadow and the kinks of the horizon fade, and the graded steps along a ray. The
 * one-line helpers (distance to the top, a point along a ray, sun visibility) are inline in ref_internal.h. */
#include "reference/ref_internal.h"

#include <math.h>

int hit_ground(const model_atmosphere *a, double h, double mu, double *t)
{
    if (!(mu < 0.0))
        return 0;
    double r = a->bottom_radius + h;
    double p2 = rho2_of(a, h);
    double rm2 = r * r * mu * mu;
    if (p2 > rm2)
        return 0;
    double den = -r * mu + sqrt(rm2 - p2);
    *t = den > 0.0 ? p2 / den : 0.0;
    return 1;
}

/* Distances along a ray (from (h, mu), sun at mu_s, nu = dot(ray, sun)) where it crosses the boundary of the earth's
 * shadow, i.e. where the inclusive ground test toward the sun flips. With p(t) the point, the shadow is
 * p.s < 0 and |p|^2 - (p.s)^2 <= Rb^2, i.e. (1 - nu^2) t^2 + 2 r (mu - mu_s nu) t + (rho^2 - r^2 mu_s^2) <= 0
 * (rho^2 = r^2 - Rb^2, no cancellation) on the anti-sun side. Returns the number of crossings in (0, tend). */
static int shadow_crossings(const model_atmosphere *a, double h, double mu, double mus, double nu, double tend,
                            double out[2])
{
    double r = a->bottom_radius + h;
    double A = (1.0 - nu) * (1.0 + nu), B = r * (mu - mus * nu), C = rho2_of(a, h) - r * r * mus * mus;
    double roots[2];
    int n = 0, k = 0;
    if (A > 1e-12) {
        double disc = B * B - A * C;
        if (disc <= 0.0)
            return 0;
        double q = -(B + (B >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
        roots[n++] = q / A;
        if (q != 0.0)
            roots[n++] = C / q;
    } else if (B != 0.0) {
        roots[n++] = -C / (2.0 * B);
    }
    for (int i = 0; i < n; ++i) {
        double t = roots[i];
        if (t > 0.0 && t < tend && r * mus + t * nu < 0.0)
            out[k++] = t;
    }
    if (k == 2 && out[0] > out[1]) {
        double tmp = out[0];
        out[0] = out[1];
        out[1] = tmp;
    }
    return k;
}

/* Distances along a ray where mu_s at the point, (r mu_s + t nu) / r_t, equals c: (r mu_s + t nu)^2 =
 * c^2 (r^2 + 2 r mu t + t^2) on the side where r mu_s + t nu has the sign of c. Appends those in (0, tend). */
static int mus_crossings(const model_atmosphere *a, double h, double mu, double mus, double nu, double tend, double c,
                         double *out)
{
    double r = a->bottom_radius + h;
    double A = (nu - c) * (nu + c), B = r * (mus * nu - c * c * mu), C = r * r * (mus - c) * (mus + c);
    double roots[2];
    int n = 0, k = 0;
    if (fabs(A) > 1e-12) {
        double disc = B * B - A * C;
        if (disc < 0.0)
            return 0;
        double q = -(B + (B >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
        roots[n++] = q / A;
        if (q != 0.0)
            roots[n++] = C / q;
    } else if (B != 0.0) {
        roots[n++] = -C / (2.0 * B);
    }
    for (int i = 0; i < n; ++i) {
        double t = roots[i];
        if (t > 0.0 && t < tend && (r * mus + t * nu) * c > 0.0)
            out[k++] = t;
    }
    return k;
}

int ray_cuts(const model_atmosphere *a, double h, double mu, double mus, double nu, double tend, double *cuts)
{
    if (a->sun_visibility != MODEL_SUN_VISIBILITY_LESSON_FADE)
        return 0;
    int n = shadow_crossings(a, h, mu, mus, nu, tend, cuts);
    n += mus_crossings(a, h, mu, mus, nu, tend, -0.05, cuts + n);
    n += mus_crossings(a, h, mu, mus, nu, tend, 0.05, cuts + n);
    for (int i = 1; i < n; ++i) /* insertion sort */
        for (int j = i; j > 0 && cuts[j - 1] > cuts[j]; --j) {
            double tmp = cuts[j];
            cuts[j] = cuts[j - 1];
            cuts[j - 1] = tmp;
        }
    return n;
}

/* The grading of ray_step: quadratic in a uniform parameter. */
static double grade(double u) { return u * u; }

void ray_step(const model_atmosphere *a, double h, double mu, double tend, int ground, int graded, int steps,
              int k, double *t, double *dt)
{
    double t0, t1;
    if (!graded || steps < 2) {
        t0 = tend * k / steps;
        t1 = tend * (k + 1) / steps;
    } else if (mu >= 0.0) {
        t0 = tend * grade((double)k / steps);
        t1 = tend * grade((double)(k + 1) / steps);
    } else if (ground) {
        t0 = tend * (1.0 - grade((double)(steps - k) / steps));
        t1 = tend * (1.0 - grade((double)(steps - k - 1) / steps));
    } else {
        double ts = -(a->bottom_radius + h) * mu; /* tangent point */
        if (ts > tend)
            ts = tend;
        int n1 = (int)floor(steps * (ts / tend) + 0.5);
        if (n1 < 1)
            n1 = 1;
        if (n1 > steps - 1)
            n1 = steps - 1;
        if (k < n1) {
            t0 = ts * (1.0 - grade((double)(n1 - k) / n1));
            t1 = ts * (1.0 - grade((double)(n1 - k - 1) / n1));
        } else {
            int n2 = steps - n1;
            t0 = ts + (tend - ts) * grade((double)(k - n1) / n2);
            t1 = ts + (tend - ts) * grade((double)(k - n1 + 1) / n2);
        }
    }
    *t = 0.5 * (t0 + t1);
    *dt = t1 - t0;
}
