/* Scene files (schema and rules in scene.h): read, parsed by cJSON, walked section by section onto the options with
 * the field readers of scene_validate.c. */
#include "app/scene/scene.h"
#include "app/cli/bad_value.h"
#include "app/scene/light.h"
#include "app/quality/quality.h"
#include "app/scene/scene_sun.h"
#include "app/scene/scene_spectral.h"
#include "app/cli/options_sunvis.h"
#include "app/scene/scene_validate.h"
#include "app/scene/exr_names.h"
#include "io/exr_meta.h"
#include <cjson/cJSON.h>
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define SCENE_MAX_BYTES (1 << 20)

/* The description of the scene loaded last: --dump-scene keeps it (a dump of mars.json still says what it is and
 * cites its sources). The options struct has no field for it; options_parse runs once per process. */
static char *loaded_description;

const char *scene_loaded_description(void) { return loaded_description; }


static int parse_planet(const scene_ctx *c, const cJSON *planet)
{
    static const char *const names[] = {"ground_radius_km", "atmosphere_top_km", "ground_albedo"};
    model_atmosphere *a = &c->o->atmosphere;
    if (scene_check_fields(c, planet, "planet", names, COUNT(names))) return 2;
    scene_range radius = scene_only_range(RADIUS_MIN, RADIUS_MAX);
    if (scene_get_number(c, planet, "ground_radius_km", "planet", radius, &a->bottom_radius) ||
        scene_get_number(c, planet, "atmosphere_top_km", "planet", radius, &a->top_radius) ||
        scene_get_array(c, planet, "ground_albedo", "planet", scene_flag_range("--ground-albedo", false), 3, c->o->ground_albedo, NULL))
        return 2;
    if (!(a->top_radius > a->bottom_radius)) {
        bool top_given = cJSON_GetObjectItemCaseSensitive(planet, "atmosphere_top_km") != NULL;
        return scene_fail(c, top_given ? "planet.atmosphere_top_km" : "planet.ground_radius_km",
                    "the atmosphere top (%g km) is not above the ground (%g km); expected atmosphere_top_km > "
                    "ground_radius_km", a->top_radius, a->bottom_radius);
    }
    return 0;
}

/* One Bruneton layer: {"width_km", "exp_term", "exp_scale_per_km", "linear_term_per_km", "constant_term"}. */
static int parse_layer(const scene_ctx *c, const cJSON *layer, const char *path, model_density_layer *out)
{
    static const char *const names[] = {"width_km", "exp_term", "exp_scale_per_km", "linear_term_per_km",
                                        "constant_term"};
    if (!cJSON_IsObject(layer)) return scene_fail(c, path, "expected an object, got %s", scene_type_of(layer));
    scene_range any = scene_only_range(-1000.0, 1000.0);
    return scene_check_fields(c, layer, path, names, COUNT(names)) ||
           scene_get_number(c, layer, "width_km", path, scene_only_range(0.0, HEIGHT_MAX), &out->width) ||
           scene_get_number(c, layer, "exp_term", path, any, &out->exp_term) ||
           scene_get_number(c, layer, "exp_scale_per_km", path, any, &out->exp_scale) ||
           scene_get_number(c, layer, "linear_term_per_km", path, any, &out->linear_term) ||
           scene_get_number(c, layer, "constant_term", path, any, &out->constant_term) ? 2 : 0;
}

/* density: {"profile": "exponential" | "tent" | "layers", ...its parameters}, for any species:
 *   exponential: scale_height_km (exp(-h/H));  tent: center_km, half_width_km;
 *   layers: [layer] or [layer 0, layer 1] (Bruneton's DensityProfileLayer pair; one layer applies everywhere).
 * Without "profile" the form follows from the parameters given. Parameters not given keep the current profile's
 * values when it has that form. */
