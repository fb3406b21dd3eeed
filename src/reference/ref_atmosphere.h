/* vksky CPU reference of the atmosphere model in docs/model.md.
 *
 * Double precision, no Vulkan, only libm. It is the independent ground truth that the GPU output is tested
 * against: every integral is evaluated directly (no LUT for transmittance) with step counts large enough to be
 * converged (see ref_quality_converged()). Units: kilometres, radians; the camera's local up is +Y.
 *
 * Not thread-safe: ref_sky_radiance() builds a multi-scattering table lazily in a small static cache.
 */
#ifndef VKSKY_REF_ATMOSPHERE_H
#define VKSKY_REF_ATMOSPHERE_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ref_atmosphere {
    double bottom_radius, top_radius; /* km */
    double rayleigh_scattering[3], rayleigh_scale_height;
    double mie_scattering[3], mie_absorption[3], mie_scale_height, mie_g;
    double ozone_absorption[3], ozone_center, ozone_half_width;
    double sun_illuminance[3];
} ref_atmosphere;

/* Hillaire 2020 Table 1 defaults (docs/model.md "Medium"). */
void ref_atmosphere_earth(ref_atmosphere *out);

/* dir(az, el) = (cos el cos az, sin el, cos el sin az). */
void ref_dir(double azimuth_rad, double elevation_rad, double out[3]);

/* Bruneton transmittance-LUT mapping with the texel-centre sub-UV (docs/model.md). width/height = LUT size
 * (u <-> x_mu over width, v <-> x_r over height). x is clamped to [0, 1] on both sides (what a clamp-to-edge
 * sampler does), so rays below the horizon map to the last u texel centre. */
void ref_transmittance_uv_to_params(const ref_atmosphere *a, double u, double v, int width, int height,
                                    double *altitude, double *mu);
void ref_transmittance_params_to_uv(const ref_atmosphere *a, double altitude, double mu, int width, int height,
                                    double *u, double *v);

/* T(h, mu) to the top boundary, no ground test, `steps` midpoint steps (4000 is converged to ~1e-7). The
 * altitude is clamped to [0, top - bottom]. Rays below the horizon pass through the planet (as the model says)
 * and give ~0. */
void ref_transmittance(const ref_atmosphere *a, double altitude, double mu, int steps, double out[3]);

/* Psi(h, mu_s), per unit sun illuminance, per docs/model.md but with the nested transmittance integrated
 * directly: sqrt_dirs x sqrt_dirs stratified directions (8 = the GPU's 64), `steps` view steps per direction,
 * `sun_steps` for each nested transmittance. Applies the 10 m altitude clamp. */
void ref_multiscatter(const ref_atmosphere *a, double altitude, double mu_s, int sqrt_dirs, int steps,
                      int sun_steps, double out[3]);

/* The same Psi integral by a quadrature that converges fast (NOT the model's stratification, so its n = 8 is not
 * the GPU's 64 directions): the polar angle is split at the horizon (sqrt_dirs/2 Gauss-Legendre nodes per side, in
 * s with mu = mu_h +- (1 -+ mu_h) s^2), sqrt_dirs azimuths at midpoints, `steps` steps per direction graded toward
 * the lowest point of the ray, nested transmittance direct with `sun_steps`. Applies the 10 m altitude clamp.
 * ref_sky_radiance() tabulates exactly this (with ms_sqrt_dirs, ms_steps). */
void ref_multiscatter_converged(const ref_atmosphere *a, double altitude, double mu_s, int sqrt_dirs, int steps,
                                int sun_steps, double out[3]);

/* Ms LUT texel (i, j) of a W x H LUT -> (altitude, mu_s): mu_s = 2x - 1 (u, i), h = x (top - bottom) (v, j) with
 * x = k / (N - 1) (texel-centre sub-UV). The altitude is NOT clamped to 10 m here (ref_multiscatter does it). */
void ref_multiscatter_texel_params(const ref_atmosphere *a, int i, int j, int width, int height, double *altitude,
                                   double *mu_s);

typedef struct ref_quality {
    int view_steps;   /* midpoint steps along the view ray */
    int sun_steps;    /* midpoint steps of every nested transmittance */
    int ms_sqrt_dirs; /* Psi: sqrt_dirs x sqrt_dirs directions */
    int ms_steps;     /* Psi: steps per direction */
} ref_quality;

/* The counts proven converged (< 0.1 % remaining change per doubling) by tests/test_reference.c. */
ref_quality ref_quality_converged(void);

/* Sky radiance (scene-linear, units of the GPU's HDR output, sun disc EXCLUDED, not clamped to 65504) seen from
 * camera altitude `altitude` (>= 0; above the top the ray enters the atmosphere, radiance 0 if it misses it),
 * with unit view and sun directions in the camera's local frame (up = +Y; they are normalised defensively).
 * Psi at each view sample comes from a double-precision table built lazily (and cached) per atmosphere and per
 * (ms_sqrt_dirs, ms_steps, sun_steps); see ref_atmosphere.c for its layout and its measured error. */
void ref_sky_radiance(const ref_atmosphere *a, double altitude, const double view_dir[3], const double sun_dir[3],
                      ref_quality q, double out_rgb[3]);

/* View direction of pixel (x, y) (y = 0 at the top) of a width x height image, docs/model.md "Conventions of the
 * image"; fov_y_rad is the vertical field of view. */
void ref_pixel_dir(int x, int y, int width, int height, double yaw_rad, double pitch_rad, double fov_y_rad,
                   double out[3]);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_REF_ATMOSPHERE_H */
