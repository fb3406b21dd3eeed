/* vksky CPU reference of the atmosphere model in docs/model.md.
 *
 * Double precision, no Vulkan, only libm. It is the independent ground truth that the GPU output is tested
 * against: transmittance is integrated directly (no LUT), and every count is large enough to be converged
 * (ref_quality_converged(); tests/test_reference.c proves it). Units: kilometres, radians; local up is +Y.
 * Inputs are expected finite (ref_sky_radiance returns 0 for unusable ones).
 *
 * Threads: ref_sky_radiance() builds a multi-scattering table lazily (per atmosphere and Psi counts, in a small
 * static cache, ~2 s at the converged counts; its rows are filled on worker threads, one per core, the same bytes
 * for any count: tests/test_psi_threads.c). Building is not thread-safe (two callers must not build at once); once
 * the table exists (one call made), concurrent calls with the same atmosphere and counts are. Everything else is
 * reentrant.
 *
 * The implementation is split by what it computes; ref_internal.h lists which file holds what.
 */
#ifndef VKSKY_REF_ATMOSPHERE_H
#define VKSKY_REF_ATMOSPHERE_H

#include "model/medium.h"
#include <signal.h>
#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

/* dir(az, el) = (cos el cos az, sin el, cos el sin az). */
void ref_dir(double azimuth_rad, double elevation_rad, double out[3]);

/* Bruneton transmittance-LUT mapping with the texel-centre sub-UV (docs/model.md). width/height = LUT size
 * (u <-> x_mu over width, v <-> x_r over height). x is clamped to [0, 1] on both sides (what a clamp-to-edge
 * sampler does), so rays below the horizon map to the last u texel centre. */
void ref_transmittance_uv_to_params(const model_atmosphere *a, double u, double v, int width, int height,
                                    double *altitude, double *mu);
void ref_transmittance_params_to_uv(const model_atmosphere *a, double altitude, double mu, int width, int height,
                                    double *u, double *v);

/* T(h, mu) to the top boundary, no ground test, `steps` uniform midpoint steps (4000: relative error ~2e-7). The
 * altitude is clamped to [0, top - bottom]. Rays below the horizon pass through the planet (as the model says)
 * and give ~0 (the GPU's LUT holds the horizon value there; only shadowed points ever ask for it). */
void ref_transmittance(const model_atmosphere *a, double altitude, double mu, int steps, double out[3]);

/* Psi(h, mu_s), per unit sun illuminance, exactly the model's quadrature but with the nested transmittance
 * integrated directly: sqrt_dirs x sqrt_dirs stratified directions (8 = the GPU's 64), `steps` uniform midpoint
 * steps per direction, `sun_steps` for each nested transmittance. Applies the 10 m altitude clamp.
 * For checking the GPU's LUT texel by texel. It is NOT a way to converged values: its integrand jumps at the
 * horizon, so it converges O(1/n) and erratically in sqrt_dirs (~5 % off at 64x64; the GPU's 8x8 is 2-22 % off
 * in daylight). Converged Psi: ref_multiscatter_converged(). */
void ref_multiscatter(const model_atmosphere *a, double altitude, double mu_s, int sqrt_dirs, int steps,
                      int sun_steps, double out[3]);

/* The same Psi integral (the model's, over the whole sphere and every ray) by a quadrature that converges fast
 * and cleanly; NOT the model's stratification, so its sqrt_dirs = 8 is not the GPU's 64 directions:
 *  - polar angle split at the horizon mu_h = -rho/r: sqrt_dirs/2 Gauss-Legendre nodes on each side, in s with
 *    mu = mu_h +- (1 -+ mu_h) s^2;
 *  - sqrt_dirs/2 azimuths at midpoints (the model's azimuth rule);
 *  - `steps` midpoint steps per direction (2 x steps when mu_s < -0.05), graded quadratically toward the lowest
 *    point of the ray, steps that contain an earth-shadow boundary or a kink of the horizon fade integrated
 *    piecewise;
 *  - nested transmittance direct with `sun_steps`. Applies the 10 m altitude clamp.
 * ref_sky_radiance() tabulates exactly this (with ms_sqrt_dirs, ms_steps; its nested transmittance from a fine
 * table, 1e-5 from direct). At (48, 64, 128): < 0.1 % change when any count is doubled (tests/test_reference.c). */
void ref_multiscatter_converged(const model_atmosphere *a, double altitude, double mu_s, int sqrt_dirs, int steps,
                                int sun_steps, double out[3]);