static int parse_density(const scene_ctx *c, const cJSON *species, const char *parent, model_density_profile *out)
{
    static const char *const profiles[] = {"exponential", "tent", "layers"};
    static const char *const names[] = {"profile", "scale_height_km", "center_km", "half_width_km", "layers"};
    const cJSON *d;
    char path[PATH_LEN], p[PATH_LEN];
    if (scene_get_object(c, species, "density", parent, &d)) return 2;
    if (!d) return 0;
    scene_join(path, parent, "density");
    if (scene_check_fields(c, d, path, names, COUNT(names))) return 2;
    int form = -1;
    const cJSON *profile = scene_field(d, "profile", path, p);
    if (profile) {
        if (!cJSON_IsString(profile)) return scene_fail(c, p, "expected a string (exponential, tent or layers), got %s", scene_type_of(profile));
        for (int i = 0; i < COUNT(profiles); ++i)
            if (!strcmp(profile->valuestring, profiles[i])) form = i;
        if (form < 0) {
            char value[64];
            scene_printable(value, sizeof value, profile->valuestring);
            return scene_fail(c, p, "unknown profile '%s'; expected exponential, tent or layers", value);
        }
    } else {
        form = cJSON_GetObjectItemCaseSensitive(d, "layers") ? 2
             : (cJSON_GetObjectItemCaseSensitive(d, "center_km") || cJSON_GetObjectItemCaseSensitive(d, "half_width_km")) ? 1
             : cJSON_GetObjectItemCaseSensitive(d, "scale_height_km") ? 0 : -1;
        if (form < 0) return 0;
    }
    /* Fields of another form are an error, not silently ignored. */
    static const int owner[] = {-1, 0, 1, 1, 2};
    for (int i = 1; i < COUNT(names); ++i)
        if (owner[i] != form && cJSON_GetObjectItemCaseSensitive(d, names[i])) {
            scene_join(p, path, names[i]);
            static const char *const accepted[] = {"scale_height_km", "center_km, half_width_km", "layers"};
            return scene_fail(c, p, "not a parameter of the %s profile; it takes %s", profiles[form], accepted[form]);
        }
    scene_range h = scene_only_range(HEIGHT_MIN, HEIGHT_MAX);
    if (form == 0) {
        double H = 8.0;
        model_profile_as_exponential(out, &H);
        if (scene_get_number(c, d, "scale_height_km", path, h, &H)) return 2;
        *out = model_profile_exponential(H);
        return 0;
    }
    if (form == 1) {
        double center = 25.0, half_width = 15.0;
        model_profile_as_tent(out, &center, &half_width);
        if (scene_get_number(c, d, "center_km", path, scene_only_range(0.0, HEIGHT_MAX), &center) ||
            scene_get_number(c, d, "half_width_km", path, h, &half_width))
            return 2;
        *out = model_profile_tent(center, half_width);
        return 0;
    }
    const cJSON *layers = scene_field(d, "layers", path, p);
    int n = cJSON_IsArray(layers) ? cJSON_GetArraySize(layers) : -1;
    if (!layers) return scene_fail(c, p, "missing; the layers profile needs an array of 1 or 2 layer objects");
    if (n < 0) return scene_fail(c, p, "expected an array of 1 or 2 layer objects, got %s", scene_type_of(layers));
    if (n != 1 && n != 2) return scene_fail(c, p, "%d layers; expected 1 or 2 (Bruneton's layer pair)", n);
    model_density_profile result = {{{0}}};
    for (int i = 0; i < n; ++i) {
        char lp[PATH_LEN];
        if (snprintf(lp, sizeof lp, "%s[%d]", p, i) >= (int)sizeof lp) lp[sizeof lp - 1] = '\0';
        if (parse_layer(c, cJSON_GetArrayItem(layers, i), lp, &result.layers[i])) return 2;
    }
    if (n == 1) result.layers[1] = result.layers[0];
    *out = result;
    return 0;
}

/* A coefficient triple the model does not have: must be all zero. */
static int get_zero_triple(const scene_ctx *c, const cJSON *obj, const char *key, const char *parent, const char *why)
{
    double v[3] = {0, 0, 0};
    char p[PATH_LEN];
    if (scene_get_array(c, obj, key, parent, scene_only_range(0.0, COEFF_MAX), 3, v, NULL)) return 2;
    scene_join(p, parent, key);
    if (v[0] != 0 || v[1] != 0 || v[2] != 0) return scene_fail(c, p, "not supported (%s); expected [0, 0, 0]", why);
    return 0;
}

