/* tools/model_error.c: the model's error against real physics, as a Markdown table (docs/model_error.md).
 *
 * For sun elevations {90, 45, 20, 5, 2, 0, -2, -4, -6} deg and four views from 1 m altitude — zenith, the horizon
 * toward the sun (pitch 2 deg), the horizon away from it (pitch 2 deg, yaw + 180) and 30 deg up at 90 deg azimuth
 * from the sun — it prints the model (ref_sky_radiance, converged: the CPU reference of docs/model.md, sun disc
 * excluded) next to the Monte Carlo path tracer (pt_radiance: all orders, ground albedo 0, no horizon fade) with
 * its standard error, and the model's relative luminance error (L = 0.2126 R + 0.7152 G + 0.0722 B).
 *
 * Samples are adaptive: a pilot run, then enough further samples for the luminance's standard error to reach
 * --target (relative, default 0.005) or --max-samples, whichever comes first; pilot and main run are merged.
 *
 *   model_error [--target REL] [--pilot N] [--max-samples N] [--threads T] [--seed S]
 */
#include "reference/path_tracer.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static double lum(const double c[3]) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

static double lum_se(const double s[3])
{
    return sqrt(0.2126 * 0.2126 * s[0] * s[0] + 0.7152 * 0.7152 * s[1] * s[1] + 0.0722 * 0.0722 * s[2] * s[2]);
}

static void usage(void)
{
    fprintf(stderr, "usage: model_error [--target REL] [--pilot N] [--max-samples N] [--threads T] [--seed S]\n");
}

int main(int argc, char **argv)
{
    double target = 0.005;
    long long pilot = 20000, max_samples = 20000000;
    int threads = 2;
    unsigned long long seed = 2020;
    for (int i = 1; i < argc; ++i) {
        if (i + 1 >= argc) {
            usage();
            return 2;
        }
        if (!strcmp(argv[i], "--target"))
            target = atof(argv[++i]);
        else if (!strcmp(argv[i], "--pilot"))
            pilot = atoll(argv[++i]);
        else if (!strcmp(argv[i], "--max-samples"))
            max_samples = atoll(argv[++i]);
        else if (!strcmp(argv[i], "--threads"))
            threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--seed"))
            seed = strtoull(argv[++i], NULL, 10);
        else {
            usage();
            return 2;
        }
    }
    if (!(target > 0.0) || pilot < 2 || max_samples < pilot || threads < 1) {
        usage();
        return 2;
    }

    static const double sun_els[] = {90.0, 45.0, 20.0, 5.0, 2.0, 0.0, -2.0, -4.0, -6.0};
    static const struct {
        const char *name;
        double az, el;
    } views[] = {
        {"zenith", 0.0, 90.0},
        {"toward sun, 2 deg up", 0.0, 2.0},
        {"away from sun, 2 deg up", 180.0, 2.0},
        {"30 deg up, 90 deg az", 90.0, 30.0},
    };
    const int n_sun = (int)(sizeof sun_els / sizeof sun_els[0]), n_view = (int)(sizeof views / sizeof views[0]);
    const double altitude = 0.001;

    ref_atmosphere a;
    ref_atmosphere_earth(&a);
    ref_quality q = ref_quality_converged();
    double t_start = now_s();

    printf("Camera altitude 1 m; model = ref_sky_radiance (converged: view_steps %d, sun_steps %d, ms %dx%d dirs, "
           "%d steps); PT = pt_radiance (all orders, ground albedo 0), +- = 1 standard error; luminance "
           "L = 0.2126 R + 0.7152 G + 0.0722 B; error = (L_model - L_PT) / L_PT.\n"
           "Adaptive samples: pilot %lld, target relative stderr of L_PT %.3g, cap %lld; %d threads, seed %llu.\n\n",
           q.view_steps, q.sun_steps, q.ms_sqrt_dirs, q.ms_sqrt_dirs, q.ms_steps, pilot, target, max_samples,
           threads, seed);
    printf("| sun | view | model RGB | PT RGB (+- stderr) | L model | L PT (+- stderr) | model error | samples | time |\n");
    printf("|---:|---|---|---|---:|---:|---:|---:|---:|\n");
    fflush(stdout);

    double worst_err = 0.0;
    for (int i = 0; i < n_sun; ++i) {
        for (int j = 0; j < n_view; ++j) {
            double v[3], s[3], M[3], P[3], se[3];
            ref_dir(views[j].az * DEG, views[j].el * DEG, v);
            ref_dir(0.0, sun_els[i] * DEG, s);
            double t0 = now_s();
            ref_sky_radiance(&a, altitude, v, s, q, M);

            /* pilot */
            pt_settings ps = {pilot, seed + 1000ull * i + j, 0.0, 0, threads};
            pt_radiance(&a, altitude, v, s, &ps, P, se);
            long long n = pilot;
            double Lp = lum(P), rel = Lp > 0.0 ? lum_se(se) / Lp : 0.0;
            if (rel > target) {
                double want = (double)pilot * (rel / target) * (rel / target) * 1.1;
                long long more = (long long)fmin(want, (double)max_samples) - pilot;
                if (more > 0) {
                    double P2[3], se2[3];
                    pt_settings ps2 = {more, seed + 1000ull * i + j + 500000ull, 0.0, 0, threads};
                    pt_radiance(&a, altitude, v, s, &ps2, P2, se2);
                    for (int c = 0; c < 3; ++c) {
                        double w1 = (double)pilot / (pilot + more), w2 = (double)more / (pilot + more);
                        P[c] = w1 * P[c] + w2 * P2[c];
                        se[c] = sqrt(w1 * w1 * se[c] * se[c] + w2 * w2 * se2[c] * se2[c]);
                    }
                    n += more;
                }
            }
            double dt = now_s() - t0;
            double Lm = lum(M);
            Lp = lum(P);
            double sL = lum_se(se);
            double err = Lp > 0.0 ? (Lm - Lp) / Lp : 0.0, err_se = Lp > 0.0 ? fabs(Lm / Lp) * sL / Lp : 0.0;
            if (fabs(err) > fabs(worst_err))
                worst_err = err;
            printf("| %+.0f | %s | %.4g %.4g %.4g | %.4g %.4g %.4g (+- %.2g %.2g %.2g) | %.4g | %.4g +- %.2g (%.2f%%) "
                   "| %+.1f%% +- %.1f%% | %lld | %.1f s |\n",
                   sun_els[i], views[j].name, M[0], M[1], M[2], P[0], P[1], P[2], se[0], se[1], se[2], Lm, Lp, sL,
                   Lp > 0.0 ? 100.0 * sL / Lp : 0.0, 100.0 * err, 100.0 * err_se, n, dt);
            fflush(stdout);
        }
    }
    printf("\nWorst model luminance error: %+.1f%%. Total runtime %.0f s.\n", 100.0 * worst_err, now_s() - t_start);
    return 0;
}