/* Ms LUT texel (i, j) of a W x H LUT -> (altitude, mu_s): mu_s = sign(2x - 1) (2x - 1)^2 (u, i), h = x (top - bottom) (v, j) with
 * x = k / (N - 1) (texel-centre sub-UV). The altitude is NOT clamped to 10 m here (ref_multiscatter does it). */
void ref_multiscatter_texel_params(const model_atmosphere *a, int i, int j, int width, int height, double *altitude,
                                   double *mu_s);

typedef struct ref_quality {
    int view_steps;   /* midpoint steps along the view ray (graded, split at shadow/fade boundaries) */
    int sun_steps;    /* uniform midpoint steps of every nested sun transmittance along the view ray */
    int ms_sqrt_dirs; /* Psi table: ref_multiscatter_converged's sqrt_dirs */
    int ms_steps;     /* Psi table: ref_multiscatter_converged's steps */
    int ms_off;       /* 1: single scattering only, no Psi table (tests of what does not depend on it; 0 default) */
} ref_quality;

/* {view 512, sun 256, ms_sqrt_dirs 48, ms_steps 64}. Doubling a count changes the radiance by (13 rays from noon
 * to sun -6 deg, ground to 36000 km, tests/test_reference.c): view_steps 3e-5, sun_steps 8e-5; Psi itself changes
 * < 4.4e-4 per doubling of its counts at the test's points. Doubling both Psi counts at once (96, 128) changes the
 * radiance by <= 3e-4 for the sun down to -8 deg (24 rays, measured while developing), 1.4e-3 at -10 deg (where
 * the sky is 1e-7 of noon). ~2 ms per ref_sky_radiance call once the Psi table exists (~2 s to build). */
ref_quality ref_quality_converged(void);

/* Sky radiance (scene-linear, units of the GPU's HDR output, sun disc EXCLUDED, not clamped to 65504) seen from
 * camera altitude `altitude` (>= 0; above the top the ray enters the atmosphere, radiance 0 if it misses it),
 * with unit view and sun directions in the camera's local frame (up = +Y; they are normalised defensively).
 * Psi at each view sample is interpolated from a double-precision table of ref_multiscatter_converged values,
 * built lazily and cached per atmosphere (less sun illuminance and g, which Psi does not depend on) and per
 * (ms_sqrt_dirs, ms_steps). Error the table adds: <= 4e-5 in daylight, <= 2e-4 down to sun -6 deg. */
void ref_sky_radiance(const model_atmosphere *a, double altitude, const double view_dir[3], const double sun_dir[3],
                      ref_quality q, double out_rgb[3]);

/* The graceful stop (app/runs/stop.h): while *flag is non-zero, a table being built (Psi, the sun's transmittance) stops
 * at its next row and none is kept, so radiance computed from then on lacks multiple scattering: the caller, which
 * looks at the same flag, discards it. NULL (the default) turns this off. */
void ref_set_cancel(const volatile sig_atomic_t *flag);

/* Aerial perspective to a point: from camera altitude `altitude` along the unit view direction (local frame, up =
 * +Y) to the point `distance` km away, with the sun toward sun_dir. L_point_seen = L_point T + S with S =
 * rayleigh + mie exactly: `rayleigh` holds the single scattering of every species with the Rayleigh phase
 * (Rayleigh and the extra species) plus their share Psi sigma_s of the multiple scattering, `mie` Mie's single
 * scattering plus its share. The march of ref_sky_radiance stopped at the point (the same steps and cuts over
 * the shorter segment; a point beyond the ray's end is clamped to it; the lit ground's reflection, which is
 * the surface's own radiance, is not included). distance <= 0: T = 1, S = 0. */
typedef struct ref_aerial {
    double transmittance[3];
    double rayleigh[3], mie[3];
} ref_aerial;
void ref_radiance_to_point(const model_atmosphere *a, double altitude, const double view_dir[3],
                           const double sun_dir[3], double distance, ref_quality q, ref_aerial *out);

/* View direction of pixel (x, y) (y = 0 at the top) of a width x height image, docs/model.md "Conventions of the
 * image"; fov_y_rad is the vertical field of view. */
void ref_pixel_dir(int x, int y, int width, int height, double yaw_rad, double pitch_rad, double fov_y_rad,
                   double out[3]);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_REF_ATMOSPHERE_H */