static int parse_species(const scene_ctx *c, const cJSON *species)
{
    static const char *const known[] = {"rayleigh", "mie", "ozone"};
    static const char *const rayleigh_names[] = {"scattering", "absorption", "density"};
    static const char *const mie_names[] = {"scattering", "absorption", "density", "phase"};
    static const char *const ozone_names[] = {"scattering", "absorption", "density"};
    static const char *const phase_names[] = {"model", "g"};
    model_atmosphere *a = &c->o->atmosphere;
    scene_range coeff = scene_only_range(0.0, COEFF_MAX);
    /* Any other name is an extra species (MODEL_MAX_EXTRA_SPECIES at most): a gas that absorbs and scatters
     * with the Rayleigh phase. The scene's list replaces the current one. */
    static const char *const extra_names[] = {"scattering", "absorption", "density"};
    int extras = 0;
    model_extra_species staged[MODEL_MAX_EXTRA_SPECIES];
    memset(staged, 0, sizeof staged);
    for (const cJSON *it = species->child; it; it = it->next) {
        char p[PATH_LEN];
        scene_join(p, "species", it->string);
        bool known_name = false;
        for (int i = 0; i < COUNT(known); ++i) known_name = known_name || !strcmp(it->string, known[i]);
        for (const cJSON *prev = species->child; prev != it; prev = prev->next)
            if (!strcmp(prev->string, it->string)) return scene_fail(c, p, "given twice; give each species once");
        if (!cJSON_IsObject(it)) return scene_fail(c, p, "expected an object, got %s", scene_type_of(it));
        if (known_name) continue;
        size_t len = strlen(it->string);
        bool valid = len > 0 && len < sizeof a->extra[0].name && islower((unsigned char)it->string[0]);
        for (size_t i = 0; i < len; ++i)
            valid = valid && (islower((unsigned char)it->string[i]) || isdigit((unsigned char)it->string[i]) ||
                              it->string[i] == '_');
        if (!valid)
            return scene_fail(c, p, "not a species name; an extra species is named with a-z, 0-9 and _ (starting with a "
                              "letter, %d characters at most)", (int)sizeof a->extra[0].name - 1);
        if (extras == MODEL_MAX_EXTRA_SPECIES)
            return scene_fail(c, p, "one species too many; vksky takes %d beyond rayleigh, mie and ozone",
                        MODEL_MAX_EXTRA_SPECIES);
        if (cJSON_GetObjectItemCaseSensitive(it, "phase"))
            return scene_fail(c, p, "an extra species scatters with the Rayleigh (molecular) phase and takes no phase; "
                              "put aerosols with a forward lobe in mie");
        model_extra_species e = {.density = model_profile_exponential(8.0)};
        memcpy(e.name, it->string, len + 1);
        if (scene_check_fields(c, it, p, extra_names, COUNT(extra_names)) ||
            scene_get_array(c, it, "scattering", p, coeff, 3, e.scattering, NULL) ||
            scene_get_array(c, it, "absorption", p, coeff, 3, e.absorption, NULL))
            return 2;
        if (!cJSON_GetObjectItemCaseSensitive(it, "density")) {
            char dp[PATH_LEN];
            scene_join(dp, p, "density");
            return scene_fail(c, dp, "missing; an extra species needs a density profile (exponential, tent or layers)");
        }
        if (parse_density(c, it, p, &e.density)) return 2;
        staged[extras++] = e;
    }
    a->extra_count = extras;
    memcpy(a->extra, staged, sizeof staged);
    const cJSON *s;
    if (scene_get_object(c, species, "rayleigh", "species", &s)) return 2;
    if (s && (scene_check_fields(c, s, "species.rayleigh", rayleigh_names, COUNT(rayleigh_names)) ||
              scene_get_array(c, s, "scattering", "species.rayleigh", coeff, 3, a->rayleigh_scattering, NULL) ||
              get_zero_triple(c, s, "absorption", "species.rayleigh",
                              "vksky's Rayleigh species only scatters; put absorption on mie or ozone") ||
              parse_density(c, s, "species.rayleigh", &a->rayleigh_density)))
        return 2;
    if (scene_get_object(c, species, "mie", "species", &s)) return 2;
    if (s) {
        const cJSON *phase;
        if (scene_check_fields(c, s, "species.mie", mie_names, COUNT(mie_names)) ||
            scene_get_array(c, s, "scattering", "species.mie", coeff, 3, a->mie_scattering, NULL) ||
            scene_get_array(c, s, "absorption", "species.mie", coeff, 3, a->mie_absorption, NULL) ||
            parse_density(c, s, "species.mie", &a->mie_density) ||
            scene_get_object(c, s, "phase", "species.mie", &phase))
            return 2;
        if (phase && (scene_check_fields(c, phase, "species.mie.phase", phase_names, COUNT(phase_names)) ||
                      scene_get_word(c, phase, "model", "species.mie.phase", phase_words, COUNT(phase_words),
                               &c->o->mie_phase) ||
                      scene_get_number(c, phase, "g", "species.mie.phase", scene_flag_range("--mie-g", false), &a->mie_g)))
            return 2;
    }
    if (scene_get_object(c, species, "ozone", "species", &s)) return 2;
    if (s && (scene_check_fields(c, s, "species.ozone", ozone_names, COUNT(ozone_names)) ||
              get_zero_triple(c, s, "scattering", "species.ozone",
                              "vksky's ozone only absorbs; put scattering on rayleigh or mie") ||
              scene_get_array(c, s, "absorption", "species.ozone", coeff, 3, a->ozone_absorption, NULL) ||
              parse_density(c, s, "species.ozone", &a->ozone_density)))
        return 2;
    return 0;
}

