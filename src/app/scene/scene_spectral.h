/* The scene file's "spectral" section (issue 32): the medium per wavelength for the spectral reference.
 *   "spectral": {
 *     "rayleigh": {"law": "bodhaine", "air_density": 1}            Bodhaine et al. 1999 x sea-level air density
 *               | {"law": "rgb"},                                   (default: from species.rayleigh's RGB)
 *     "mie":      {"law": "angstrom", "exponent": 1.3,
 *                  "optical_depth_500": 0.084, "single_scattering_albedo": 0.93}   the column's depth at 500 nm
 *               | {"law": "angstrom", "exponent": 1.3, "scattering_550_per_km": x, "absorption_550_per_km": y},
 *     "ozone":    {"law": "cross-section", "column_du": 343.8}        the column in Dobson units (1 DU = 2.6867e20
 *               | {"law": "cross-section", "number_density_per_m3": n}   molecules m^-2), or the peak density
 *   }
 * Species not named keep the laws spectral_medium_from_rgb makes of their RGB coefficients. Columns are turned
 * into coefficients through the species' density profiles, so the section is read after "species". The RGB
 * coefficients stay what the GPU renders. */
#ifndef VKSKY_APP_SCENE_SPECTRAL_H
#define VKSKY_APP_SCENE_SPECTRAL_H
#include "app/scene/scene_validate.h"

/* 0: read onto c->o->spectral_medium (spectral_medium_set); 2: bad input (one line on stderr). */
int scene_spectral_parse(const scene_ctx *c, const cJSON *spectral);
/* --dump-scene: adds the "spectral" section to root when the scene gave one (true: ok, false: out of memory). A law
 * made from RGB coefficients (spectral_medium_from_rgb) that has no scene form is left to be made again on load. */
bool scene_spectral_dump(cJSON *root, const options *o);
#endif
