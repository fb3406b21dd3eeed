/* The spectral CPU reference (issue 32): the converged model (ref_sky_radiance) or the path tracer (pt_radiance)
 * run wavelength by wavelength over the medium per wavelength (model/spectral_medium.h), the sun the shipped
 * top-of-atmosphere spectrum (model/spectrum.h), radiance -> CIE 1931 XYZ -> linear Rec.709.
 *
 * Wavelengths: `wavelengths` bins of equal width over [360, 830] nm, each sampled at its centre. A bin's weight is
 * the exact integral over the bin of 683 E(lambda) cmf(lambda) (the sun's spectrum times the colour matching
 * function, both piecewise linear, by Simpson's rule on 1/8-bin pieces); the atmosphere's response per unit sun
 * (sr^-1), which is smooth in lambda, is taken at the bin's centre. Three wavelengths travel together as the three
 * channels of one model_atmosphere (each channel is integrated on its own by both integrators).
 *
 * Units: XYZ in cd m^-2 sr^0 (Y is luminance) for sun_scale 1 (the sun at the top of the atmosphere); the spectrum
 * out in W m^-2 sr^-1 nm^-1. Sun disc excluded, as in ref_sky_radiance. */
#ifndef VKSKY_REF_SPECTRAL_H
#define VKSKY_REF_SPECTRAL_H

#include "model/spectral_medium.h"
#include "reference/path_tracer.h"

#ifdef __cplusplus
extern "C" {
#endif

#define REF_SPECTRAL_MIN 3
#define REF_SPECTRAL_MAX 120 /* 40 packed atmospheres: what the Psi cache keeps (psi_table.c) */

typedef struct ref_spectral {
    model_atmosphere atmosphere; /* radii, profiles, phase, sun geometry; its RGB coefficients are not used */
    spectral_medium medium;
    int wavelengths;             /* REF_SPECTRAL_MIN .. REF_SPECTRAL_MAX */
    double sun_scale;            /* x the top-of-atmosphere solar spectrum (1: absolute, photometric) */
    ref_quality q;               /* the model's counts */
    const pt_settings *pt;       /* NULL: the model; else the path tracer with these settings (seed + group) */
} ref_spectral;

/* *s for atmosphere a: the medium spectral_medium_from_rgb(a), the converged counts, sun_scale 1, the model. */
void ref_spectral_init(ref_spectral *s, const model_atmosphere *a, int wavelengths);

/* Centre of bin i of n over [360, 830] nm, and the bin's weights 683 * integral of E cmf (lm m^-2 per sr^-1 of
 * response at sun_scale 1: X, Y, Z). */
double ref_spectral_nm(int n, int i);
void ref_spectral_weights(int n, int i, double w_xyz[3]);

/* The packed atmosphere of group g (wavelengths 3g .. 3g+2; a missing third is a copy of the last), sun 1 per
 * channel. Returns how many of its channels are real wavelengths. */
int ref_spectral_group(const ref_spectral *s, int g, model_atmosphere *out, int idx[3]);

/* Sky radiance as XYZ (cd/m^2 at sun_scale 1) and, when not NULL, its standard error (path tracer; 0 for the
 * model) and the spectral radiance per bin (W m^-2 sr^-1 nm^-1). Arguments as ref_sky_radiance's. */
void ref_spectral_radiance(const ref_spectral *s, double altitude, const double view_dir[3], const double sun_dir[3],
                           double xyz[3], double xyz_stderr[3], double *spectrum);

/* Irradiance at the camera (irradiance.c). Spectral values per bin (W m^-2 nm^-1) and integrals over 360-830 nm:
 * W m^-2 and lux. Direct normal: the sun's transmitted beam (disc centre, no circumsolar light). Diffuse: the sky
 * (the model's or path tracer's radiance) over the hemisphere above the surface, plus, on a tilted surface, the
 * ground's light as an isotropic (Lambertian) reflector of the global horizontal irradiance with the scene's
 * ground albedo (RGB law over the wavelengths) seen over the tilted surface's view factor (1 - cos tilt) / 2. */
typedef struct ref_irradiance_band {
    double direct_normal, diffuse_horizontal, global_horizontal, diffuse_tilted, global_tilted;
} ref_irradiance_band;
typedef struct ref_irradiance {
    int count;
    double nm[REF_SPECTRAL_MAX];
    ref_irradiance_band spectral[REF_SPECTRAL_MAX]; /* W m^-2 nm^-1 */
    ref_irradiance_band watts;                      /* W m^-2 over 360-830 nm */
    ref_irradiance_band lux;
    double cos_incidence_tilted;                    /* cos of the sun's angle to the tilted surface's normal */
} ref_irradiance;

/* tilt_deg in [0, 180] from horizontal, the surface facing azimuth tilt_azimuth_deg (the convention of ref_dir:
 * 0 = +X); ground_albedo the RGB albedo; n_dirs the hemisphere quadrature's size (n_dirs x 2 n_dirs directions
 * about the sun). Measured against 64 (sun 60 and 20 deg, aerosol 0.07, tilt 37): 16 puts the diffuse horizontal
 * within 0.1 %, the diffuse tilted within 1.5 % (the tilted plane's edge cuts the grid), ~0.2 % of global tilted.
 * 0 on success, -1 out of memory. */
int ref_spectral_irradiance(const ref_spectral *s, double altitude, const double sun_dir[3], double tilt_deg,
                            double tilt_azimuth_deg, const double ground_albedo[3], int n_dirs, ref_irradiance *out);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_REF_SPECTRAL_H */