/* The sun's strength (issue 32, app/scene/light.h): "illuminance" [r, g, b] in the lesson's scale (20 = the real sun, read
 * as that fraction of the solar spectrum in photometric units: old files keep their meaning), "lux" (the illuminance
 * at the top of the atmosphere) or "spectrum_scale" (times the solar spectrum); at most one of them. */
static int parse_sun_strength(const scene_ctx *c, const cJSON *sun)
{
    options *o = c->o;
    int count = !!cJSON_GetObjectItemCaseSensitive(sun, "illuminance") + !!cJSON_GetObjectItemCaseSensitive(sun, "lux") +
                !!cJSON_GetObjectItemCaseSensitive(sun, "spectrum_scale");
    if (count > 1) return scene_fail(c, "sun", "illuminance, lux and spectrum_scale all set the sun's strength; "
                                               "expected at most one of them");
    double lux = -1.0, k = -1.0;
    scene_range range = scene_flag_range("--sun-lux", false);
    if (scene_get_number(c, sun, "lux", "sun", range, &lux) ||
        scene_get_number(c, sun, "spectrum_scale", "sun", scene_only_range(0.0, 1e3), &k))
        return 2;
    if (lux >= 0.0) light_set_sun_lux(o, lux);
    for (int i = 0; k >= 0.0 && i < 3; ++i) o->atmosphere.sun_illuminance[i] = k * LIGHT_RELATIVE_SUN;
    return 0;
}

static int parse_sun(const scene_ctx *c, const cJSON *sun)
{
    static const char *const names[] = {"elevation_deg", "azimuth_deg", "illuminance", "angular_radius_deg",
                                        "limb_darkening", "disc", "lux", "spectrum_scale", SCENE_SUN_PLACE_FIELDS};
    options *o = c->o;
    return scene_check_fields(c, sun, "sun", names, COUNT(names)) || scene_sun_parse(c->file, sun, o) ||
           parse_sun_strength(c, sun) ||
           scene_get_number(c, sun, "elevation_deg", "sun", scene_flag_range("--sun-elevation", false), &o->view.sun_elevation_deg) ||
           scene_get_number(c, sun, "azimuth_deg", "sun", scene_flag_range("--sun-azimuth", false), &o->view.sun_azimuth_deg) ||
           scene_get_array(c, sun, "illuminance", "sun", scene_flag_range("--sun-illuminance", false), 3,
                     o->atmosphere.sun_illuminance, NULL) ||
           scene_get_number(c, sun, "angular_radius_deg", "sun", scene_flag_range("--sun-angular-radius", false),
                      &o->sun_angular_radius_deg) ||
           scene_get_number(c, sun, "limb_darkening", "sun", scene_flag_range("--limb-darkening", false), &o->limb_darkening) ||
           scene_get_bool(c, sun, "disc", "sun", &o->sun_disc) ? 2 : 0;
}

