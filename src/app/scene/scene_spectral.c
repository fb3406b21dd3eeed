/* The scene file's "spectral" section (scene_spectral.h). */
#include "app/scene/scene_spectral.h"

#include <math.h>
#include <string.h>

/* The integral of a density profile over the atmosphere's height, km (midpoint rule, 10 m steps). */
static double column_km(const model_atmosphere *a, const model_density_profile *p)
{
    double top = a->top_radius - a->bottom_radius, dz = 0.01, s = 0.0;
    for (double z = 0.5 * dz; z < top; z += dz)
        s += model_density(p, z) * dz;
    return s;
}

static int law_word(const scene_ctx *c, const cJSON *obj, const char *path, const char *const *words, int count,
                    int *out)
{
    *out = -1;
    if (!cJSON_GetObjectItemCaseSensitive(obj, "law")) return scene_fail(c, path, "missing \"law\"");
    return scene_get_word(c, obj, "law", path, words, count, out);
}

static int parse_rayleigh(const scene_ctx *c, const cJSON *s, spectral_law *out)
{
    static const char *const names[] = {"law", "air_density"}, *const laws[] = {"bodhaine", "rgb"};
    const char *path = "spectral.rayleigh";
    int law;
    if (scene_check_fields(c, s, path, names, COUNT(names)) || law_word(c, s, path, laws, COUNT(laws), &law)) return 2;
    if (law == 1) {
        *out = (spectral_law){.kind = SPECTRAL_LAW_RGB};
        memcpy(out->rgb, c->o->atmosphere.rayleigh_scattering, sizeof out->rgb);
        return 0;
    }
    double d = 1.0;
    if (scene_get_number(c, s, "air_density", path, scene_only_range(0.0, 1000.0), &d)) return 2;
    *out = (spectral_law){.kind = SPECTRAL_LAW_RAYLEIGH, .scale = d};
    return 0;
}

static int parse_mie(const scene_ctx *c, const cJSON *s, spectral_medium *m)
{
    static const char *const names[] = {"law", "exponent", "optical_depth_500", "single_scattering_albedo",
                                        "scattering_550_per_km", "absorption_550_per_km"};
    static const char *const laws[] = {"angstrom"};
    const char *path = "spectral.mie";
    int law;
    double alpha = 1.3, tau = -1.0, ssa = 0.9, sc = -1.0, ab = 0.0;
    if (scene_check_fields(c, s, path, names, COUNT(names)) || law_word(c, s, path, laws, COUNT(laws), &law) ||
        scene_get_number(c, s, "exponent", path, scene_only_range(-4.0, 4.0), &alpha) ||
        scene_get_number(c, s, "optical_depth_500", path, scene_only_range(0.0, 100.0), &tau) ||
        scene_get_number(c, s, "single_scattering_albedo", path, scene_only_range(0.0, 1.0), &ssa) ||
        scene_get_number(c, s, "scattering_550_per_km", path, scene_only_range(0.0, COEFF_MAX), &sc) ||
        scene_get_number(c, s, "absorption_550_per_km", path, scene_only_range(0.0, COEFF_MAX), &ab))
        return 2;
    if ((tau >= 0.0) == (sc >= 0.0))
        return scene_fail(c, path, "give either optical_depth_500 (with single_scattering_albedo) or "
                                   "scattering_550_per_km (with absorption_550_per_km)");
    if (tau >= 0.0) {
        double col = column_km(&c->o->atmosphere, &c->o->atmosphere.mie_density);
        if (!(col > 0.0)) return scene_fail(c, "spectral.mie.optical_depth_500", "the mie density profile is empty");
        double ext550 = tau / col * pow(550.0 / 500.0, -alpha);
        sc = ssa * ext550;
        ab = (1.0 - ssa) * ext550;
    }
    m->mie_scattering = (spectral_law){.kind = SPECTRAL_LAW_ANGSTROM, .value_550 = sc, .exponent = alpha};
    m->mie_absorption = (spectral_law){.kind = SPECTRAL_LAW_ANGSTROM, .value_550 = ab, .exponent = alpha};
    return 0;
}

