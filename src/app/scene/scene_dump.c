/* Scene files: --dump-scene, the effective options written back as a scene (the schema in scene.h). */
#include "app/scene/scene_dump.h"
#include "app/cli/bad_value.h"
#include "app/scene/scene_sun.h"
#include "app/scene/scene_spectral.h"
#include "app/scene/scene.h"
#include "app/cli/options_sunvis.h"
#include "app/scene/scene_validate.h"
#include <cjson/cJSON.h>
#include <errno.h>
#include <string.h>

/* ---- dump -------------------------------------------------------------------------------------- */

typedef struct builder {
    bool ok;
} builder;

static cJSON *obj(builder *b, cJSON *parent, const char *key)
{
    cJSON *j = cJSON_AddObjectToObject(parent, key);
    b->ok = b->ok && j;
    return j;
}

static void num(builder *b, cJSON *parent, const char *key, double v)
{
    b->ok = b->ok && cJSON_AddNumberToObject(parent, key, v);
}

static void str(builder *b, cJSON *parent, const char *key, const char *s)
{
    b->ok = b->ok && cJSON_AddStringToObject(parent, key, s);
}

static void boolean(builder *b, cJSON *parent, const char *key, bool v)
{
    b->ok = b->ok && cJSON_AddBoolToObject(parent, key, v);
}

static void arr(builder *b, cJSON *parent, const char *key, const double *v, int n)
{
    cJSON *a = cJSON_CreateDoubleArray(v, n);
    b->ok = b->ok && a && cJSON_AddItemToObject(parent, key, a);
    if (a && !b->ok) cJSON_Delete(a);
}

/* The simplest form that is exactly the profile and that loads back: exponential, tent, or the two layers. A layers
 * profile can be an exponential or a tent whose parameter is outside that form's range (one exponential layer with
 * exp_scale_per_km -124 is a 0.008 km scale height, below HEIGHT_MIN): it stays layers (found by fuzz_scene). */
static void dump_density(builder *b, cJSON *species, const model_density_profile *p)
{
    cJSON *d = obj(b, species, "density");
    double x, y;
    if (!d) return;
    if (model_profile_as_exponential(p, &x) && x >= HEIGHT_MIN && x <= HEIGHT_MAX) {
        str(b, d, "profile", "exponential");
        num(b, d, "scale_height_km", x);
    } else if (model_profile_as_tent(p, &x, &y) && x >= 0.0 && x <= HEIGHT_MAX && y >= HEIGHT_MIN && y <= HEIGHT_MAX) {
        str(b, d, "profile", "tent");
        num(b, d, "center_km", x);
        num(b, d, "half_width_km", y);
    } else {
        str(b, d, "profile", "layers");
        cJSON *layers = cJSON_AddArrayToObject(d, "layers");
        b->ok = b->ok && layers;
        for (int i = 0; i < 2 && layers; ++i) {
            cJSON *l = cJSON_CreateObject();
            b->ok = b->ok && l && cJSON_AddItemToArray(layers, l);
            if (!l) break;
            const model_density_layer *q = &p->layers[i];
            num(b, l, "width_km", q->width);
            num(b, l, "exp_term", q->exp_term);
            num(b, l, "exp_scale_per_km", q->exp_scale);
            num(b, l, "linear_term_per_km", q->linear_term);
            num(b, l, "constant_term", q->constant_term);
        }
    }
}

static const char *word(const char *const *words, int count, int i)
{
    return i >= 0 && i < count ? words[i] : words[0];
}