static int parse_camera(const scene_ctx *c, const cJSON *cam)
{
    static const char *const names[] = {"altitude_km", "yaw_deg", "pitch_deg", "fov_deg"};
    sky_view *v = &c->o->view;
    return scene_check_fields(c, cam, "camera", names, COUNT(names)) ||
           scene_get_number(c, cam, "altitude_km", "camera", scene_flag_range("--altitude", false), &v->altitude_km) ||
           scene_get_number(c, cam, "yaw_deg", "camera", scene_flag_range("--yaw", false), &v->yaw_deg) ||
           scene_get_number(c, cam, "pitch_deg", "camera", scene_flag_range("--pitch", false), &v->pitch_deg) ||
           scene_get_number(c, cam, "fov_deg", "camera", scene_flag_range("--fov", false), &v->fov_deg) ? 2 : 0;
}

static int parse_output(const scene_ctx *c, const cJSON *out)
{
    static const char *const names[] = {"width", "height", "exposure_ev", "tonemap", "bloom", "exposure_ev100"};
    options *o = c->o;
    /* exposure_ev: the lesson's stops (--units relative; old files); exposure_ev100: photometric units' EV100, which
     * turns auto exposure off (app/scene/light.h). */
    double ev100 = NAN;
    if (scene_get_number(c, out, "exposure_ev100", "output", scene_flag_range("--exposure", false), &ev100)) return 2;
    if (!isnan(ev100)) o->exposure_ev100 = ev100, o->exposure_given = true;
    return scene_check_fields(c, out, "output", names, COUNT(names)) ||
           scene_get_int(c, out, "width", "output", scene_flag_range("--width", true), &o->width) ||
           scene_get_int(c, out, "height", "output", scene_flag_range("--height", true), &o->height) ||
           scene_get_number(c, out, "exposure_ev", "output", scene_flag_range("--exposure", false), &o->view.exposure_ev) ||
           scene_get_word(c, out, "tonemap", "output", tonemap_words, COUNT(tonemap_words), &o->view.tonemap) ||
           scene_get_bool(c, out, "bloom", "output", &o->view.bloom) ? 2 : 0;
}

static int get_size(const scene_ctx *c, const cJSON *q, const char *key, const char *flag, int *w, int *h)
{
    double v[2] = {*w, *h};
    if (scene_get_array(c, q, key, "quality", scene_flag_range(flag, true), 2, v, NULL)) return 2;
    *w = (int)v[0], *h = (int)v[1];
    return 0;
}

