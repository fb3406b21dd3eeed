/* The model of the medium: the planet, the species of the atmosphere with their density profiles, the Mie phase
 * asymmetry and the sun's illuminance (docs/model.md "Medium").
 *
 * Plain C, no Vulkan and no integrators: it is the one definition that both implementations of the model share —
 * the GPU renderer packs it into its uniform block (src/sky/atmosphere.c), the CPU reference and the path tracer
 * integrate it (src/reference/), and the scene loader fills it (src/app/). Units: kilometres, 1/km. */
#ifndef VKSKY_MODEL_MEDIUM_H
#define VKSKY_MODEL_MEDIUM_H

#include "model/sun_visibility.h"

#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A density profile as Bruneton's DensityProfileLayer pair: below layers[0].width (km) layer 0 applies, above it
 * layer 1; density = clamp(exp_term exp(exp_scale h) + linear_term h + constant_term, 0, 1), h in km. */
typedef struct model_density_layer { double width, exp_term, exp_scale, linear_term, constant_term; } model_density_layer;
typedef struct model_density_profile { model_density_layer layers[2]; } model_density_profile;

/* A species beyond Rayleigh, Mie and ozone (scene files: any other name under "species"): a gas that absorbs
 * and/or scatters with the Rayleigh (molecular) phase, e.g. NO2 or a second absorber layer. */
#define MODEL_MAX_EXTRA_SPECIES 2
typedef struct model_extra_species {
    char name[32];
    double scattering[3], absorption[3]; /* /km at density 1 */
    model_density_profile density;
} model_extra_species;

typedef struct model_atmosphere {
    double bottom_radius, top_radius; /* km */
    double rayleigh_scattering[3];
    double mie_scattering[3], mie_absorption[3], mie_g;
    double ozone_absorption[3];
    model_density_profile rayleigh_density, mie_density, ozone_density;
    int extra_count;                  /* 0 .. MODEL_MAX_EXTRA_SPECIES */
    int sun_visibility;               /* MODEL_SUN_VISIBILITY_PENUMBRA (default) or _LESSON_FADE (sun_visibility.h) */
    model_extra_species extra[MODEL_MAX_EXTRA_SPECIES];
    double sun_illuminance[3];
    double sun_angular_radius;        /* rad, the sun disc's (the penumbra's width); default 0.265 degrees */
} model_atmosphere;

double model_density(const model_density_profile *p, double altitude);
/* Exact max of model_density over the altitude range [hmin, hmax] (a path tracer's majorant). */
double model_density_max(const model_density_profile *p, double hmin, double hmax);
/* exp(-h/H), and the tent max(0, 1 - |h - center| / half_width), as profiles. */
model_density_profile model_profile_exponential(double scale_height);
model_density_profile model_profile_tent(double center, double half_width);
/* The inverse: true (and the parameters) if the profile is exactly that form. */
bool model_profile_as_exponential(const model_density_profile *p, double *scale_height);
bool model_profile_as_tent(const model_density_profile *p, double *center, double *half_width);

/* Hillaire 2020 Table 1 defaults (docs/model.md "Medium"). */
void model_atmosphere_earth(model_atmosphere *out);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_MODEL_MEDIUM_H */
