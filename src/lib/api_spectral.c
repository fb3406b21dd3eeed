/* Spectral groups as scene values (include/vksky.h, "Spectral frames"): the packing and the colour weights of the
 * command line's --spectral N, over the spectral medium (model/spectral_medium.h) and the reference's bins and
 * weights (reference/spectral.h), so that a host renders each group as an ordinary frame and sums the readbacks. */
#include "lib/lib_internal.h"
#include "model/spectrum.h"
#include "reference/spectral.h"
#include <string.h>

uint32_t vksky_spectral_group_count(uint32_t wavelengths, uint32_t per_pass)
{
    if (wavelengths < VKSKY_SPECTRAL_MIN || wavelengths > VKSKY_SPECTRAL_MAX || (per_pass != 3 && per_pass != 4))
        return 0;
    return (wavelengths + per_pass - 1) / per_pass;
}

/* The ground's albedo at a wavelength: the RGB law (680, 550, 440 nm, linear between), as the spectral reference's
 * irradiance takes it. */
static double albedo_at(const options *o, double nm)
{
    spectral_law law = {.kind = SPECTRAL_LAW_RGB};
    memcpy(law.rgb, o->ground_albedo, sizeof law.rgb);
    return spectral_law_eval(&law, nm);
}

vksky_result vksky_scene_spectral_group(const vksky_scene *scene, uint32_t wavelengths, uint32_t per_pass,
                                        uint32_t group, vksky_scene **group_scene, double xyz_weights[4][3],
                                        double nm[4])
{
    if (group_scene) *group_scene = NULL;
    uint32_t groups = vksky_spectral_group_count(wavelengths, per_pass);
    if (!scene || !group_scene || !xyz_weights || groups == 0 || group >= groups || scene->group.per_pass)
        return VKSKY_ERROR_INVALID_ARGUMENT;
    const options *o = &scene->o;
    ref_spectral s;
    ref_spectral_init(&s, &o->atmosphere, (int)wavelengths);   /* the scene's RGB medium as laws of the wavelength */
    if (o->spectral_medium_set) s.medium = o->spectral_medium; /* or the scene file's "spectral" section */
    lib_spectral_group g = {.per_pass = per_pass};
    int n = (int)wavelengths, idx[4];
    double at[4], one[3] = {1.0, 1.0, 1.0};
    /* Bins per_pass * group + c; a channel past the last bin repeats it with weight 0 (the GPU still renders it). */
    for (uint32_t c = 0; c < 4; ++c) {
        int i = (int)(per_pass * group + c);
        bool real = c < per_pass && i < n;
        idx[c] = i < n ? i : n - 1;
        at[c] = ref_spectral_nm(n, idx[c]);
        double w[3] = {0.0, 0.0, 0.0};
        if (real) ref_spectral_weights(n, idx[c], w);
        /* Per unit of the channel's image, whose sun is the scene's sun luminance: the solar spectrum's own
         * illuminance divided out, so the sum is the solar spectrum's colour at the configured sun's luminance. */
        double toa = spectrum_solar_illuminance_toa();
        for (int k = 0; k < 3; ++k) xyz_weights[c][k] = w[k] / toa;
        if (nm) nm[c] = c < per_pass ? at[c] : 0.0;
        g.ground_albedo[c] = albedo_at(o, at[c]);
    }
    spectral_medium_pack(&s.medium, &o->atmosphere, at, one, &g.medium);
    if (per_pass == 4) {
        spectral_coefficients k;
        spectral_medium_eval(&s.medium, at[3], &k);
        g.fourth = (sky_fourth){.rayleigh_scattering = k.rayleigh_scattering, .mie_scattering = k.mie_scattering,
                                .mie_absorption = k.mie_absorption, .ozone_absorption = k.ozone_absorption};
        for (int e = 0; e < VKSKY_MAX_EXTRA && e < MODEL_MAX_EXTRA_SPECIES; ++e)
            g.fourth.extra_scattering[e] = k.extra_scattering[e], g.fourth.extra_absorption[e] = k.extra_absorption[e];
    } else {
        g.ground_albedo[3] = 0.0;
    }
    vksky_result res = vksky_scene_copy(scene, group_scene);
    if (res != VKSKY_SUCCESS) return res;
    (*group_scene)->group = g;
    return VKSKY_SUCCESS;
}

vksky_result vksky_scene_spectral_coefficients(const vksky_scene *scene, uint32_t channel,
                                               vksky_spectral_coefficients *out)
{
    if (!scene || !out || !scene->group.per_pass || channel >= scene->group.per_pass)
        return VKSKY_ERROR_INVALID_ARGUMENT;
    const lib_spectral_group *g = &scene->group;
    if (channel < 3) {
        const model_atmosphere *a = &g->medium;
        *out = (vksky_spectral_coefficients){.rayleigh_scattering = a->rayleigh_scattering[channel],
                                             .mie_scattering = a->mie_scattering[channel],
                                             .mie_absorption = a->mie_absorption[channel],
                                             .ozone_absorption = a->ozone_absorption[channel],
                                             .ground_albedo = g->ground_albedo[channel]};
    } else {
        *out = (vksky_spectral_coefficients){.rayleigh_scattering = g->fourth.rayleigh_scattering,
                                             .mie_scattering = g->fourth.mie_scattering,
                                             .mie_absorption = g->fourth.mie_absorption,
                                             .ozone_absorption = g->fourth.ozone_absorption,
                                             .ground_albedo = g->ground_albedo[3]};
    }
    return VKSKY_SUCCESS;
}

void vksky_spectral_xyz_to_rec709(const double xyz[3], double rgb[3]) { spectrum_xyz_to_rec709(xyz, rgb); }