static int parse_quality(const scene_ctx *c, const cJSON *q)
{
    static const char *const names[] = {
        "preset", "sky_mode", "sky_pass", "steps", "max_steps", "steps_ramp_km", "step_distribution", "sample_offset",
        "skyview_lut", "skyview_steps", "transmittance_lut", "transmittance_steps", "multiscatter_lut",
        "multiscatter_directions", "multiscatter_steps", "lut_format", "render_scale", "bloom_mips", "bloom_res",
        "spectral"};
    options *o = c->o;
    sky_view *v = &o->view;
    sky_lut_quality *lut = &o->lut;
    if (scene_check_fields(c, q, "quality", names, COUNT(names))) return 2;
    o->scene_quality = true;
    /* The preset first: the knob fields override it. */
    int preset = -1;
    if (scene_get_word(c, q, "preset", "quality", preset_words, COUNT(preset_words), &preset)) return 2;
    if (preset >= 0) {
        const quality_config *qc = quality_preset(preset_words[preset]);
        quality_apply(qc, v, lut, &o->render_scale, &o->bloom_mips, &o->bloom_quarter);
        o->quality = preset_words[preset];   /* the word, as the flag keeps it (a preset may be another name's row) */
    }
    int mode = (int)v->mode, pass = (int)v->pass_kind, f32 = lut->lut_f32 ? 1 : 0, quarter = o->bloom_quarter ? 1 : 0;
    static const char *const bloom_res_words[] = {"half", "quarter"};   /* as --bloom-res */
    int dirs = lut->multiscatter_sqrt_dirs * lut->multiscatter_sqrt_dirs;
    scene_range max_steps = scene_flag_range("--max-steps", true);
    max_steps.min = 0;   /* 0: a fixed count (the dump writes it) */
    if (scene_get_word(c, q, "sky_mode", "quality", mode_words, COUNT(mode_words), &mode) ||
        scene_get_word(c, q, "sky_pass", "quality", pass_words, COUNT(pass_words), &pass) ||
        scene_get_int(c, q, "steps", "quality", scene_flag_range("--steps", true), &v->steps) ||
        scene_get_int(c, q, "max_steps", "quality", max_steps, &v->max_steps) ||
        scene_get_number(c, q, "steps_ramp_km", "quality", scene_flag_range("--steps-ramp", false), &v->steps_ramp_km) ||
        scene_get_number(c, q, "step_distribution", "quality", scene_flag_range("--step-distribution", false), &v->step_distribution) ||
        scene_get_number(c, q, "sample_offset", "quality", scene_flag_range("--sample-offset", false), &v->sample_offset) ||
        get_size(c, q, "skyview_lut", "--skyview-lut", &lut->skyview_width, &lut->skyview_height) ||
        scene_get_int(c, q, "skyview_steps", "quality", scene_flag_range("--skyview-steps", true), &v->skyview_steps) ||
        get_size(c, q, "transmittance_lut", "--transmittance-lut", &lut->transmittance_width, &lut->transmittance_height) ||
        scene_get_int(c, q, "transmittance_steps", "quality", scene_flag_range("--transmittance-steps", true), &lut->transmittance_steps) ||
        scene_get_int(c, q, "multiscatter_lut", "quality", scene_flag_range("--multiscatter-lut", true), &lut->multiscatter_size) ||
        scene_get_int(c, q, "multiscatter_directions", "quality", scene_flag_range("--multiscatter-dirs", true), &dirs) ||
        scene_get_int(c, q, "multiscatter_steps", "quality", scene_flag_range("--multiscatter-steps", true), &lut->multiscatter_steps) ||
        scene_get_word(c, q, "lut_format", "quality", lut_format_words, COUNT(lut_format_words), &f32) ||
        scene_get_number(c, q, "render_scale", "quality", scene_flag_range("--render-scale", false), &o->render_scale) ||
        scene_get_int(c, q, "bloom_mips", "quality", scene_flag_range("--bloom-mips", true), &o->bloom_mips) ||
        scene_get_word(c, q, "bloom_res", "quality", bloom_res_words, COUNT(bloom_res_words), &quarter) ||
        scene_get_int(c, q, "spectral", "quality", scene_flag_range("--spectral", true), &o->spectral))
        return 2;
    int root = (int)(sqrt((double)dirs) + 0.5);
    if (root * root != dirs)
        return scene_fail(c, "quality.multiscatter_directions",
                    "%d is not a perfect square; expected 1, 4, 9, ..., 4096 directions (as --multiscatter-dirs)", dirs);
    v->mode = (sky_mode_choice)mode;
    v->pass_kind = (sky_pass_kind)pass;
    lut->lut_f32 = f32 == 1;
    o->bloom_quarter = quarter == 1;
    lut->multiscatter_sqrt_dirs = root;
    if (v->max_steps != 0 && v->max_steps < v->steps)
        return scene_fail(c, cJSON_GetObjectItemCaseSensitive(q, "max_steps") ? "quality.max_steps" : "quality.steps",
                    "max_steps %d is below steps %d; expected max_steps >= steps, or max_steps 0 (a fixed count)",
                    v->max_steps, v->steps);
    return 0;
}

/* ---- loading ----------------------------------------------------------------------------------- */

