/* tools/model_error.c: the model's error against real physics, as a Markdown table (docs/model_error.md).
 *
 * For sun elevations {90, 45, 20, 5, 2, 0, -2, -4, -6} deg and four views from 1 m altitude — zenith, the horizon
 * toward the sun (pitch 2 deg), the horizon away from it (pitch 2 deg, yaw + 180) and 30 deg up at 90 deg azimuth
 * from the sun —, from 10 km (an aircraft: zenith, the horizon toward and away from the sun, sun +5 .. -6) and
 * from 400 km (orbit: the terminator below, the limb at local sunset toward, away from and across the sun), it
 * prints the model (ref_sky_radiance, converged: the CPU reference of docs/model.md, sun disc excluded; its sun
 * visibility --model penumbra (default) or lesson-fade) next to the Monte Carlo path tracer (pt_radiance: all
 * orders, ground albedo 0, the sun a disc of the same angular radius, no fade) with its standard error, and the
 * model's relative luminance error (L = 0.2126 R + 0.7152 G + 0.0722 B); then a second table that splits that
 * error into the sun visibility's share and the multiple-scattering approximation's.
 *
 * Samples are adaptive: a pilot run, then enough further samples for the luminance's standard error to reach
 * --target (relative, default 0.005) or --max-samples, whichever comes first; pilot and main run are merged.
 *
 *   model_error [--model penumbra|lesson-fade] [--target REL] [--pilot N] [--max-samples N] [--threads T] [--seed S]
 *               [--pt-from FILE]
 *
 * --pt-from FILE takes the path tracer's numbers (RGB, standard errors, samples) from an earlier run's output (its
 * first table, rows in this order) instead of tracing again: the tracer has no part of the model in it, so its
 * numbers do not change when the model does, and a model change is then measured in a minute instead of minutes.
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

/* Single scattering along a view ray from altitude h (inside the atmosphere) by brute-force quadrature (plain 3D
 * geometry, binary earth shadow of the sun's centre), optionally with the model's sun visibility (`vis`: a
 * MODEL_SUN_VISIBILITY_* kind, -1 for none) at each point, its transmittance read toward the model's direction: it
 * splits the model's error into the visibility's share (single scattering with vs without it) and the rest, which
 * is the multiple-scattering approximation (model - SS_vis vs PT - SS). Same scheme as tests/test_path_tracer.c. */
static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void coeffs(const model_atmosphere *a, double h, double sR[3], double sM[3], double st[3])
{
    double rr = model_density(&a->rayleigh_density, h), rm = model_density(&a->mie_density, h);
    double ro = model_density(&a->ozone_density, h);
    for (int c = 0; c < 3; ++c) {
        sR[c] = a->rayleigh_scattering[c] * rr;
        sM[c] = a->mie_scattering[c] * rm;
        st[c] = sR[c] + (a->mie_scattering[c] + a->mie_absorption[c]) * rm + a->ozone_absorption[c] * ro;
    }
}

static double exit_distance(const model_atmosphere *a, const double p[3], const double d[3], int *ground)
{
    double b = dot3(p, d), pp = dot3(p, p);
    double dg = b * b - (pp - a->bottom_radius * a->bottom_radius);
    if (b < 0.0 && dg >= 0.0) {
        *ground = 1;
        return -b - sqrt(dg);
    }
    *ground = 0;
    return -b + sqrt(fmax(0.0, b * b - (pp - a->top_radius * a->top_radius)));
}

static void optical_depth(const model_atmosphere *a, const double p[3], const double d[3], double tend, int n,
                          double tau[3])
{
    double tl = fmin(fmax(-dot3(p, d), 0.0), tend);
    const double len[2] = {tl, tend - tl};
    tau[0] = tau[1] = tau[2] = 0.0;
    for (int side = 0; side < 2; ++side)
        for (int k = 0; k < n && len[side] > 0.0; ++k) {
            double u = (k + 0.5) / n, t = side == 0 ? tl - len[0] * u * u : tl + len[1] * u * u;
            double dt = 2.0 * len[side] * u / n, x[3], sR[3], sM[3], st[3];
            for (int i = 0; i < 3; ++i)
                x[i] = p[i] + t * d[i];
            coeffs(a, sqrt(dot3(x, x)) - a->bottom_radius, sR, sM, st);
            for (int c = 0; c < 3; ++c)
                tau[c] += st[c] * dt;
        }
}

