#include "sky/atmosphere.h"
#include "model/fnv1a.h"
#include <stddef.h>
#include <string.h>

sky_lut_quality sky_lut_quality_default(void)
{
    return (sky_lut_quality){.transmittance_width = 256, .transmittance_height = 64, .transmittance_steps = 40,
                             .multiscatter_size = 32, .multiscatter_steps = 20, .multiscatter_sqrt_dirs = 8,
                             .lut_f32 = false, .skyview_width = 192, .skyview_height = 108};
}

sky_features sky_features_default(void)
{
    return (sky_features){.mie_phase = VKSKY_MIE_PHASE_HG, .limb_darkening = 0.6, .sun_disc = true,
                          .multiple_scattering = true};
}

_Static_assert(VKSKY_MAX_EXTRA == MODEL_MAX_EXTRA_SPECIES, "one limit on extra species for the GPU and the reference");
_Static_assert(VKSKY_SUN_VISIBILITY_PENUMBRA == MODEL_SUN_VISIBILITY_PENUMBRA &&
                   VKSKY_SUN_VISIBILITY_LESSON_FADE == MODEL_SUN_VISIBILITY_LESSON_FADE,
               "one numbering of the sun visibility models");

static bool any3(const double v[3]) { return v[0] != 0.0 || v[1] != 0.0 || v[2] != 0.0; }

/* Extra species the shaders must evaluate: those with a nonzero coefficient (the rest are compiled out). The
 * scene loader keeps them in order; a zero one in the middle still counts, to keep the indices. */
static int extra_count(const model_atmosphere *a)
{
    int n = 0;
    for (int i = 0; i < a->extra_count && i < VKSKY_MAX_EXTRA; ++i)
        if (any3(a->extra[i].scattering) || any3(a->extra[i].absorption)) n = i + 1;
    return n;
}

/* The cheapest exact form of a profile the shaders have (VKSKY_PROFILE_*). */
static int32_t profile_kind(const model_density_profile *p)
{
    double H;
    if (model_profile_as_exponential(p, &H)) return VKSKY_PROFILE_EXPONENTIAL;
    if (p->layers[0].exp_term == 0.0 && p->layers[1].exp_term == 0.0) return VKSKY_PROFILE_LINEAR;
    return VKSKY_PROFILE_GENERAL;
}

sky_variant sky_variant_of(const model_atmosphere *a, const sky_features *f)
{
    int extras = extra_count(a);
    return (sky_variant){
        .rayleigh = any3(a->rayleigh_scattering),
        .mie = any3(a->mie_scattering) || any3(a->mie_absorption),
        .ozone = any3(a->ozone_absorption),
        .multiscatter = f->multiple_scattering,
        .sun_disc = f->sun_disc,
        .ground = any3(f->ground_albedo),
        .mie_phase = f->mie_phase,
        .profile = {profile_kind(&a->rayleigh_density), profile_kind(&a->mie_density),
                    profile_kind(&a->ozone_density)},
        .extra_species = extras,
        .extra_profile = {extras > 0 ? profile_kind(&a->extra[0].density) : VKSKY_PROFILE_GENERAL,
                          extras > 1 ? profile_kind(&a->extra[1].density) : VKSKY_PROFILE_GENERAL},
        .sun_visibility = a->sun_visibility == MODEL_SUN_VISIBILITY_LESSON_FADE ? VKSKY_SUN_VISIBILITY_LESSON_FADE
                                                                               : VKSKY_SUN_VISIBILITY_PENUMBRA,
        .spectral4 = f->spectral4,
    };
}

static vksky_vec4 v4(const double rgb[3], double w)
{
    return (vksky_vec4){(float)rgb[0], (float)rgb[1], (float)rgb[2], (float)w};
}

