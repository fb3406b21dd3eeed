/* vksky Monte Carlo volumetric path tracer: the physical ground truth the model (docs/model.md) is measured against.
 *
 * Same medium as model_atmosphere (spherical planet, Rayleigh + Mie (Henyey-Greenstein, g = mie_g) + ozone
 * (absorption only), the density profiles of docs/model.md, RGB), but real physics instead of the model's
 * approximations: ALL scattering orders with the true phase functions, no horizon fade, a binary earth shadow,
 * Lambertian ground (albedo a parameter, 0 by default). The sun is a directional light of per-channel illuminance
 * a->sun_illuminance whose disc is EXCLUDED: light reaches the camera only after >= 1 scattering event.
 *
 * Method (unbiased; see pt_paths.c for the details):
 *  - each colour channel is traced monochromatically (its own path, its own sigma_t), so no spectral MIS is needed;
 *  - free paths are sampled with delta tracking against piecewise-constant majorants: every ray is cut into
 *    segments that are monotone in altitude (split at the tangent point), each at most a few km of altitude
 *    change, and the majorant of a segment is the exact maximum of sigma_t over it (exponential profiles peak at
 *    the segment's lowest point, the ozone tent over its altitude range);
 *  - the direct sun term along every ray is a ratio-tracking "collision" estimator: at every tentative collision
 *    of the majorant process, NEE toward the sun (shadow test against the planet, sun transmittance by ratio
 *    tracking) weighted by the running ratio-tracking transmittance; the majorant is scaled up where a ray is
 *    optically thin so that each ray gets at least a few tentative points (it works in the optically thin limit);
 *  - the continuation (higher orders) follows the first REAL collision of the same majorant process (delta
 *    tracking), with the single-scattering albedo as weight, a new direction sampled from the local phase mixture
 *    (Rayleigh / HG in proportion to their scattering coefficients); at the ground, Lambertian NEE and
 *    cosine-weighted continuation; Russian roulette on long paths when max_bounces = 0.
 * Geometry in double precision, with the cancellation-free forms of docs/model.md: every vertex carries
 * rho^2 = r^2 - Rb^2 and altitudes along a ray are h_t = (rho^2 + t (t + 2 r mu)) / (r_t + Rb).
 *
 * Deterministic for a given seed, independently of the thread count: the samples are cut into fixed chunks, each
 * with its own xoshiro256** stream seeded from (seed, chunk index), and the chunks' statistics are merged in order.
 */
#ifndef VKSKY_PATH_TRACER_H
#define VKSKY_PATH_TRACER_H

#include "reference/ref_atmosphere.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pt_settings {
    long long samples;        /* paths per channel (each sample = one path per R, G, B) */
    unsigned long long seed;  /* same seed, same result (bit for bit, whatever the thread count) */
    double ground_albedo;     /* Lambertian, 0 by default */
    int max_bounces;          /* 0: unlimited (Russian roulette); k: scattering vertices 1..k only (1 = single) */
    int threads;              /* 0: 1 */
} pt_settings;

/* Radiance along view_dir (unit, camera frame up = +Y) from camera altitude (km, >= 0; above the top the ray
 * enters the atmosphere first, 0 if it misses it), sun disc excluded, in the units of ref_sky_radiance.
 * out_stderr (may be NULL): the standard error of each channel's estimate (sample standard deviation / sqrt(N)). */
void pt_radiance(const model_atmosphere *a, double altitude, const double view_dir[3], const double sun_dir[3],
                 const pt_settings *s, double out_rgb[3], double out_stderr[3]);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_PATH_TRACER_H */