static void single_scattering(const model_atmosphere *a, double h, const double v[3], const double s[3], int vis,
                              double out[3])
{
    const int n_out = 4000, n_in = 200;
    double cam[3] = {0.0, a->bottom_radius + h, 0.0}, tau_v[3] = {0.0, 0.0, 0.0};
    int ground;
    double tend = exit_distance(a, cam, v, &ground), nu = dot3(v, s), g = a->mie_g;
    double pR = 3.0 / (16.0 * PI) * (1.0 + nu * nu);
    double pM = (1.0 - g * g) / (4.0 * PI * pow(1.0 + g * g - 2.0 * g * nu, 1.5));
    out[0] = out[1] = out[2] = 0.0;
    for (int k = 0; k < n_out; ++k) {
        double u = (k + 0.5) / n_out, t = tend * u * u, dt = 2.0 * tend * u / n_out, x[3], sR[3], sM[3], st[3];
        for (int i = 0; i < 3; ++i)
            x[i] = cam[i] + t * v[i];
        coeffs(a, sqrt(dot3(x, x)) - a->bottom_radius, sR, sM, st);
        double Ts[3] = {0.0, 0.0, 0.0}, tau_s[3];
        int gs;
        double ts = exit_distance(a, x, s, &gs);
        if (vis >= 0) {
            /* The model's visibility, its transmittance toward mu_t in the vertical plane of the sun. */
            double r = sqrt(dot3(x, x)), hx = r - a->bottom_radius, up[3], hor[3], st[3], mu_t, hl = 0.0;
            double mus = dot3(x, s) / r;
            for (int i = 0; i < 3; ++i) {
                up[i] = x[i] / r;
                hor[i] = s[i] - mus * up[i];
                hl += hor[i] * hor[i];
            }
            hl = sqrt(hl);
            double f = model_sun_visibility(vis, sqrt(fmax(0.0, hx * (2.0 * a->bottom_radius + hx))), r,
                                            a->bottom_radius, mus, a->sun_angular_radius, &mu_t);
            if (f > 0.0) {
                double sh = sqrt(fmax(0.0, (1.0 - mu_t) * (1.0 + mu_t)));
                for (int i = 0; i < 3; ++i)
                    st[i] = mu_t * up[i] + (hl > 0.0 ? sh * hor[i] / hl : 0.0);
                int gt;
                double tt = exit_distance(a, x, st, &gt);
                optical_depth(a, x, st, tt, n_in, tau_s);
                for (int c = 0; c < 3; ++c)
                    Ts[c] = f * exp(-tau_s[c]);
            }
        } else if (!gs) {
            optical_depth(a, x, s, ts, n_in, tau_s);
            for (int c = 0; c < 3; ++c)
                Ts[c] = exp(-tau_s[c]);
        }
        for (int c = 0; c < 3; ++c) {
            out[c] += exp(-(tau_v[c] + 0.5 * st[c] * dt)) * a->sun_illuminance[c] * (sR[c] * pR + sM[c] * pM) * Ts[c] *
                      dt;
            tau_v[c] += st[c] * dt;
        }
    }
}

/* The path tracer's columns of an earlier run's first table (see --pt-from); returns the rows read, -1 on error. */
static int read_pt(const char *path, int n_rows, double (*P)[3], double (*se)[3], long long *samples)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    char line[2048];
    int n = 0;
    while (n < n_rows && fgets(line, sizeof line, f)) {
        if (strncmp(line, "| ", 2) != 0 || !strstr(line, "(+- ") || !strstr(line, "% |"))
            continue;
        /* fields: sun | view | model RGB | PT RGB (+- stderr) | L model | L PT | error | samples | time */
        char *field[10] = {0};
        int k = 0;
        for (char *c = line; *c && k < 10; ++c)
            if (*c == '|')
                field[k++] = c + 1;
        if (k < 9 || sscanf(field[3], "%lf %lf %lf (+- %lf %lf %lf)", &P[n][0], &P[n][1], &P[n][2], &se[n][0],
                            &se[n][1], &se[n][2]) != 6 || sscanf(field[7], "%lld", &samples[n]) != 1)
            break;
        ++n;
    }
    fclose(f);
    return n;
}

