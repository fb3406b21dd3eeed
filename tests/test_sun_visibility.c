/* The penumbra's geometry (src/model/sun_visibility.c) against an independent computation: the solid-angle fraction
 * of the sun's cone whose rays miss the planet, integrated numerically ring by ring on the sphere. A ray from a point
 * at radius r with zenith cosine w hits the planet iff w <= -rho / r (the reference's inclusive ground test); on the
 * ring at angle psi from the sun's centre, w = cos(psi) mu_s + sin(psi) cos(omega) sqrt(1 - mu_s^2), so the visible
 * part of the ring is the arc cos(omega) > q, of length 2 acos(q). The rings are summed with the midpoint rule in
 * psi, weighted by sin(psi). Nothing here uses the formula under test (the lens of a circle and the horizon's
 * curvature): only the ray/sphere test.
 *
 * Altitudes 0, 1 mm, 10 km, 400 km, 36 000 km; the disc fully above, fully below, grazing (its edge on the horizon
 * from either side) and cut anywhere between; the default sun radius and larger ones. Then robustness: no NaN and
 * values in [0, 1] over extreme inputs, monotone in the sun's height, and the lesson's fade unchanged. */
#include "model/sun_visibility.h"

#include <math.h>
#include <stdio.h>

#define PI 3.14159265358979323846
static const double RB = 6360.0;

static int failures;

/* Fraction of the cone of angular radius R around a sun at zenith cosine mu_s that misses the planet. */
static double fraction_by_rings(double h, double mu_s, double R, int rings)
{
    double r = RB + h, rho = sqrt(h * (2.0 * RB + h));
    double horizon = -rho / r, ms = sqrt((1.0 - mu_s) * (1.0 + mu_s));
    double sum = 0.0, norm = 0.0;
    for (int i = 0; i < rings; ++i) {
        double psi = R * (i + 0.5) / rings, w = sin(psi);
        double q;
        if (ms * w > 0.0)
            q = (horizon - cos(psi) * mu_s) / (ms * w);
        else
            q = cos(psi) * mu_s > horizon ? -2.0 : 2.0;
        double arc = q <= -1.0 ? 1.0 : (q >= 1.0 ? 0.0 : acos(q) / PI);
        sum += w * arc;
        norm += w;
    }
    return sum / norm;
}

static void check(const char *what, double got, double want, double tol)
{
    if (!(fabs(got - want) <= tol)) {
        printf("FAIL %s: %.9f, expected %.9f (tolerance %.1e)\n", what, got, want, tol);
        ++failures;
    }
}

