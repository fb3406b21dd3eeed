/* The table behind ref_sky_radiance's Psi: the Psi table itself and the small cache of Psi tables. It is filled by
 * multiscatter.c's quadrature, which reads the sun transmittance table (sun_table.c): the calls go one way,
 * psi_table -> multiscatter -> sun_table (tests/layering_test.sh checks that no call circle returns). */
#include "reference/ref_internal.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Rows: h = 0.01 + (top - 0.01) y^2, y uniform (the 10 m clamp is the first row).
 * Columns: three segments in mu_s that meet at the kinks of the horizon fade, -0.05 and +0.05 (nodes on both, no
 * interpolation stencil crosses them): [-1, -0.05] with nodes crowded toward -0.05 (the twilight tail, where Psi
 * falls by ~e every 0.01), [-0.05, 0.05] with cosine spacing (crowded toward both kinks, where log Psi bends
 * fastest), [0.05, 1] crowded toward 0.05.
 * Values: log(Psi) (floored at 1e-300), bicubic Catmull-Rom within a segment, the result clamped to the range of
 * its 16 taps so that the steep tail cannot overshoot.
 * Filled by the converged quadrature (ref_multiscatter_converged's, twilight columns with twice the steps) with the
 * nested transmittance read from the sun table.
 * Error it adds to the radiance (table vs a 56 x (96 + 61 + 80) table, 22 rays, converged counts): <= 4e-5 in
 * daylight, <= 2e-4 for the sun down to -6 deg, 8e-4 at -10 deg (radiance 1e-7 of noon there). */
#ifndef PSI_ROWS
#define PSI_ROWS 24
#endif
#ifndef PSI_SEG0
#define PSI_SEG0 40 /* [-1, -0.05]:  mu_s = -1 + 0.95 (1 - (1 - u)^2) */
#endif
#ifndef PSI_SEG1
#define PSI_SEG1 31 /* [-0.05, 0.05]: mu_s = -0.05 + 0.05 (1 - cos(pi u)) */
#endif
#ifndef PSI_SEG2
#define PSI_SEG2 32 /* [0.05, 1]:    mu_s = 0.05 + 0.95 u^2 */
#endif
#define PSI_COLS (PSI_SEG0 + PSI_SEG1 + PSI_SEG2)

struct psi_table {
    double v[PSI_ROWS][PSI_COLS][3 + MS_MOMENTS]; /* segments side by side; the shared end nodes are stored twice;
                                                     [3..]: the second bounce's moments (multiscatter_row), 0 for
                                                     the lesson's model */
};

static const int psi_seg_n[3] = {PSI_SEG0, PSI_SEG1, PSI_SEG2};
static const int psi_seg_off[3] = {0, PSI_SEG0, PSI_SEG0 + PSI_SEG1};

static double psi_seg_mus(int seg, double u)
{
    switch (seg) {
    case 0:
        return -1.0 + 0.95 * (1.0 - (1.0 - u) * (1.0 - u));
    case 1:
        return -0.05 + 0.05 * (1.0 - cos(REF_PI * u));
    default:
        return 0.05 + 0.95 * u * u;
    }
}

/* mu_s -> (segment, u) */
static int psi_seg_u(double mus, double *u)
{
    if (mus <= -0.05) {
        *u = 1.0 - sqrt(clampd((-0.05 - mus) / 0.95, 0.0, 1.0));
        return 0;
    }
    if (mus <= 0.05) {
        *u = acos(clampd(1.0 - (mus + 0.05) / 0.05, -1.0, 1.0)) / REF_PI;
        return 1;
    }
    *u = sqrt(clampd((mus - 0.05) / 0.95, 0.0, 1.0));
    return 2;
}

static double psi_row_h(const model_atmosphere *a, int j)
{
    double y = (double)j / (PSI_ROWS - 1);
    return j == PSI_ROWS - 1 ? atmo_height(a) : 0.01 + (atmo_height(a) - 0.01) * y * y;
}

/* The sun table of the last atmosphere a Psi table was built for (Psi tables of other counts reuse it). */
static sun_table *g_sun_table;
static model_atmosphere g_sun_table_atmo;

static const sun_table *sun_table_get(const model_atmosphere *a)
{
    if (g_sun_table && memcmp(&g_sun_table_atmo, a, sizeof *a) == 0)
        return g_sun_table;
    free(g_sun_table);
    g_sun_table = sun_table_build(a);
    g_sun_table_atmo = *a;
    return g_sun_table;
}

/* One row of the table (altitude j): every column once (the shared segment ends are evaluated twice: cheap, and
 * keeps this simple); the twilight columns (segment 0) with twice the steps, as ref_multiscatter_converged does. A
 * row reads only the atmosphere, the mu_s nodes and the sun table, and writes only its own t->v[j]: rows are
 * independent, so they can be filled on any thread in any order and the table is the same bit for bit. */
static int psi_row_fill(psi_table *t, const model_atmosphere *a, const double *mus, int j, int sqrt_dirs, int steps,
                        const sun_table *st)
{
    double res[PSI_COLS][3], an[PSI_COLS][MS_MOMENTS];
    const int lesson = a->sun_visibility == MODEL_SUN_VISIBILITY_LESSON_FADE;
    double h = psi_row_h(a, j);
    polar_rule pr;
    if (!polar_horizon(a, h, sqrt_dirs, &pr))
        return 0;
    int ok = multiscatter_row(a, h, mus, PSI_SEG0, ms_azimuths(sqrt_dirs), &pr, ms_steps_for(steps, -1.0), 1, 0, st,
                              res, lesson ? NULL : an) &&
             multiscatter_row(a, h, mus + PSI_SEG0, PSI_COLS - PSI_SEG0, ms_azimuths(sqrt_dirs), &pr, steps, 1, 0,
                              st, res + PSI_SEG0, lesson ? NULL : an + PSI_SEG0);
    free(pr.mu);
    if (!ok)
        return 0;
    for (int c = 0; c < 3; ++c) /* the shared node -0.05 belongs to the 1x-steps side (continuity) */
        res[PSI_SEG0 - 1][c] = res[PSI_SEG0][c];
    for (int k = 0; k < MS_MOMENTS; ++k)
        an[PSI_SEG0 - 1][k] = an[PSI_SEG0][k];
    for (int i = 0; i < PSI_COLS; ++i) {
        for (int c = 0; c < 3; ++c)
            t->v[j][i][c] = log(fmax(res[i][c], 1e-300));
        for (int k = 0; k < MS_MOMENTS; ++k)
            t->v[j][i][3 + k] = lesson ? 0.0 : an[i][k];
    }
    return 1;
}

/* The rows on worker threads (~4 s of one core per atmosphere at the converged counts: every reference run, and
 * many tests, build one or more; issue 27 items 3 and 5). Worker w fills rows w, w + n, w + 2n, ...: a fixed split,
 * no shared counter; each row's result does not depend on who computes it. */
typedef struct psi_job {
    psi_table *t;
    const model_atmosphere *a;
    const double *mus;
    const sun_table *st;
    int sqrt_dirs, steps, first, stride, ok;
} psi_job;

static void *psi_worker(void *arg)
{
    psi_job *J = arg;
    for (int j = J->first; J->ok && j < PSI_ROWS; j += J->stride)
        J->ok = !ref_cancelled() && psi_row_fill(J->t, J->a, J->mus, j, J->sqrt_dirs, J->steps, J->st);
    return NULL;
}

static int psi_threads_default(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > PSI_ROWS ? PSI_ROWS : (int)n;
}

psi_table *psi_table_build(const model_atmosphere *a, int sqrt_dirs, int steps, int threads)
{
    psi_table *t = malloc(sizeof *t);
    const sun_table *st = sun_table_get(a); /* built here, on this thread, before any worker reads it */
    double mus[PSI_COLS];
    if (!t || !st) {
        free(t);
        return NULL;
    }
    for (int seg = 0; seg < 3; ++seg)
        for (int i = 0; i < psi_seg_n[seg]; ++i)
            mus[psi_seg_off[seg] + i] = psi_seg_mus(seg, (double)i / (psi_seg_n[seg] - 1));
    mus[0] = -1.0;
    mus[PSI_SEG0 - 1] = mus[PSI_SEG0] = -0.05;
    mus[PSI_SEG0 + PSI_SEG1 - 1] = mus[PSI_SEG0 + PSI_SEG1] = 0.05;
    mus[PSI_COLS - 1] = 1.0;
    int n = threads > 0 ? threads : psi_threads_default();
    n = n > PSI_ROWS ? PSI_ROWS : n;
    psi_job jobs[PSI_ROWS];
    pthread_t tid[PSI_ROWS];
    int started = 0, ok = 1;
    for (int w = 0; w < n; ++w)
        jobs[w] = (psi_job){t, a, mus, st, sqrt_dirs, steps, w, n, 1};
    /* workers 1..n-1 on threads, worker 0 here; the workers whose thread could not start run here after it */
    for (int w = 1; w < n && pthread_create(&tid[w], NULL, psi_worker, &jobs[w]) == 0; ++w)
        started = w;
    psi_worker(&jobs[0]);
    for (int w = started + 1; w < n; ++w)
        psi_worker(&jobs[w]);
    for (int w = 1; w <= started; ++w)
        pthread_join(tid[w], NULL);
    for (int w = 0; w < n; ++w)
        ok = ok && jobs[w].ok;
    if (!ok) {
        free(t);
        return NULL;
    }
    return t;
}

size_t psi_table_bytes(void) { return sizeof(psi_table); }

void psi_table_eval(const psi_table *t, const model_atmosphere *a, double h, double mus, double out[3],
                    double mom[MS_MOMENTS])
{
    double u;
    h = ms_altitude(a, h);
    int seg = psi_seg_u(clampd(mus, -1.0, 1.0), &u);
    double y = sqrt(clampd((h - 0.01) / (atmo_height(a) - 0.01), 0.0, 1.0));
    int ix[4], iy[4];
    double wx[4], wy[4];
    /* mu_s is quadratic in u at -0.05 (the upper end of segment 0, both ends of segment 1) and at 0.05 (both ends
     * of segment 1, the lower end of segment 2), h in y at the bottom row: mirror ghosts there. */
    cubic_taps(u * (psi_seg_n[seg] - 1), psi_seg_n[seg], seg >= 1, seg <= 1, ix, wx);
    cubic_taps(y * (PSI_ROWS - 1), PSI_ROWS, 1, 0, iy, wy);
    for (int c = 0; c < 3 + MS_MOMENTS; ++c) {
        double s = 0.0, lo = INFINITY, hi = -INFINITY;
        for (int b = 0; b < 4; ++b)
            for (int k = 0; k < 4; ++k) {
                double v = t->v[iy[b]][psi_seg_off[seg] + ix[k]][c];
                s += wy[b] * wx[k] * v;
                lo = v < lo ? v : lo;
                hi = v > hi ? v : hi;
            }
        s = clampd(s, lo, hi);
        if (c >= 3)
            mom[c - 3] = s;
        else
            out[c] = s < -690.0 ? 0.0 : exp(s);
    }
}

/* Lazily built tables, keyed by the atmosphere's bytes (less E and g) and the Psi counts; the oldest is replaced
 * when all slots are taken. Building is not thread-safe; looking up an existing table is. */
#define PSI_CACHE_SLOTS 40 /* the spectral reference packs 3 wavelengths per atmosphere: 40 tables hold 120 */

typedef struct psi_cache_slot {
    model_atmosphere atmo;
    int sqrt_dirs, steps;
    unsigned long long used;
    psi_table *table;
} psi_cache_slot;

static psi_cache_slot g_psi_cache[PSI_CACHE_SLOTS];
static unsigned long long g_psi_clock;

void psi_key_atmosphere(const model_atmosphere *a, model_atmosphere *key)
{
    /* Psi is per unit sun illuminance: the key leaves out E, and g where the first bounce is isotropic (the
     * lesson's model; the penumbra's uses the real phases, multiscatter.c). */
    *key = *a;
    if (key->sun_visibility == MODEL_SUN_VISIBILITY_LESSON_FADE)
        key->mie_g = 0.0;
    key->sun_illuminance[0] = key->sun_illuminance[1] = key->sun_illuminance[2] = 0.0;
}

const psi_table *psi_cache_get(const model_atmosphere *a_in, int sqrt_dirs, int steps)
{
    model_atmosphere a;
    psi_key_atmosphere(a_in, &a);
    psi_cache_slot *victim = &g_psi_cache[0];
    for (int i = 0; i < PSI_CACHE_SLOTS; ++i) {
        psi_cache_slot *s = &g_psi_cache[i];
        if (s->table && s->sqrt_dirs == sqrt_dirs && s->steps == steps && memcmp(&s->atmo, &a, sizeof a) == 0)
            return s->table; /* read-only on a hit: concurrent lookups of an existing table are safe */
        if (!s->table || (victim->table && s->used < victim->used))
            victim = s;
    }
    /* VKSKY_PSI_CACHE=DIR (the test suite's): a table an earlier process stored, else built and stored (psi_disk.c). */
    const char *dir = getenv("VKSKY_PSI_CACHE");
    if (dir && !*dir)
        dir = NULL;
    psi_table *t = dir ? psi_disk_load(dir, &a, sqrt_dirs, steps, sizeof *t) : NULL;
    if (!t) {
        t = psi_table_build(&a, sqrt_dirs, steps, 0);
        if (t && dir)
            psi_disk_store(dir, &a, sqrt_dirs, steps, t, sizeof *t);
    }
    if (!t)
        return NULL;
    free(victim->table);
    victim->atmo = a;
    victim->sqrt_dirs = sqrt_dirs;
    victim->steps = steps;
    victim->table = t;
    victim->used = ++g_psi_clock;
    return t;
}

void psi_cache_clear(void)
{
    for (int i = 0; i < PSI_CACHE_SLOTS; ++i) {
        free(g_psi_cache[i].table);
        g_psi_cache[i].table = NULL;
    }
}