static int parse_ozone(const scene_ctx *c, const cJSON *s, spectral_law *out)
{
    static const char *const names[] = {"law", "column_du", "number_density_per_m3"}, *const laws[] = {"cross-section"};
    const char *path = "spectral.ozone";
    int law;
    double du = -1.0, n = -1.0;
    if (scene_check_fields(c, s, path, names, COUNT(names)) || law_word(c, s, path, laws, COUNT(laws), &law) ||
        scene_get_number(c, s, "column_du", path, scene_only_range(0.0, 10000.0), &du) ||
        scene_get_number(c, s, "number_density_per_m3", path, scene_only_range(0.0, 1e22), &n))
        return 2;
    if ((du >= 0.0) == (n >= 0.0)) return scene_fail(c, path, "give either column_du or number_density_per_m3");
    if (du >= 0.0) {
        double col = column_km(&c->o->atmosphere, &c->o->atmosphere.ozone_density) * 1e3; /* m */
        if (!(col > 0.0)) return scene_fail(c, "spectral.ozone.column_du", "the ozone density profile is empty");
        n = du * 2.6867e20 / col;
    }
    *out = (spectral_law){.kind = SPECTRAL_LAW_OZONE, .scale = n};
    return 0;
}

int scene_spectral_parse(const scene_ctx *c, const cJSON *spectral)
{
    static const char *const names[] = {"rayleigh", "mie", "ozone"};
    spectral_medium m;
    spectral_medium_from_rgb(&c->o->atmosphere, &m);
    const cJSON *s;
    if (scene_check_fields(c, spectral, "spectral", names, COUNT(names))) return 2;
    if (scene_get_object(c, spectral, "rayleigh", "spectral", &s) ||
        (s && parse_rayleigh(c, s, &m.rayleigh_scattering)))
        return 2;
    if (scene_get_object(c, spectral, "mie", "spectral", &s) || (s && parse_mie(c, s, &m)))
        return 2;
    if (scene_get_object(c, spectral, "ozone", "spectral", &s) || (s && parse_ozone(c, s, &m.ozone_absorption)))
        return 2;
    c->o->spectral_medium = m;
    c->o->spectral_medium_set = true;
    return 0;
}

/* --dump-scene: the laws as they stand, in the forms that load back exactly (number density, per-km values). */
bool scene_spectral_dump(cJSON *root, const options *o)
{
    if (!o->spectral_medium_set) return true;
    const spectral_medium *m = &o->spectral_medium;
    cJSON *s = cJSON_AddObjectToObject(root, "spectral"), *j;
    bool ok = s != NULL;
    if (ok && m->rayleigh_scattering.kind == SPECTRAL_LAW_RAYLEIGH) {
        ok = (j = cJSON_AddObjectToObject(s, "rayleigh")) && cJSON_AddStringToObject(j, "law", "bodhaine") &&
             cJSON_AddNumberToObject(j, "air_density", m->rayleigh_scattering.scale);
    } else if (ok) {
        ok = (j = cJSON_AddObjectToObject(s, "rayleigh")) && cJSON_AddStringToObject(j, "law", "rgb");
    }
    if (ok && m->mie_scattering.kind == SPECTRAL_LAW_ANGSTROM && m->mie_absorption.kind == SPECTRAL_LAW_ANGSTROM &&
        m->mie_scattering.exponent == m->mie_absorption.exponent)
        ok = (j = cJSON_AddObjectToObject(s, "mie")) && cJSON_AddStringToObject(j, "law", "angstrom") &&
             cJSON_AddNumberToObject(j, "exponent", m->mie_scattering.exponent) &&
             cJSON_AddNumberToObject(j, "scattering_550_per_km", m->mie_scattering.value_550) &&
             cJSON_AddNumberToObject(j, "absorption_550_per_km", m->mie_absorption.value_550);
    if (ok && m->ozone_absorption.kind == SPECTRAL_LAW_OZONE)
        ok = (j = cJSON_AddObjectToObject(s, "ozone")) && cJSON_AddStringToObject(j, "law", "cross-section") &&
             cJSON_AddNumberToObject(j, "number_density_per_m3", m->ozone_absorption.scale);
    return ok;
}
