/* Atmosphere parameters on the CPU (the model's model_atmosphere, in double) packed into the uniform block the
 * shaders read (AtmosphereParams in shaders/glsl/shared.h). */
#ifndef VKSKY_SKY_ATMOSPHERE_H
#define VKSKY_SKY_ATMOSPHERE_H
#include "model/medium.h"
#include "shared.h"
#include <stdbool.h>
#include <volk.h>
#include <stdint.h>

/* LUT quality knobs. Sizes and format are fixed when the renderer is created; step counts can change at run
 * time (they are uniforms; a change recomputes the LUTs). */
typedef struct sky_lut_quality {
    int transmittance_width, transmittance_height;   /* 256 x 64 */
    int transmittance_steps;      /* 40 */
    int multiscatter_size;        /* 32 (square) */
    int multiscatter_steps;       /* 20 */
    int multiscatter_sqrt_dirs;   /* 8 -> 64 directions */
    bool lut_f32;                 /* RGBA32F LUTs instead of RGBA16F */
    int skyview_width, skyview_height;   /* 192 x 108 */
} sky_lut_quality;

sky_lut_quality sky_lut_quality_default(void);

/* The four-wide spectral build (SPECTRAL4 shaders, --spectral N): the fourth wavelength's value of every per-channel
 * quantity, packed into the .w slots of the uniform block (the three others are the model_atmosphere's channels). */
typedef struct sky_fourth {
    double rayleigh_scattering, mie_scattering, mie_absorption, ozone_absorption;
    double extra_scattering[VKSKY_MAX_EXTRA], extra_absorption[VKSKY_MAX_EXTRA];
    double sun_illuminance, ground_albedo;
} sky_fourth;

/* Scene features beyond the medium (scene files and their flags). */
typedef struct sky_features {
    double ground_albedo[3];      /* Lambertian; 0: the ground is black and not shaded (compiled out) */
    int mie_phase;                /* VKSKY_MIE_PHASE_HG or VKSKY_MIE_PHASE_CORNETTE_SHANKS */
    double limb_darkening;        /* u of 1 - u (1 - cos); 0.6 */
    bool sun_disc;
    bool multiple_scattering;     /* false: no multi-scattering LUT pass, no Psi term */
    bool sun_disc_power;          /* the disc integrates to the sun's illuminance (else the lesson's sun x 10) */
    bool spectral4;               /* pack `fourth` as a fourth channel (set by the renderer: its desc.spectral4) */
    sky_fourth fourth;
} sky_features;
sky_features sky_features_default(void);

/* The pipeline variant a scene needs: specialization constants VKSKY_SPEC_* (shared.h). */
typedef struct sky_variant {
    VkBool32 rayleigh, mie, ozone, multiscatter, sun_disc, ground;
    int32_t mie_phase;
    int32_t profile[3];           /* VKSKY_PROFILE_* of Rayleigh, Mie, ozone */
    int32_t extra_species;        /* extra species evaluated (0 .. VKSKY_MAX_EXTRA) */
    int32_t extra_profile[VKSKY_MAX_EXTRA];
    int32_t sun_visibility;       /* VKSKY_SUN_VISIBILITY_* (the model's sun_visibility) */
    VkBool32 spectral4;           /* the SPECTRAL4 shaders (not a specialization constant: other SPIR-V) */
} sky_variant;
sky_variant sky_variant_of(const model_atmosphere *a, const sky_features *f);
void sky_atmosphere_pack(const model_atmosphere *a, double sun_angular_radius_rad, sky_lut_quality q,
                         const sky_features *f, AtmosphereParams *out);
/* FNV-1a of the packed block's LUT-relevant part (for the variant's VKSKY_SUN_VISIBILITY_*): LUTs are recomputed
 * only when it changes. */
uint64_t sky_atmosphere_lut_hash(const AtmosphereParams *p, int sun_visibility);
#endif