static void usage(void)
{
    fprintf(stderr, "usage: model_error [--model penumbra|lesson-fade] [--target REL] [--pilot N] [--max-samples N] "
                    "[--threads T] [--seed S]\n");
}

#include "model_rows.h"

int main(int argc, char **argv)
{
    double target = 0.005;
    long long pilot = 20000, max_samples = 20000000;
    int threads = 2, model = MODEL_SUN_VISIBILITY_PENUMBRA;
    unsigned long long seed = 2020;
    const char *pt_from = NULL;
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
        else if (!strcmp(argv[i], "--pt-from"))
            pt_from = argv[++i];
        else if (!strcmp(argv[i], "--seed"))
            seed = strtoull(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--model")) {
            ++i;
            if (!strcmp(argv[i], "penumbra"))
                model = MODEL_SUN_VISIBILITY_PENUMBRA;
            else if (!strcmp(argv[i], "lesson-fade"))
                model = MODEL_SUN_VISIBILITY_LESSON_FADE;
            else {
                usage();
                return 2;
            }
        } else {
            usage();
            return 2;
        }
    }
    if (!(target > 0.0) || pilot < 2 || max_samples < pilot || threads < 1) {
        usage();
        return 2;
    }

    row rows[MAX_ROWS];
    const int n_rows = build_rows(rows);
    model_atmosphere a;
    model_atmosphere_earth(&a);
    a.sun_visibility = model;
    ref_quality q = ref_quality_converged();
    static double pt_P[MAX_ROWS][3], pt_se[MAX_ROWS][3];
    static long long pt_n[MAX_ROWS];
    if (pt_from && read_pt(pt_from, n_rows, pt_P, pt_se, pt_n) != n_rows) {
        fprintf(stderr, "model_error: --pt-from %s: expected the %d rows of an earlier run's first table\n", pt_from,
                n_rows);
        return 2;
    }
    double t_start = now_s();

    printf("Model: sun visibility %s (sun angular radius %.3f deg). Model = ref_sky_radiance (converged: view_steps "
           "%d, sun_steps %d, ms %dx%d dirs, %d steps); PT = pt_radiance (all orders, ground albedo 0, the sun a disc), "
           "+- = 1 standard error; luminance L = 0.2126 R + 0.7152 G + 0.0722 B; error = (L_model - L_PT) / L_PT.\n"
           "Adaptive samples: pilot %lld, target relative stderr of L_PT %.3g, cap %lld; %d threads, seed %llu%s%s.\n\n",
           model == MODEL_SUN_VISIBILITY_PENUMBRA ? "penumbra" : "lesson-fade", a.sun_angular_radius / DEG,
           q.view_steps, q.sun_steps, q.ms_sqrt_dirs, q.ms_sqrt_dirs, q.ms_steps, pilot, target, max_samples, threads,
           seed, pt_from ? "; PT columns from " : "", pt_from ? pt_from : "");
    printf("| sun | view | model RGB | PT RGB (+- stderr) | L model | L PT (+- stderr) | model error | samples | time |\n");
    printf("|---:|---|---|---|---:|---:|---:|---:|---:|\n");
    fflush(stdout);

    double worst_err = 0.0, Lm_all[MAX_ROWS], Lp_all[MAX_ROWS];
    for (int i = 0; i < n_rows; ++i) {
        const row *w = &rows[i];
        double v[3], s[3], M[3], P[3], se[3];
        ref_dir(w->az * DEG, w->el * DEG, v);
        ref_dir(0.0, w->sun_el * DEG, s);
        double t0 = now_s();
        ref_sky_radiance(&a, w->altitude, v, s, q, M);

        long long n = pilot;
        if (pt_from) {
            for (int c = 0; c < 3; ++c)
                P[c] = pt_P[i][c], se[c] = pt_se[i][c];
            n = pt_n[i];
            goto measured;
        }
        /* pilot (the seeds of the 1 m rows are those of the earlier 36-row table) */
        unsigned long long row_seed = seed + (i < 36 ? 1000ull * (i / 4) + i % 4 : 100000ull + 1000ull * i);
        pt_settings ps = {pilot, row_seed, 0.0, 0, threads};
        pt_radiance(&a, w->altitude, v, s, &ps, P, se);
        double Lp = lum(P), rel = Lp > 0.0 ? lum_se(se) / Lp : 0.0;
        if (rel > target) {
            double want = (double)pilot * (rel / target) * (rel / target) * 1.1;
            long long more = (long long)fmin(want, (double)max_samples) - pilot;
            if (more > 0) {
                double P2[3], se2[3];
                pt_settings ps2 = {more, row_seed + 500000ull, 0.0, 0, threads};
                pt_radiance(&a, w->altitude, v, s, &ps2, P2, se2);
                for (int c = 0; c < 3; ++c) {
                    double w1 = (double)pilot / (pilot + more), w2 = (double)more / (pilot + more);
                    P[c] = w1 * P[c] + w2 * P2[c];
                    se[c] = sqrt(w1 * w1 * se[c] * se[c] + w2 * w2 * se2[c] * se2[c]);
                }
                n += more;
            }
        }
    measured:;
        double dt = now_s() - t0;
        double Lm = lum(M);
        Lp = lum(P);
        double sL = lum_se(se);
        double err = Lp > 0.0 ? (Lm - Lp) / Lp : 0.0, err_se = Lp > 0.0 ? fabs(Lm / Lp) * sL / Lp : 0.0;
        Lm_all[i] = Lm;
        Lp_all[i] = Lp;
        if (fabs(err) > fabs(worst_err))
            worst_err = err;
        printf("| %+.0f | %s | %.4g %.4g %.4g | %.4g %.4g %.4g (+- %.2g %.2g %.2g) | %.4g | %.4g +- %.2g (%.2f%%) "
               "| %+.1f%% +- %.1f%% | %lld | %.1f s |\n",
               w->sun_el, w->name, M[0], M[1], M[2], P[0], P[1], P[2], se[0], se[1], se[2], Lm, Lp, sL,
               Lp > 0.0 ? 100.0 * sL / Lp : 0.0, 100.0 * err, 100.0 * err_se, n, dt);
        fflush(stdout);
    }
    printf("\nWorst model luminance error: %+.1f%%.\n\n", 100.0 * worst_err);

    /* Decomposition of the error (luminances; shares relative to L_PT), cameras inside the atmosphere. */
    printf("Where the error comes from (luminance): SS = single scattering by quadrature (binary shadow of the sun's "
           "centre), SS vis = the same with the model's sun visibility; MS = everything else: PT - SS (truth) and "
           "model - SS vis (the model's multiple-scattering term, Psi). The two shares add up to the model error.\n\n");
    printf("| sun | view | SS | SS vis | MS truth | MS model | visibility share | MS share | model error |\n");
    printf("|---:|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int i = 0; i < n_rows; ++i) {
        const row *w = &rows[i];
        if (w->altitude >= a.top_radius - a.bottom_radius)
            continue;
        double v[3], s[3], ss_rgb[3], ssv_rgb[3];
        ref_dir(w->az * DEG, w->el * DEG, v);
        ref_dir(0.0, w->sun_el * DEG, s);
        single_scattering(&a, w->altitude, v, s, -1, ss_rgb);
        single_scattering(&a, w->altitude, v, s, model, ssv_rgb);
        double Lp = Lp_all[i], Lm = Lm_all[i], ss = lum(ss_rgb), ssv = lum(ssv_rgb);
        double mst = Lp - ss, msm = Lm - ssv, inv = Lp > 0.0 ? 100.0 / Lp : 0.0;
        printf("| %+.0f | %s | %.4g | %.4g | %.4g | %.4g | %+.1f%% | %+.1f%% | %+.1f%% |\n", w->sun_el, w->name, ss,
               ssv, mst, msm, (ssv - ss) * inv, (msm - mst) * inv, (Lm - Lp) * inv);
    }
    printf("\nTotal runtime %.0f s.\n", now_s() - t_start);
    return 0;
}
