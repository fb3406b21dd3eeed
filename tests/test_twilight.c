/* Sunset and twilight against physics (issue 17): the model (the converged CPU reference, ref_sky_radiance, with the
 * default sun visibility: the penumbra) against the path tracer (all orders, true phase functions, the sun a disc)
 * on a subset of docs/model_error.md's grid: sun +5, 0, -2, -4 degrees; the zenith, the horizon toward the sun and
 * away from it (2 degrees up), from 1 m. The path tracer runs at reduced sample counts; its standard error (3 sigma
 * of the ratio) is the margin added to each bound.
 *
 * Bounds: the targets (sun >= +5: 3 %; 0 .. +5: 5 %; -2: 10 %; -4 .. -6: 20 %), on every row (the model
 * meets them all since the second bounce's moments, docs/model_error.md). The lesson's fade is run too, to show
 * (and assert) what the penumbra buys: at sun 0 and below, its error is at least 3x the penumbra's.
 *
 * And the "no daytime row may get worse than today": on the daytime rows where the two models come
 * closest (docs/model_error.md: the noon horizon, the noon zenith, 30 degrees up at sun 20 and 45), the penumbra's
 * |error| must not exceed the lesson's by more than 3 sigma of the path tracer's estimate (both are measured
 * against the same estimate, so only its own noise can blur the comparison, and only where the two errors have
 * opposite signs: 0.04-0.12 % here, against margins of 0.4-1.9 %). */
#include "reference/path_tracer.h"

#include <math.h>
#include <stdio.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

static double lum(const double c[3]) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

typedef struct row {
    double sun_el, az, el;
    const char *view;
    long long samples; /* per channel: ~1 % standard error on L_PT */
    double target;     /* the bound, asserted */
} row;

/* One row measured: both models (the converged reference) and the path tracer (seed `seed`) from 1 m; the
 * luminances of the penumbra model, the lesson's fade and the tracer, and the tracer's standard error. */
typedef struct measured { double model, fade, pt, pt_se; } measured;

static measured measure(const model_atmosphere *pen, const model_atmosphere *fade, const row *r,
                        unsigned long long seed)
{
    double v[3], s[3], M[3], F[3], P[3], se[3];
    ref_dir(r->az * DEG, r->el * DEG, v);
    ref_dir(0.0, r->sun_el * DEG, s);
    ref_sky_radiance(pen, 0.001, v, s, ref_quality_converged(), M);
    ref_sky_radiance(fade, 0.001, v, s, ref_quality_converged(), F);
    pt_settings ps = {r->samples, seed, 0.0, 0, 2};
    pt_radiance(pen, 0.001, v, s, &ps, P, se);
    measured m = {lum(M), lum(F), lum(P), 0.0};
    m.pt_se = sqrt(0.2126 * 0.2126 * se[0] * se[0] + 0.7152 * 0.7152 * se[1] * se[1] + 0.0722 * 0.0722 * se[2] * se[2]);
    return m;
}

int main(void)
{
    const row rows[] = {
        {5.0, 0.0, 90.0, "zenith", 30000, 0.03},
        {5.0, 0.0, 2.0, "toward sun", 20000, 0.03},
        {5.0, 180.0, 2.0, "away from sun", 20000, 0.03},
        {0.0, 0.0, 90.0, "zenith", 30000, 0.05},
        {0.0, 0.0, 2.0, "toward sun", 30000, 0.05},
        {0.0, 180.0, 2.0, "away from sun", 30000, 0.05},
        {-2.0, 0.0, 90.0, "zenith", 40000, 0.10},
        {-2.0, 0.0, 2.0, "toward sun", 30000, 0.10},
        {-2.0, 180.0, 2.0, "away from sun", 150000, 0.10},
        {-4.0, 0.0, 90.0, "zenith", 160000, 0.20},
        {-4.0, 0.0, 2.0, "toward sun", 50000, 0.20},
        {-4.0, 180.0, 2.0, "away from sun", 700000, 0.20},
    };
    const int n = (int)(sizeof rows / sizeof rows[0]);
    model_atmosphere pen, fade;
    model_atmosphere_earth(&pen);
    fade = pen;
    fade.sun_visibility = MODEL_SUN_VISIBILITY_LESSON_FADE;
    int failures = 0;
    for (int i = 0; i < n; ++i) {
        const row *r = &rows[i];
        measured m = measure(&pen, &fade, r, 1717ull + 31ull * (unsigned long long)i);
        double Lp = m.pt, Lm = m.model, Lf = m.fade, sL = m.pt_se;
        double err = (Lm - Lp) / Lp, err_fade = (Lf - Lp) / Lp;
        double margin = 3.0 * fabs(Lm / Lp) * sL / Lp; /* 3 sigma of the ratio */
        int ok = fabs(err) <= r->target + margin;
        printf("sun %+4.0f %-14s penumbra %+6.1f%%  lesson fade %+6.1f%%  (PT stderr %.2f%%, target %2.0f%%) %s\n",
               r->sun_el, r->view, 100 * err, 100 * err_fade, 100 * sL / Lp, 100 * r->target, ok ? "ok" : "FAIL");
        if (!ok)
            ++failures;
        if (r->sun_el <= 0.0 && !(fabs(err_fade) >= 3.0 * fabs(err))) {
            printf("FAIL: the penumbra does not improve on the fade here (%.1f%% vs %.1f%%)\n", 100 * err,
                   100 * err_fade);
            ++failures;
        }
    }
    const row day[] = {
        {90.0, 0.0, 2.0, "horizon", 1000000, 0.0},
        {90.0, 0.0, 90.0, "zenith", 500000, 0.0},
        {45.0, 90.0, 30.0, "30 up, 90 az", 300000, 0.0},
        {20.0, 90.0, 30.0, "30 up, 90 az", 300000, 0.0},
    };
    for (int i = 0; i < (int)(sizeof day / sizeof day[0]); ++i) {
        const row *r = &day[i];
        measured m = measure(&pen, &fade, r, 4242ull + 31ull * (unsigned long long)i);
        double Lp = m.pt, sL = m.pt_se;
        double err = (m.model - Lp) / Lp, err_fade = (m.fade - Lp) / Lp, margin = 3.0 * sL / Lp;
        int ok = fabs(err) <= fabs(err_fade) + margin;
        printf("sun %+4.0f %-14s penumbra %+6.2f%%  lesson fade %+6.2f%%  (PT stderr %.3f%%): no worse %s\n", r->sun_el,
               r->view, 100 * err, 100 * err_fade, 100 * sL / Lp, ok ? "ok" : "FAIL");
        if (!ok)
            ++failures;
    }
    if (failures) {
        printf("twilight: %d failure(s)\n", failures);
        return 1;
    }
    printf("twilight: ok\n");
    return 0;
}
