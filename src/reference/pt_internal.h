/* Internals of the path tracer (path_tracer.h), shared by its two files and by nothing else:
 *   pt_paths.c     one path of one colour channel: the RNG, the medium and its majorants, the ray geometry, the
 *                  majorant segments, direction sampling, the estimator (trace_path)
 *   path_tracer.c  the driver: the camera ray, chunks of samples on threads, the statistics (pt_radiance) */
#ifndef VKSKY_PT_INTERNAL_H
#define VKSKY_PT_INTERNAL_H

#include "reference/path_tracer.h"

#include <stdint.h>

/* xoshiro256** seeded by splitmix64, one stream per chunk of samples. */
typedef struct pt_rng {
    uint64_t s[4];
} pt_rng;

/* The stream `stream` of seed `seed`. */
void rng_seed(pt_rng *g, uint64_t seed, uint64_t stream);

/* The medium of one channel and the sun. */
typedef struct pt_ctx {
    double Rb, Rt, top;
    const model_atmosphere *atmo; /* the density profiles */
    double bR, bMs, bMt, bO; /* Rayleigh scattering, Mie scattering, Mie extinction, ozone absorption */
    double bEs[MODEL_MAX_EXTRA_SPECIES], bEa[MODEL_MAX_EXTRA_SPECIES]; /* extra species: scattering, absorption */
    double g, E, albedo;
    double sun[3];
    double sun_cap;  /* 1 - cos(sun angular radius) = 2 sin^2(R/2): the sun's cone, sampled uniformly (0: a point) */
    int max_bounces;
} pt_ctx;

static inline double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

typedef struct pt_ray {
    double p[3], d[3];
    double rho2, r, h, b; /* r^2 - Rb^2, |p|, altitude, r mu = p.d */
} pt_ray;

/* R from a point p, its rho^2 = r^2 - Rb^2 (negative taken as 0) and a unit direction d. */
void ray_set(const pt_ctx *C, pt_ray *R, const double p[3], double rho2, const double d[3]);

/* One path of channel C from `start`: its radiance estimate (see pt_paths.c for the estimator). */
double trace_path(const pt_ctx *C, const pt_ray *start, pt_rng *g);

#endif /* VKSKY_PT_INTERNAL_H */