static int read_all(const char *path, const char *shown, char **text, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(options_report_stream(), "vksky: --scene: cannot read '%s': %s\n", shown, strerror(errno));
        return 2;
    }
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap + 1);
    while (buf) {
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (n > SCENE_MAX_BYTES || got == 0) break;
        if (n == cap) {
            char *bigger = realloc(buf, 2 * cap + 1);
            if (!bigger) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = bigger, cap *= 2;
        }
    }
    int err = ferror(f) ? errno : 0;
    fclose(f);
    if (!buf) {
        fprintf(options_report_stream(), "vksky: --scene: cannot read '%s': out of memory\n", shown);
        return 2;
    }
    if (err) {
        fprintf(options_report_stream(), "vksky: --scene: cannot read '%s': %s\n", shown, strerror(err));
        free(buf);
        return 2;
    }
    if (n > SCENE_MAX_BYTES) {
        fprintf(options_report_stream(), "vksky: --scene: '%s' is larger than %d bytes; expected a scene (a small JSON file)\n", shown,
                SCENE_MAX_BYTES);
        free(buf);
        return 2;
    }
    buf[n] = '\0';
    *text = buf, *len = n;
    return 0;
}

static bool exr_file(const char *path)
{
    size_t n = strlen(path);
    return n >= 4 && !strcasecmp(path + n - 4, ".exr");
}

/* The scene an EXR made by vksky carries in its header (app/runs/exr_header.h): the effective scene of its render. */
static int read_exr_scene(const char *path, const char *shown, char **text, size_t *len)
{
    char err[512];
    int rc = io_exr_read_string_attr(path, EXR_HEADER_SCENE, text, err, sizeof err);
    if (rc < 0) fprintf(options_report_stream(), "vksky: --scene: %s\n", err);
    if (rc > 0) fprintf(options_report_stream(), "vksky: --scene: '%s' has no '%s' attribute; expected an EXR written by vksky (or a "
                                "scene .json file)\n", shown, EXR_HEADER_SCENE);
    if (rc != 0) return 2;
    *len = strlen(*text);
    if (*len > SCENE_MAX_BYTES) {
        fprintf(options_report_stream(), "vksky: --scene: '%s' carries a scene larger than %d bytes; expected a scene (a small JSON "
                        "text)\n", shown, SCENE_MAX_BYTES);
        free(*text);
        *text = NULL;
        return 2;
    }
    return 0;
}

/* The units an EXR made by vksky was rendered in (its "vksky:units", app/scene/light.c's text): --scene OUT.exr
 * renders in them again (a --units flag still overrides: flags come after the scene). A file without the attribute
 * keeps the default; one with a value vksky does not write is refused. */
static int read_exr_units(const char *path, const char *shown, options *o)
{
    char err[512], *units = NULL;
    int rc = io_exr_read_string_attr(path, EXR_HEADER_UNITS, &units, err, sizeof err);
    if (rc > 0) return 0;
    if (rc < 0) {
        fprintf(options_report_stream(), "vksky: --scene: %s\n", err);
        return 2;
    }
    if (!strncmp(units, "relative", 8)) o->units = OPTIONS_UNITS_RELATIVE;
    else if (!strncmp(units, "cd/m2", 5)) o->units = OPTIONS_UNITS_PHOTOMETRIC;
    else rc = 2;
    if (rc) fprintf(options_report_stream(), "vksky: --scene: '%s': unknown %s '%.40s'; expected 'relative ...' or 'cd/m2 ...'\n",
                    shown, EXR_HEADER_UNITS, units);
    free(units);
    return rc;
}

static bool blank(char ch)
{
    return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\n';
}

/* 1-based line and column (in characters: UTF-8 continuation bytes do not count) of byte offset `at`. */
static void line_column(const char *text, size_t at, int *line, int *column)
{
    *line = 1, *column = 1;
    for (size_t i = 0; i < at; ++i) {
        if (text[i] == '\n') ++*line, *column = 1;
        else if (((unsigned char)text[i] & 0xC0) != 0x80) ++*column;
    }
}

