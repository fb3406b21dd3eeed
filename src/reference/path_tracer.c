/* vksky path tracer, the driver: the camera ray (or where it enters the atmosphere), the samples cut into fixed
 * chunks with their own RNG streams, run on threads, and the chunks' statistics merged in order (so the result is
 * the same for any thread count). One path: pt_paths.c. What it computes: path_tracer.h. */
#include "reference/pt_internal.h"

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#define PT_CHUNK 512          /* samples per RNG stream / statistics chunk */

/* ---------------------------------------------------------------------------------------------------------- */
/* Driver: chunks of samples, threads, statistics                                                             */

typedef struct pt_stats {
    double n, mean[3], m2[3];
} pt_stats;

typedef struct pt_job {
    pt_ctx ctx[3];
    pt_ray start;
    long long samples;
    long long nchunks;
    uint64_t seed;
    atomic_llong next;
    pt_stats *chunks;
} pt_job;

static void run_chunk(pt_job *J, long long ci)
{
    pt_rng g;
    pt_stats *st = &J->chunks[ci];
    long long first = ci * PT_CHUNK, count = J->samples - first;
    if (count > PT_CHUNK)
        count = PT_CHUNK;
    rng_seed(&g, J->seed, (uint64_t)ci);
    memset(st, 0, sizeof *st);
    for (long long i = 0; i < count; ++i) {
        st->n += 1.0;
        for (int c = 0; c < 3; ++c) {
            double x = trace_path(&J->ctx[c], &J->start, &g);
            double d = x - st->mean[c];
            st->mean[c] += d / st->n;
            st->m2[c] += d * (x - st->mean[c]);
        }
    }
}

static void *worker(void *arg)
{
    pt_job *J = arg;
    for (;;) {
        long long ci = atomic_fetch_add(&J->next, 1);
        if (ci >= J->nchunks)
            break;
        run_chunk(J, ci);
    }
    return NULL;
}

static void stats_merge(pt_stats *a, const pt_stats *b)
{
    if (b->n <= 0.0)
        return;
    if (a->n <= 0.0) {
        *a = *b;
        return;
    }
    double n = a->n + b->n;
    for (int c = 0; c < 3; ++c) {
        double d = b->mean[c] - a->mean[c];
        a->mean[c] += d * b->n / n;
        a->m2[c] += b->m2[c] + d * d * a->n * b->n / n;
    }
    a->n = n;
}

static void normalize3(const double in[3], double out[3])
{
    double l = sqrt(dot3(in, in));
    for (int i = 0; i < 3; ++i)
        out[i] = l > 0.0 ? in[i] / l : 0.0;
}

void pt_radiance(const model_atmosphere *a, double altitude, const double view_dir[3], const double sun_dir[3],
                 const pt_settings *s, double out_rgb[3], double out_stderr[3])
{
    double v[3], sd[3];
    for (int c = 0; c < 3; ++c) {
        out_rgb[c] = 0.0;
        if (out_stderr)
            out_stderr[c] = 0.0;
    }
    if (!a || !s || s->samples <= 0 || !(altitude == altitude))
        return;
    normalize3(view_dir, v);
    normalize3(sun_dir, sd);
    if (dot3(v, v) == 0.0 || dot3(sd, sd) == 0.0)
        return;

    pt_job *J = calloc(1, sizeof *J);
    if (!J)
        return;
    const double Rb = a->bottom_radius, Rt = a->top_radius, top = Rt - Rb;
    for (int c = 0; c < 3; ++c) {
        pt_ctx *C = &J->ctx[c];
        C->Rb = Rb;
        C->Rt = Rt;
        C->top = top;
        C->atmo = a;
        C->bR = a->rayleigh_scattering[c];
        C->bMs = a->mie_scattering[c];
        C->bMt = a->mie_scattering[c] + a->mie_absorption[c];
        C->bO = a->ozone_absorption[c];
        for (int i = 0; i < a->extra_count; ++i) {
            C->bEs[i] = a->extra[i].scattering[c];
            C->bEa[i] = a->extra[i].absorption[c];
        }
        C->g = a->mie_g;
        C->E = a->sun_illuminance[c];
        C->albedo = s->ground_albedo > 0.0 ? s->ground_albedo : 0.0;
        C->max_bounces = s->max_bounces;
        memcpy(C->sun, sd, sizeof sd);
        double half = 0.5 * (a->sun_angular_radius > 0.0 ? a->sun_angular_radius : 0.0);
        C->sun_cap = 2.0 * sin(half) * sin(half);
    }

    /* Camera, or the point where the view ray enters the atmosphere. */
    double h = altitude > 0.0 ? altitude : 0.0;
    double p[3] = {0.0, Rb + h, 0.0};
    double rho2 = h * (2.0 * Rb + h);
    if (h > top) {
        double b = (Rb + h) * v[1];
        double c = (h - top) * (Rb + h + Rt); /* r^2 - Rt^2 */
        double disc = b * b - c;
        if (!(b < 0.0) || !(disc > 0.0) || !isfinite(c)) {
            free(J);
            return; /* misses the atmosphere */
        }
        double t = c / (-b + sqrt(disc));
        for (int i = 0; i < 3; ++i)
            p[i] += t * v[i];
        rho2 = top * (Rt + Rb);
    }
    ray_set(&J->ctx[0], &J->start, p, rho2, v);

    J->samples = s->samples;
    J->nchunks = (s->samples + PT_CHUNK - 1) / PT_CHUNK;
    J->seed = s->seed;
    atomic_init(&J->next, 0);
    J->chunks = calloc((size_t)J->nchunks, sizeof *J->chunks);
    if (!J->chunks) {
        free(J);
        return;
    }
    int nt = s->threads > 0 ? s->threads : 1;
    if (nt > 256)
        nt = 256;
    if (nt > J->nchunks)
        nt = (int)J->nchunks;
    pthread_t tid[256];
    int started = 0;
    for (int i = 1; i < nt; ++i) {
        if (pthread_create(&tid[started], NULL, worker, J) != 0)
            break;
        ++started;
    }
    worker(J);
    for (int i = 0; i < started; ++i)
        pthread_join(tid[i], NULL);

    pt_stats tot;
    memset(&tot, 0, sizeof tot);
    for (long long i = 0; i < J->nchunks; ++i)
        stats_merge(&tot, &J->chunks[i]);
    for (int c = 0; c < 3; ++c) {
        out_rgb[c] = tot.mean[c];
        if (out_stderr)
            out_stderr[c] = tot.n > 1.0 ? sqrt(tot.m2[c] / (tot.n - 1.0) / tot.n) : 0.0;
    }
    free(J->chunks);
    free(J);
}