void sky_atmosphere_pack(const model_atmosphere *a, double sun_angular_radius_rad, sky_lut_quality q,
                         const sky_features *f, AtmosphereParams *out)
{
    memset(out, 0, sizeof *out);
    /* Rt - Rb in double: the shaders never subtract planet-scale radii themselves. */
    out->radii = (vksky_vec4){(float)a->bottom_radius, (float)a->top_radius,
                              (float)(a->top_radius - a->bottom_radius), 0.0f};
    out->rayleigh_scattering = v4(a->rayleigh_scattering, 0.0);
    out->mie_scattering = v4(a->mie_scattering, 0.0);
    out->mie_absorption = v4(a->mie_absorption, a->mie_g);
    out->ozone_absorption = v4(a->ozone_absorption, 0.0);
    const model_density_profile *profiles[VKSKY_SPECIES] = {&a->rayleigh_density, &a->mie_density, &a->ozone_density};
    float widths[8] = {0};
    int species = 3 + extra_count(a);
    for (int i = 0; i < species - 3; ++i) {
        out->extra_scattering[i] = v4(a->extra[i].scattering, 0.0);
        out->extra_absorption[i] = v4(a->extra[i].absorption, 0.0);
        profiles[3 + i] = &a->extra[i].density;
    }
    for (int s = 0; s < species; ++s) {
        widths[s] = (float)profiles[s]->layers[0].width;
        for (int l = 0; l < 2; ++l) {
            const model_density_layer *d = &profiles[s]->layers[l];
            out->profiles[2 * s + l] = (vksky_vec4){(float)d->exp_term, (float)d->exp_scale, (float)d->linear_term,
                                                    (float)d->constant_term};
        }
    }
    out->profile_widths[0] = (vksky_vec4){widths[0], widths[1], widths[2], widths[3]};
    out->profile_widths[1] = (vksky_vec4){widths[4], widths[5], widths[6], widths[7]};
    out->sun = v4(a->sun_illuminance, sun_angular_radius_rad);
    out->lut_steps = (vksky_vec4){(float)q.transmittance_steps, (float)q.multiscatter_steps,
                                  (float)q.multiscatter_sqrt_dirs, f->multiple_scattering ? 1.0f : 0.0f};
    out->ground = v4(f->ground_albedo, f->limb_darkening);
    out->sun_disc = (vksky_vec4){f->sun_disc_power ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f};
    if (f->spectral4) {
        /* SPECTRAL4: every .w is the fourth wavelength's; the scalars the RGB block keeps there move to scalars4. */
        const sky_fourth *w = &f->fourth;
        out->scalars4 = (vksky_vec4){(float)a->mie_g, (float)sun_angular_radius_rad, (float)f->limb_darkening, 1.0f};
        out->rayleigh_scattering.w = (float)w->rayleigh_scattering;
        out->mie_scattering.w = (float)w->mie_scattering;
        out->mie_absorption.w = (float)w->mie_absorption;
        out->ozone_absorption.w = (float)w->ozone_absorption;
        for (int i = 0; i < species - 3; ++i) {
            out->extra_scattering[i].w = (float)w->extra_scattering[i];
            out->extra_absorption[i].w = (float)w->extra_absorption[i];
        }
        out->sun.w = (float)w->sun_illuminance;
        out->ground.w = (float)w->ground_albedo;
    }
}

uint64_t sky_atmosphere_lut_hash(const AtmosphereParams *p, int sun_visibility)
{
    /* Everything but the sun's illuminance and limb (the LUTs are per unit illuminance) and, for the lesson's model
     * (isotropic phase), the Mie g; the ground albedo counts (the multi-scattering ground bounce), and so does the
     * sun's size (the penumbra's width; the visibility model itself is a pipeline variant, rebuilt with them). The
     * penumbra's MS LUT scatters its first bounce with the real phases: g counts there. */
    bool real_phase = sun_visibility != VKSKY_SUN_VISIBILITY_LESSON_FADE;
    const vksky_vec4 fields[] = {p->radii, p->rayleigh_scattering, p->mie_scattering,
                                 {p->mie_absorption.x, p->mie_absorption.y, p->mie_absorption.z, 0},
                                 p->ozone_absorption, p->lut_steps, {p->ground.x, p->ground.y, p->ground.z, 0},
                                 /* the ground-irradiance LUT marches the sky with the Mie phase */
                                 {p->ground.x + p->ground.y + p->ground.z > 0.0f || real_phase ? p->mie_absorption.w : 0.0f, 0, 0, 0},
                                 {p->sun.w, 0, 0, 0}};
    uint64_t h = MODEL_FNV1A_OFFSET;
    h = model_fnv1a(h, fields, sizeof fields);
    h = model_fnv1a(h, p->extra_scattering, sizeof p->extra_scattering);
    h = model_fnv1a(h, p->extra_absorption, sizeof p->extra_absorption);
    h = model_fnv1a(h, p->profile_widths, sizeof p->profile_widths);
    if (p->scalars4.w != 0.0f) {
        /* SPECTRAL4 (scalars4 set): the fourth wavelength's coefficients and albedo count, and g and the sun's size
         * from their new places (the extras' .w are hashed with the arrays above). */
        const float fourth[] = {p->rayleigh_scattering.w, p->mie_scattering.w, p->mie_absorption.w,
                                p->ozone_absorption.w, p->ground.w, p->scalars4.x, p->scalars4.y};
        h = model_fnv1a(h, fourth, sizeof fourth);
    }
    return model_fnv1a(h, p->profiles, sizeof p->profiles);
}