int main(void)
{
    const double altitudes[] = {0.0, 1e-6, 10.0, 400.0, 36000.0};
    const double radii_deg[] = {0.265, 1.0, 3.0};
    /* The sun centre's height above the horizon in units of R: fully below, grazing from below, cut, half, grazing
     * from above, fully above. */
    const double heights[] = {-3.0, -1.2, -1.0, -0.999, -0.9, -0.5, -0.2, 0.0, 0.1, 0.5, 0.9, 0.999, 1.0, 1.2, 3.0};
    double worst[3] = {0.0, 0.0, 0.0};
    for (unsigned ia = 0; ia < sizeof altitudes / sizeof *altitudes; ++ia)
        for (unsigned ir = 0; ir < sizeof radii_deg / sizeof *radii_deg; ++ir)
            for (unsigned k = 0; k < sizeof heights / sizeof *heights; ++k) {
                double h = altitudes[ia], R = radii_deg[ir] * PI / 180.0;
                double r = RB + h, rho = sqrt(h * (2.0 * RB + h));
                double elevation = -asin(rho / r) + heights[k] * R; /* the horizon dips by asin(rho / r) */
                double mu_s = sin(elevation);
                double want = fraction_by_rings(h, mu_s, R, 400000);
                double got = model_sun_visible_fraction(rho, RB, mu_s, R);
                /* The lens is the plane picture of the spherical overlap: its error is O(R^2) relative (measured:
                 * 3.8e-7 at the default radius, 5.7e-6 at 1 degree, 6.2e-5 at 3); the ring sum converges to ~1e-8. */
                double tol = 1e-6 + 0.03 * R * R;
                char what[160];
                snprintf(what, sizeof what, "fraction h=%g km R=%g deg height=%g R", h, radii_deg[ir], heights[k]);
                check(what, got, want, tol);
                if (fabs(got - want) > worst[ir])
                    worst[ir] = fabs(got - want);
                double mu_t;
                double v = model_sun_visibility(MODEL_SUN_VISIBILITY_PENUMBRA, rho, r, RB, mu_s, R, &mu_t);
                check("model_sun_visibility == fraction", v, got, 1e-15);
                /* The transmittance direction lies above the horizon whenever some of the sun is visible. */
                if (v > 1e-6 && !(mu_t > -rho / r)) { /* (a sliver of 1e-6 or less sits on the horizon) */
                    printf("FAIL transmittance direction below the horizon: h=%g mu_t=%.9g horizon=%.9g\n", h, mu_t,
                           -rho / r);
                    ++failures;
                }
                if (heights[k] >= 1.0 && mu_t != mu_s) {
                    printf("FAIL the whole disc is up but mu_t != mu_s at h=%g\n", h);
                    ++failures;
                }
            }
    for (unsigned ir = 0; ir < sizeof radii_deg / sizeof *radii_deg; ++ir)
        printf("R = %g deg: worst |penumbra - ring integral| = %.2e\n", radii_deg[ir], worst[ir]);

    /* Exact ends: fully below is 0 and fully above 1, exactly (no residue of a cancellation). */
    const double R0 = MODEL_SUN_ANGULAR_RADIUS_DEFAULT;
    for (unsigned ia = 0; ia < sizeof altitudes / sizeof *altitudes; ++ia) {
        double h = altitudes[ia], r = RB + h, rho = sqrt(h * (2.0 * RB + h));
        double dip = asin(rho / r);
        check("fully above is 1", model_sun_visible_fraction(rho, RB, sin(-dip + 1.01 * R0), R0), 1.0, 0.0);
        check("fully below is 0", model_sun_visible_fraction(rho, RB, sin(-dip - 1.01 * R0), R0), 0.0, 0.0);
        check("centre on the horizon is ~1/2", model_sun_visible_fraction(rho, RB, sin(-dip), R0),
              fraction_by_rings(h, sin(-dip), R0, 400000), 2e-6);
    }

    /* Robustness: finite, in [0, 1], monotone in the sun's elevation, over altitudes from 0 to 1e6 km, mu_s over
     * [-1, 1] (including the exact ends) and radii 0 (a point sun) to 10 degrees. */
    const double alt_all[] = {0.0, 1e-9, 1e-6, 1e-3, 1.0, 10.0, 100.0, 400.0, 36000.0, 1e6};
    const double rad_all[] = {0.0, 1e-4, R0, 0.01, 0.1745};
    for (unsigned ia = 0; ia < sizeof alt_all / sizeof *alt_all; ++ia)
        for (unsigned ir = 0; ir < sizeof rad_all / sizeof *rad_all; ++ir) {
            double h = alt_all[ia], r = RB + h, rho = sqrt(h * (2.0 * RB + h)), prev = -1.0;
            for (int i = 0; i <= 20000; ++i) {
                double mu_s = -1.0 + 2.0 * i / 20000.0, mu_t;
                double f = model_sun_visibility(MODEL_SUN_VISIBILITY_PENUMBRA, rho, r, RB, mu_s, rad_all[ir], &mu_t);
                if (!(f >= 0.0 && f <= 1.0) || !isfinite(mu_t) || f < prev - 1e-12) {
                    printf("FAIL robustness h=%g R=%g mu_s=%.6f: f=%g (previous %g) mu_t=%g\n", h, rad_all[ir], mu_s,
                           f, prev, mu_t);
                    ++failures;
                    break;
                }
                prev = f;
            }
            if (prev != 1.0) {
                printf("FAIL sun at the zenith not fully visible: h=%g R=%g f=%g\n", h, rad_all[ir], prev);
                ++failures;
            }
        }
    /* A point sun is the inclusive binary shadow. */
    check("point sun above", model_sun_visible_fraction(0.0, RB, 1e-12, 0.0), 1.0, 0.0);
    check("point sun on the horizon", model_sun_visible_fraction(0.0, RB, 0.0, 0.0), 0.0, 0.0);

    /* The lesson's model: binary shadow times saturate(10 mu_s + 0.5), the transmittance at mu_s. */
    {
        double h = 10.0, r = RB + h, rho = sqrt(h * (2.0 * RB + h)), mu_t;
        check("fade at mu_s = 0", model_sun_visibility(MODEL_SUN_VISIBILITY_LESSON_FADE, rho, r, RB, 0.0, R0, &mu_t),
              0.5, 0.0);
        check("fade at mu_s = 0.03", model_sun_visibility(MODEL_SUN_VISIBILITY_LESSON_FADE, rho, r, RB, 0.03, R0, &mu_t),
              0.8, 1e-15);
        check("fade shadow", model_sun_visibility(MODEL_SUN_VISIBILITY_LESSON_FADE, rho, r, RB, -0.06, R0, &mu_t), 0.0,
              0.0);
        check("fade transmittance direction", mu_t, -0.06, 0.0);
    }

    if (failures) {
        printf("%d failure(s)\n", failures);
        return 1;
    }
    printf("sun_visibility: all checks passed\n");
    return 0;
}