static int syntax_error(const scene_ctx *c, const char *text, size_t len, const char *why_at)
{
    size_t at = why_at && why_at >= text && why_at <= text + len ? (size_t)(why_at - text) : len;
    int line, column;
    line_column(text, at, &line, &column);
    bool at_end = true;
    for (size_t i = at; i < len; ++i) at_end = at_end && blank(text[i]);
    if (at < len && text[at] == '\0') {
        fprintf(options_report_stream(), "vksky: %s:%d:%d: a NUL byte; expected JSON text\n", c->file, line, column);
        return 2;
    }
    if (at_end) {
        fprintf(options_report_stream(), "vksky: %s:%d:%d: syntax error: unexpected end of the file (an unclosed object, array or "
                        "string?); expected a JSON object\n", c->file, line, column);
        return 2;
    }
    /* The line the parser stopped in (from its first non-blank character), to show where. */
    size_t start = at;
    while (start > 0 && text[start - 1] != '\n') --start;
    while (start < at && blank(text[start])) ++start;
    char near[48], shown[48];
    size_t k = 0;
    for (size_t i = start; i < len && text[i] != '\n' && text[i] != '\r' && k + 1 < sizeof near; ++i) near[k++] = text[i];
    near[k] = '\0';
    scene_printable(shown, sizeof shown, near);
    fprintf(options_report_stream(), "vksky: %s:%d:%d: syntax error near '%s'; expected JSON (no comments, no trailing commas, "
                    "strings in double quotes)\n", c->file, line, column, shown);
    return 2;
}

int scene_load(const char *path, options *o)
{
    static const char *const names[] = {"description", "planet", "species", "multiple_scattering", "sun", "camera",
                                        "output", "quality", "sun_visibility", "spectral"};
    scene_ctx c = {.o = o};
    scene_printable(c.file, sizeof c.file, path);
    char *text = NULL;
    size_t len = 0;
    if (exr_file(path) ? read_exr_scene(path, c.file, &text, &len) : read_all(path, c.file, &text, &len)) return 2;
    if (exr_file(path) && read_exr_units(path, c.file, o)) {
        free(text);
        return 2;
    }
    int rc = 2;
    cJSON *root = NULL;
    size_t first = 0;
    while (first < len && blank(text[first])) ++first;
    const char *nul = memchr(text, '\0', len);
    if (first == len) {
        fprintf(options_report_stream(), "vksky: %s: empty file; expected a JSON object (see scenes/README.md)\n", c.file);
        goto done;
    }
    if (nul) {
        rc = syntax_error(&c, text, len, nul);
        goto done;
    }
    /* The length includes the terminating NUL: cJSON's "nothing after the value" check looks for it. */
    root = cJSON_ParseWithLengthOpts(text, len + 1, NULL, true);
    if (!root) {
        rc = syntax_error(&c, text, len, cJSON_GetErrorPtr());
        goto done;
    }
    if (!cJSON_IsObject(root)) {
        fprintf(options_report_stream(), "vksky: %s: the top level is %s; expected a JSON object {...} (see scenes/README.md)\n",
                c.file, scene_type_of(root));
        goto done;
    }
    const cJSON *description = cJSON_GetObjectItemCaseSensitive(root, "description");
    if (scene_check_fields(&c, root, "", names, COUNT(names))) goto done;
    if (description && !cJSON_IsString(description)) {
        scene_fail(&c, "description", "expected a string, got %s", scene_type_of(description));
        goto done;
    }
    free(loaded_description);
    loaded_description = description ? strdup(description->valuestring) : NULL;
    const cJSON *section;
    if (scene_get_object(&c, root, "planet", "", &section) || (section && parse_planet(&c, section))) goto done;
    if (scene_get_object(&c, root, "species", "", &section) || (section && parse_species(&c, section))) goto done;
    if (scene_get_object(&c, root, "spectral", "", &section) || (section && scene_spectral_parse(&c, section)))
        goto done;   /* after species and planet: columns become coefficients through their profiles */
    if (scene_get_bool(&c, root, "multiple_scattering", "", &o->multiple_scattering)) goto done;
    if (scene_get_word(&c, root, "sun_visibility", "", sunvis_words, SUNVIS_WORD_COUNT, &o->atmosphere.sun_visibility))
        goto done;
    if (scene_get_object(&c, root, "sun", "", &section) || (section && parse_sun(&c, section))) goto done;
    if (scene_get_object(&c, root, "camera", "", &section) || (section && parse_camera(&c, section))) goto done;
    if (scene_get_object(&c, root, "output", "", &section) || (section && parse_output(&c, section))) goto done;
    if (scene_get_object(&c, root, "quality", "", &section) || (section && parse_quality(&c, section))) goto done;
    rc = 0;
done:
    cJSON_Delete(root);
    free(text);
    return rc;
}
