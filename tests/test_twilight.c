/* Sunset and twilight against physics (issue 17): the model (the converged CPU reference, ref_sky_radiance, with the
 * default sun visibility: the penumbra) against the path tracer (all orders, true phase functions, the sun a disc)
 * on a subset of docs/model_error.md's grid: sun +5, 0, -2, -4 degrees; the zenith, the horizon toward the sun and
 * away from it (2 degrees up), from 1 m. The path tracer runs at reduced sample counts; its standard error (3 sigma
 * of the ratio) is the margin added to each bound.
 *
 * Bounds: the targets (sun >= +5: 3 %; 0 .. +5: 5 %; -2: 10 %; -4 .. -6: 20 %), on every row (the model
 * meets them all since the second bounce's moments, docs/model_error.md), and (issue 31) the tighter bound of each row's
 * error on docs/model_error.md (its full run) + 3 sigma of both estimates, so a row that regresses fails long before
 * the targets do; two rows from 10 km too. The lesson's fade is run too, to show
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
    /* Issue 31: docs/model_error.md's row (the documented full run: the model's and the tracer's luminance, the
     * tracer's relative standard error). Its error + 3 sigma is the tighter bound: a 5x regression of a row fails. */
    double page_model, page_pt, page_se;
    double altitude; /* km; 0: 1 m */
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
    double h = r->altitude > 0.0 ? r->altitude : 0.001;
    ref_sky_radiance(pen, h, v, s, ref_quality_converged(), M);
    ref_sky_radiance(fade, h, v, s, ref_quality_converged(), F);
    pt_settings ps = {r->samples, seed, 0.0, 0, 2};
    pt_radiance(pen, h, v, s, &ps, P, se);
    measured m = {lum(M), lum(F), lum(P), 0.0};
    m.pt_se = sqrt(0.2126 * 0.2126 * se[0] * se[0] + 0.7152 * 0.7152 * se[1] * se[1] + 0.0722 * 0.0722 * se[2] * se[2]);
    return m;
}

int main(void)
{
    const row rows[] = {
        {5.0, 0.0, 90.0, "zenith", 30000, 0.03, 0.07245, 0.07259, 0.0006, 0},
        {5.0, 0.0, 2.0, "toward sun", 20000, 0.03, 2.934, 2.956, 0.0007, 0},
        {5.0, 180.0, 2.0, "away from sun", 20000, 0.03, 0.7646, 0.7686, 0.0007, 0},
        {0.0, 0.0, 90.0, "zenith", 30000, 0.05, 0.02507, 0.02511, 0.0005, 0},
        {0.0, 0.0, 2.0, "toward sun", 30000, 0.05, 0.6914, 0.7008, 0.0007, 0},
        {0.0, 180.0, 2.0, "away from sun", 30000, 0.05, 0.1133, 0.1153, 0.0007, 0},
        {-2.0, 0.0, 90.0, "zenith", 40000, 0.10, 0.008378, 0.008422, 0.0008, 0},
        {-2.0, 0.0, 2.0, "toward sun", 30000, 0.10, 0.135, 0.1374, 0.0007, 0},
        {-2.0, 180.0, 2.0, "away from sun", 150000, 0.10, 0.008132, 0.008515, 0.0014, 0},
        {-4.0, 0.0, 90.0, "zenith", 160000, 0.20, 0.001492, 0.001513, 0.0015, 0},
        {-4.0, 0.0, 2.0, "toward sun", 50000, 0.20, 0.04075, 0.0415, 0.0008, 0},
        {-4.0, 180.0, 2.0, "away from sun", 700000, 0.20, 0.001518, 0.001577, 0.0027, 0},
        /* From 10 km (an aircraft), level: the page's rows at sun 0 toward the sun and -2 away from it. */
        {0.0, 0.0, 0.0, "10 km toward", 30000, 0.05, 0.622, 0.6204, 0.0007, 10.0},
        {-2.0, 180.0, 0.0, "10 km away", 60000, 0.10, 0.03126, 0.03162, 0.0012, 10.0},
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
        /* The page's error + 3 sigma of both estimates + the page's 4-digit rounding of each luminance (0.1 %). */
        double page_err = r->page_model / r->page_pt - 1.0;
        double rel_se = sL / Lp;
        double page_bound = fabs(page_err) + 3.0 * sqrt(rel_se * rel_se + r->page_se * r->page_se) + 0.001;
        int ok = fabs(err) <= r->target + margin && fabs(err) <= page_bound;
        printf("sun %+4.0f %-14s penumbra %+6.1f%%  lesson fade %+6.1f%%  (PT stderr %.2f%%, target %2.0f%%, "
               "page %+.2f%% -> bound %.2f%%) %s\n", r->sun_el, r->view, 100 * err, 100 * err_fade, 100 * rel_se,
               100 * r->target, 100 * page_err, 100 * page_bound, ok ? "ok" : "FAIL");
        if (!ok)
            ++failures;
        if (r->sun_el <= 0.0 && !(fabs(err_fade) >= 3.0 * fabs(err))) {
            printf("FAIL: the penumbra does not improve on the fade here (%.1f%% vs %.1f%%)\n", 100 * err,
                   100 * err_fade);
            ++failures;
        }
    }
    const row day[] = {
        {90.0, 0.0, 2.0, "horizon", 1000000, 0.0, 0, 0, 0, 0},
        {90.0, 0.0, 90.0, "zenith", 500000, 0.0, 0, 0, 0, 0},
        {45.0, 90.0, 30.0, "30 up, 90 az", 300000, 0.0, 0, 0, 0, 0},
        {20.0, 90.0, 30.0, "30 up, 90 az", 300000, 0.0, 0, 0, 0, 0},
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
