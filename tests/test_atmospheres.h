/* Test media shared by the CPU and GPU tests (header only). */
#ifndef VKSKY_TEST_ATMOSPHERES_H
#define VKSKY_TEST_ATMOSPHERES_H
#include "reference/ref_atmosphere.h"
#include <math.h>

/* Earth with general Bruneton layer pairs (none of the named forms): a 2 km well-mixed haze (3x Table 1's Mie)
 * under an exponential tail, an ozone layer with a flat top (clamped at 1 from 15 to 20 km), and Rayleigh with
 * a linear term and the [0, 1] clamp. */
static inline model_atmosphere test_layered_atmosphere(void)
{
    model_atmosphere a;
    model_atmosphere_earth(&a);
    for (int c = 0; c < 3; ++c) a.mie_scattering[c] *= 3.0;
    a.mie_density = (model_density_profile){{{.width = 2.0, .constant_term = 1.0},
                                           {.exp_term = exp(2.0 / 1.2), .exp_scale = -1.0 / 1.2}}};
    a.ozone_density = (model_density_profile){{{.width = 20.0, .linear_term = 0.2, .constant_term = -2.0},
                                             {.linear_term = -1.0 / 15.0, .constant_term = 35.0 / 15.0}}};
    a.rayleigh_density = (model_density_profile){{{.width = 0.0},
                                                {.exp_term = 1.0, .exp_scale = -1.0 / 8.0, .linear_term = -0.002,
                                                 .constant_term = 0.05}}};
    return a;
}

/* From `base`: *extras adds two extra species copying ozone (absorption, profile) and Rayleigh (scattering,
 * profile); *doubled has ozone and Rayleigh doubled instead. The medium is additive: the two are the same. */
static inline void test_extra_species_pair(const model_atmosphere *base, model_atmosphere *extras, model_atmosphere *doubled)
{
    *extras = *doubled = *base;
    extras->extra_count = 2;
    extras->extra[0] = (model_extra_species){.name = "ozone_copy", .density = base->ozone_density};
    extras->extra[1] = (model_extra_species){.name = "rayleigh_copy", .density = base->rayleigh_density};
    for (int c = 0; c < 3; ++c) {
        extras->extra[0].absorption[c] = base->ozone_absorption[c];
        extras->extra[1].scattering[c] = base->rayleigh_scattering[c];
        doubled->ozone_absorption[c] *= 2.0;
        doubled->rayleigh_scattering[c] *= 2.0;
    }
}
#endif