int scene_dump(const options *o, FILE *out)
{
    const model_atmosphere *a = &o->atmosphere;
    const sky_view *v = &o->view;
    const sky_lut_quality *lut = &o->lut;
    builder b = {.ok = true};
    cJSON *root = cJSON_CreateObject();
    if (!root) return 1;
    char description[160];
    snprintf(description, sizeof description, "vksky %s --dump-scene: the effective scene (defaults, then the "
             "command-line flags)", VKSKY_VERSION);
    str(&b, root, "description", o->scene_path && scene_loaded_description() ? scene_loaded_description() : description);

    cJSON *planet = obj(&b, root, "planet");
    num(&b, planet, "ground_radius_km", a->bottom_radius);
    num(&b, planet, "atmosphere_top_km", a->top_radius);
    arr(&b, planet, "ground_albedo", o->ground_albedo, 3);

    static const double zero[3] = {0, 0, 0};
    cJSON *species = obj(&b, root, "species"), *s, *d;
    s = obj(&b, species, "rayleigh");
    arr(&b, s, "scattering", a->rayleigh_scattering, 3);
    arr(&b, s, "absorption", zero, 3);
    dump_density(&b, s, &a->rayleigh_density);
    s = obj(&b, species, "mie");
    arr(&b, s, "scattering", a->mie_scattering, 3);
    arr(&b, s, "absorption", a->mie_absorption, 3);
    dump_density(&b, s, &a->mie_density);
    d = obj(&b, s, "phase");
    str(&b, d, "model", word(phase_words, COUNT(phase_words), o->mie_phase));
    num(&b, d, "g", a->mie_g);
    s = obj(&b, species, "ozone");
    arr(&b, s, "scattering", zero, 3);
    arr(&b, s, "absorption", a->ozone_absorption, 3);
    dump_density(&b, s, &a->ozone_density);
    for (int i = 0; i < a->extra_count; ++i) {
        s = obj(&b, species, a->extra[i].name);
        arr(&b, s, "scattering", a->extra[i].scattering, 3);
        arr(&b, s, "absorption", a->extra[i].absorption, 3);
        dump_density(&b, s, &a->extra[i].density);
    }

    b.ok = b.ok && scene_spectral_dump(root, o);   /* the medium per wavelength (issue 32), when given */
    boolean(&b, root, "multiple_scattering", o->multiple_scattering);
    str(&b, root, "sun_visibility", sunvis_name(a->sun_visibility));

    cJSON *sun = obj(&b, root, "sun");
    if (!scene_sun_by_place(o)) {   /* else the date and place give them (scene_sun_dump) */
        num(&b, sun, "elevation_deg", v->sun_elevation_deg);
        num(&b, sun, "azimuth_deg", v->sun_azimuth_deg);
    }
    b.ok = b.ok && scene_sun_dump(sun, o);
    arr(&b, sun, "illuminance", a->sun_illuminance, 3);
    num(&b, sun, "angular_radius_deg", o->sun_angular_radius_deg);
    num(&b, sun, "limb_darkening", o->limb_darkening);
    boolean(&b, sun, "disc", o->sun_disc);

    cJSON *cam = obj(&b, root, "camera");
    num(&b, cam, "altitude_km", v->altitude_km);
    num(&b, cam, "yaw_deg", v->yaw_deg);
    num(&b, cam, "pitch_deg", v->pitch_deg);
    num(&b, cam, "fov_deg", v->fov_deg);

    cJSON *output = obj(&b, root, "output");
    num(&b, output, "width", o->width);
    num(&b, output, "height", o->height);
    /* Once photometric units hold EV100 (given or metered) in the view, the lesson's stops are kept apart. */
    num(&b, output, "exposure_ev", v->ev100 ? o->exposure_stops : v->exposure_ev);
    if (o->units == OPTIONS_UNITS_PHOTOMETRIC && o->exposure_given) num(&b, output, "exposure_ev100", o->exposure_ev100);
    str(&b, output, "tonemap", word(tonemap_words, COUNT(tonemap_words), v->tonemap));
    boolean(&b, output, "bloom", v->bloom);

    cJSON *q = obj(&b, root, "quality");
    if (o->quality) str(&b, q, "preset", o->quality);   /* then every knob, so the preset changes nothing on load */
    str(&b, q, "sky_mode", word(mode_words, COUNT(mode_words), (int)v->mode));
    str(&b, q, "sky_pass", word(pass_words, COUNT(pass_words), (int)v->pass_kind));
    num(&b, q, "steps", v->steps);
    num(&b, q, "max_steps", v->max_steps);
    num(&b, q, "steps_ramp_km", v->steps_ramp_km);
    num(&b, q, "step_distribution", v->step_distribution);
    num(&b, q, "sample_offset", v->sample_offset);
    double size[2] = {lut->skyview_width, lut->skyview_height};
    arr(&b, q, "skyview_lut", size, 2);
    num(&b, q, "skyview_steps", v->skyview_steps);
    size[0] = lut->transmittance_width, size[1] = lut->transmittance_height;
    arr(&b, q, "transmittance_lut", size, 2);
    num(&b, q, "transmittance_steps", lut->transmittance_steps);
    num(&b, q, "multiscatter_lut", lut->multiscatter_size);
    num(&b, q, "multiscatter_directions", lut->multiscatter_sqrt_dirs * lut->multiscatter_sqrt_dirs);
    num(&b, q, "multiscatter_steps", lut->multiscatter_steps);
    str(&b, q, "lut_format", lut->lut_f32 ? "f32" : "f16");
    num(&b, q, "render_scale", o->render_scale);
    num(&b, q, "bloom_mips", o->bloom_mips);
    str(&b, q, "bloom_res", o->bloom_quarter ? "quarter" : "half");
    if (o->spectral > 0) num(&b, q, "spectral", o->spectral);   /* --spectral's (or --quality auto's) wavelengths */

    char *text = b.ok ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    if (!text) {
        fprintf(options_report_stream(), "vksky: --dump-scene: out of memory\n");
        return 1;
    }
    int rc = fputs(text, out) < 0 || fputc('\n', out) == EOF || fflush(out) != 0 ? 1 : 0;
    if (rc) fprintf(options_report_stream(), "vksky: --dump-scene: cannot write the scene: %s\n", strerror(errno));
    cJSON_free(text);
    return rc;
}

