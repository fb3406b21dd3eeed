/* Scene files (schema and rules in scene.h): read, parsed by cJSON, validated field by field onto the options. */
#include "app/scene.h"
#include "app/quality.h"
#include "app/scene_sun.h"
#include <cjson/cJSON.h>
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#define SCENE_MAX_BYTES (1 << 20)
#define PATH_LEN 160

/* Ranges of the fields that have no command-line flag. */
#define RADIUS_MIN 1.0
#define RADIUS_MAX 1e6
#define COEFF_MAX 1000.0
#define HEIGHT_MIN 0.01
#define HEIGHT_MAX 1000.0

typedef struct range {
    double min, max;
    bool integer;
    const char *flag;   /* the flag the range comes from (NULL: a scene-only field) */
} range;

typedef struct ctx {
    char file[PATH_LEN];   /* printable copy of the file name, for messages */
    options *o;
} ctx;

static const char *const tonemap_words[] = {"clamp", "reinhard", "aces"};          /* VKSKY_TONEMAP_* order */
static const char *const mode_words[] = {"march", "skyview", "auto", "fill"};       /* sky_mode_choice order */
static const char *const pass_words[] = {"fragment", "compute", "auto"};            /* sky_pass_kind order */
static const char *const lut_format_words[] = {"f16", "f32"};
static const char *const phase_words[] = {"henyey-greenstein", "cornette-shanks"};  /* options.mie_phase */
static const char *const preset_words[] = {"low", "medium", "high", "ultra"};
#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* The description of the scene loaded last: --dump-scene keeps it (a dump of mars.json still says what it is and
 * cites its sources). The options struct has no field for it; options_parse runs once per process. */
static char *loaded_description;

/* A printable, bounded copy (control characters -> '?'): messages stay one line whatever the file holds. */
static void printable(char *dst, size_t n, const char *src)
{
    size_t k = 0;
    for (; src && *src && k + 1 < n; ++src) dst[k++] = (unsigned char)*src < 0x20 || *src == 0x7f ? '?' : *src;
    dst[k] = '\0';
}

static void join(char *out, const char *parent, const char *key)
{
    char k[64];
    printable(k, sizeof k, key);
    /* Long paths are cut; the return value is checked only to say so to the compiler. */
    if (snprintf(out, PATH_LEN, "%s%s%s", parent, parent[0] ? "." : "", k) >= PATH_LEN) out[PATH_LEN - 1] = '\0';
}

__attribute__((format(printf, 3, 4))) static int fail(const ctx *c, const char *path, const char *fmt, ...)
{
    char msg[640];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fprintf(stderr, "vksky: %s: %s: %s\n", c->file, path, msg);
    return 2;
}

static const char *type_of(const cJSON *j)
{
    if (cJSON_IsNumber(j)) return "a number";
    if (cJSON_IsString(j)) return "a string";
    if (cJSON_IsBool(j)) return "a boolean";
    if (cJSON_IsNull(j)) return "null";
    if (cJSON_IsArray(j)) return "an array";
    if (cJSON_IsObject(j)) return "an object";
    return "an invalid value";
}

static void word_list(char *out, size_t n, const char *const *words, int count, const char *last_sep)
{
    size_t k = 0;
    out[0] = '\0';
    for (int i = 0; i < count && k < n; ++i)
        k += (size_t)snprintf(out + k, n - k, "%s%s", words[i], i + 2 < count ? ", " : i + 1 < count ? last_sep : "");
}

static range flag_range(const char *flag, bool integer)
{
    range r = {0, 0, integer, flag};
    if (!options_flag_range(flag, &r.min, &r.max)) {
        fprintf(stderr, "vksky: internal error: no range for %s in the flag table\n", flag);
        abort();
    }
    return r;
}

static range scene_range(double min, double max)
{
    return (range){min, max, false, NULL};
}

/* Unknown and repeated fields of an object. */
static int check_fields(const ctx *c, const cJSON *obj, const char *path, const char *const *names, int count)
{
    for (const cJSON *it = obj->child; it; it = it->next) {
        char p[PATH_LEN];
        join(p, path, it->string);
        bool known = false;
        for (int i = 0; i < count; ++i) known = known || !strcmp(it->string, names[i]);
        if (!known) {
            char list[512];
            word_list(list, sizeof list, names, count, ", ");
            return fail(c, p, "unknown field; accepted: %s", list);
        }
        for (const cJSON *prev = obj->child; prev != it; prev = prev->next)
            if (!strcmp(prev->string, it->string)) return fail(c, p, "given twice; give each field once");
    }
    return 0;
}

/* Field `key` of `obj` (NULL if absent); its path in *path. */
static const cJSON *field(const cJSON *obj, const char *key, const char *parent, char *path)
{
    join(path, parent, key);
    return obj ? cJSON_GetObjectItemCaseSensitive(obj, key) : NULL;
}

static int get_object(const ctx *c, const cJSON *obj, const char *key, const char *parent, const cJSON **out)
{
    char p[PATH_LEN];
    const cJSON *j = field(obj, key, parent, p);
    *out = NULL;
    if (!j) return 0;
    if (!cJSON_IsObject(j)) return fail(c, p, "expected an object, got %s", type_of(j));
    *out = j;
    return 0;
}

static int check_number(const ctx *c, const cJSON *j, const char *path, range r, double *out)
{
    const char *what = r.integer ? "an integer" : "a number";
    char as[48] = "";
    if (r.flag) snprintf(as, sizeof as, " (as %s)", r.flag);
    if (!cJSON_IsNumber(j)) return fail(c, path, "expected %s, got %s", what, type_of(j));
    double v = j->valuedouble;
    if (!isfinite(v)) return fail(c, path, "not a finite number; expected %s in [%g, %g]%s", what, r.min, r.max, as);
    if (r.integer && v != floor(v))
        return fail(c, path, "%.10g is not an integer; expected an integer in [%g, %g]%s", v, r.min, r.max, as);
    if (v < r.min || v > r.max)
        return fail(c, path, "%.10g is out of range; expected %s in [%g, %g]%s", v, what, r.min, r.max, as);
    *out = v;
    return 0;
}

static int get_number(const ctx *c, const cJSON *obj, const char *key, const char *parent, range r, double *out)
{
    char p[PATH_LEN];
    const cJSON *j = field(obj, key, parent, p);
    return j ? check_number(c, j, p, r, out) : 0;
}

static int get_int(const ctx *c, const cJSON *obj, const char *key, const char *parent, range r, int *out)
{
    double v = *out;
    r.integer = true;
    if (get_number(c, obj, key, parent, r, &v)) return 2;
    *out = (int)v;
    return 0;
}

/* An array of exactly n numbers in r; *given tells whether the field was there. */
static int get_array(const ctx *c, const cJSON *obj, const char *key, const char *parent, range r, int n, double *out,
                     bool *given)
{
    char p[PATH_LEN];
    const cJSON *j = field(obj, key, parent, p);
    if (given) *given = j != NULL;
    if (!j) return 0;
    const char *what = r.integer ? "integers" : "numbers";
    if (!cJSON_IsArray(j)) return fail(c, p, "expected an array of %d %s, got %s", n, what, type_of(j));
    if (cJSON_GetArraySize(j) != n)
        return fail(c, p, "expected %d %s, got %d", n, what, cJSON_GetArraySize(j));
    double v[4];
    int i = 0;
    for (const cJSON *e = j->child; e; e = e->next, ++i) {
        char pe[PATH_LEN + 16];
        snprintf(pe, sizeof pe, "%s[%d]", p, i);
        if (check_number(c, e, pe, r, &v[i])) return 2;
    }
    memcpy(out, v, (size_t)n * sizeof *out);
    return 0;
}

static int get_bool(const ctx *c, const cJSON *obj, const char *key, const char *parent, bool *out)
{
    char p[PATH_LEN];
    const cJSON *j = field(obj, key, parent, p);
    if (!j) return 0;
    if (!cJSON_IsBool(j)) return fail(c, p, "expected true or false, got %s", type_of(j));
    *out = cJSON_IsTrue(j);
    return 0;
}

static int get_word(const ctx *c, const cJSON *obj, const char *key, const char *parent, const char *const *words,
                    int count, int *out)
{
    char p[PATH_LEN], list[256], value[64];
    const cJSON *j = field(obj, key, parent, p);
    if (!j) return 0;
    word_list(list, sizeof list, words, count, " or ");
    if (!cJSON_IsString(j)) return fail(c, p, "expected a string (%s), got %s", list, type_of(j));
    for (int i = 0; i < count; ++i)
        if (!strcmp(j->valuestring, words[i])) {
            *out = i;
            return 0;
        }
    printable(value, sizeof value, j->valuestring);
    return fail(c, p, "unknown value '%s'; expected %s", value, list);
}

/* ---- sections ---------------------------------------------------------------------------------- */

static int parse_planet(const ctx *c, const cJSON *planet)
{
    static const char *const names[] = {"ground_radius_km", "atmosphere_top_km", "ground_albedo"};
    model_atmosphere *a = &c->o->atmosphere;
    if (check_fields(c, planet, "planet", names, COUNT(names))) return 2;
    range radius = scene_range(RADIUS_MIN, RADIUS_MAX);
    if (get_number(c, planet, "ground_radius_km", "planet", radius, &a->bottom_radius) ||
        get_number(c, planet, "atmosphere_top_km", "planet", radius, &a->top_radius) ||
        get_array(c, planet, "ground_albedo", "planet", flag_range("--ground-albedo", false), 3, c->o->ground_albedo, NULL))
        return 2;
    if (!(a->top_radius > a->bottom_radius)) {
        bool top_given = cJSON_GetObjectItemCaseSensitive(planet, "atmosphere_top_km") != NULL;
        return fail(c, top_given ? "planet.atmosphere_top_km" : "planet.ground_radius_km",
                    "the atmosphere top (%g km) is not above the ground (%g km); expected atmosphere_top_km > "
                    "ground_radius_km", a->top_radius, a->bottom_radius);
    }
    return 0;
}

/* One Bruneton layer: {"width_km", "exp_term", "exp_scale_per_km", "linear_term_per_km", "constant_term"}. */
static int parse_layer(const ctx *c, const cJSON *layer, const char *path, model_density_layer *out)
{
    static const char *const names[] = {"width_km", "exp_term", "exp_scale_per_km", "linear_term_per_km",
                                        "constant_term"};
    if (!cJSON_IsObject(layer)) return fail(c, path, "expected an object, got %s", type_of(layer));
    range any = scene_range(-1000.0, 1000.0);
    return check_fields(c, layer, path, names, COUNT(names)) ||
           get_number(c, layer, "width_km", path, scene_range(0.0, HEIGHT_MAX), &out->width) ||
           get_number(c, layer, "exp_term", path, any, &out->exp_term) ||
           get_number(c, layer, "exp_scale_per_km", path, any, &out->exp_scale) ||
           get_number(c, layer, "linear_term_per_km", path, any, &out->linear_term) ||
           get_number(c, layer, "constant_term", path, any, &out->constant_term) ? 2 : 0;
}

/* density: {"profile": "exponential" | "tent" | "layers", ...its parameters}, for any species:
 *   exponential: scale_height_km (exp(-h/H));  tent: center_km, half_width_km;
 *   layers: [layer] or [layer 0, layer 1] (Bruneton's DensityProfileLayer pair; one layer applies everywhere).
 * Without "profile" the form follows from the parameters given. Parameters not given keep the current profile's
 * values when it has that form. */
static int parse_density(const ctx *c, const cJSON *species, const char *parent, model_density_profile *out)
{
    static const char *const profiles[] = {"exponential", "tent", "layers"};
    static const char *const names[] = {"profile", "scale_height_km", "center_km", "half_width_km", "layers"};
    const cJSON *d;
    char path[PATH_LEN], p[PATH_LEN];
    if (get_object(c, species, "density", parent, &d)) return 2;
    if (!d) return 0;
    join(path, parent, "density");
    if (check_fields(c, d, path, names, COUNT(names))) return 2;
    int form = -1;
    const cJSON *profile = field(d, "profile", path, p);
    if (profile) {
        if (!cJSON_IsString(profile)) return fail(c, p, "expected a string (exponential, tent or layers), got %s", type_of(profile));
        for (int i = 0; i < COUNT(profiles); ++i)
            if (!strcmp(profile->valuestring, profiles[i])) form = i;
        if (form < 0) {
            char value[64];
            printable(value, sizeof value, profile->valuestring);
            return fail(c, p, "unknown profile '%s'; expected exponential, tent or layers", value);
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
            join(p, path, names[i]);
            static const char *const accepted[] = {"scale_height_km", "center_km, half_width_km", "layers"};
            return fail(c, p, "not a parameter of the %s profile; it takes %s", profiles[form], accepted[form]);
        }
    range h = scene_range(HEIGHT_MIN, HEIGHT_MAX);
    if (form == 0) {
        double H = 8.0;
        model_profile_as_exponential(out, &H);
        if (get_number(c, d, "scale_height_km", path, h, &H)) return 2;
        *out = model_profile_exponential(H);
        return 0;
    }
    if (form == 1) {
        double center = 25.0, half_width = 15.0;
        model_profile_as_tent(out, &center, &half_width);
        if (get_number(c, d, "center_km", path, scene_range(0.0, HEIGHT_MAX), &center) ||
            get_number(c, d, "half_width_km", path, h, &half_width))
            return 2;
        *out = model_profile_tent(center, half_width);
        return 0;
    }
    const cJSON *layers = field(d, "layers", path, p);
    int n = cJSON_IsArray(layers) ? cJSON_GetArraySize(layers) : -1;
    if (!layers) return fail(c, p, "missing; the layers profile needs an array of 1 or 2 layer objects");
    if (n < 0) return fail(c, p, "expected an array of 1 or 2 layer objects, got %s", type_of(layers));
    if (n != 1 && n != 2) return fail(c, p, "%d layers; expected 1 or 2 (Bruneton's layer pair)", n);
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
static int get_zero_triple(const ctx *c, const cJSON *obj, const char *key, const char *parent, const char *why)
{
    double v[3] = {0, 0, 0};
    char p[PATH_LEN];
    if (get_array(c, obj, key, parent, scene_range(0.0, COEFF_MAX), 3, v, NULL)) return 2;
    join(p, parent, key);
    if (v[0] != 0 || v[1] != 0 || v[2] != 0) return fail(c, p, "not supported (%s); expected [0, 0, 0]", why);
    return 0;
}

static int parse_species(const ctx *c, const cJSON *species)
{
    static const char *const known[] = {"rayleigh", "mie", "ozone"};
    static const char *const rayleigh_names[] = {"scattering", "absorption", "density"};
    static const char *const mie_names[] = {"scattering", "absorption", "density", "phase"};
    static const char *const ozone_names[] = {"scattering", "absorption", "density"};
    static const char *const phase_names[] = {"model", "g"};
    model_atmosphere *a = &c->o->atmosphere;
    range coeff = scene_range(0.0, COEFF_MAX);
    /* Any other name is an extra species (MODEL_MAX_EXTRA_SPECIES at most): a gas that absorbs and scatters
     * with the Rayleigh phase. The scene's list replaces the current one. */
    static const char *const extra_names[] = {"scattering", "absorption", "density"};
    int extras = 0;
    model_extra_species staged[MODEL_MAX_EXTRA_SPECIES];
    memset(staged, 0, sizeof staged);
    for (const cJSON *it = species->child; it; it = it->next) {
        char p[PATH_LEN];
        join(p, "species", it->string);
        bool known_name = false;
        for (int i = 0; i < COUNT(known); ++i) known_name = known_name || !strcmp(it->string, known[i]);
        for (const cJSON *prev = species->child; prev != it; prev = prev->next)
            if (!strcmp(prev->string, it->string)) return fail(c, p, "given twice; give each species once");
        if (!cJSON_IsObject(it)) return fail(c, p, "expected an object, got %s", type_of(it));
        if (known_name) continue;
        size_t len = strlen(it->string);
        bool valid = len > 0 && len < sizeof a->extra[0].name && islower((unsigned char)it->string[0]);
        for (size_t i = 0; i < len; ++i)
            valid = valid && (islower((unsigned char)it->string[i]) || isdigit((unsigned char)it->string[i]) ||
                              it->string[i] == '_');
        if (!valid)
            return fail(c, p, "not a species name; an extra species is named with a-z, 0-9 and _ (starting with a "
                              "letter, %d characters at most)", (int)sizeof a->extra[0].name - 1);
        if (extras == MODEL_MAX_EXTRA_SPECIES)
            return fail(c, p, "one species too many; vksky takes %d beyond rayleigh, mie and ozone",
                        MODEL_MAX_EXTRA_SPECIES);
        if (cJSON_GetObjectItemCaseSensitive(it, "phase"))
            return fail(c, p, "an extra species scatters with the Rayleigh (molecular) phase and takes no phase; "
                              "put aerosols with a forward lobe in mie");
        model_extra_species e = {.density = model_profile_exponential(8.0)};
        memcpy(e.name, it->string, len + 1);
        if (check_fields(c, it, p, extra_names, COUNT(extra_names)) ||
            get_array(c, it, "scattering", p, coeff, 3, e.scattering, NULL) ||
            get_array(c, it, "absorption", p, coeff, 3, e.absorption, NULL))
            return 2;
        if (!cJSON_GetObjectItemCaseSensitive(it, "density")) {
            char dp[PATH_LEN];
            join(dp, p, "density");
            return fail(c, dp, "missing; an extra species needs a density profile (exponential, tent or layers)");
        }
        if (parse_density(c, it, p, &e.density)) return 2;
        staged[extras++] = e;
    }
    a->extra_count = extras;
    memcpy(a->extra, staged, sizeof staged);
    const cJSON *s;
    if (get_object(c, species, "rayleigh", "species", &s)) return 2;
    if (s && (check_fields(c, s, "species.rayleigh", rayleigh_names, COUNT(rayleigh_names)) ||
              get_array(c, s, "scattering", "species.rayleigh", coeff, 3, a->rayleigh_scattering, NULL) ||
              get_zero_triple(c, s, "absorption", "species.rayleigh",
                              "vksky's Rayleigh species only scatters; put absorption on mie or ozone") ||
              parse_density(c, s, "species.rayleigh", &a->rayleigh_density)))
        return 2;
    if (get_object(c, species, "mie", "species", &s)) return 2;
    if (s) {
        const cJSON *phase;
        if (check_fields(c, s, "species.mie", mie_names, COUNT(mie_names)) ||
            get_array(c, s, "scattering", "species.mie", coeff, 3, a->mie_scattering, NULL) ||
            get_array(c, s, "absorption", "species.mie", coeff, 3, a->mie_absorption, NULL) ||
            parse_density(c, s, "species.mie", &a->mie_density) ||
            get_object(c, s, "phase", "species.mie", &phase))
            return 2;
        if (phase && (check_fields(c, phase, "species.mie.phase", phase_names, COUNT(phase_names)) ||
                      get_word(c, phase, "model", "species.mie.phase", phase_words, COUNT(phase_words),
                               &c->o->mie_phase) ||
                      get_number(c, phase, "g", "species.mie.phase", flag_range("--mie-g", false), &a->mie_g)))
            return 2;
    }
    if (get_object(c, species, "ozone", "species", &s)) return 2;
    if (s && (check_fields(c, s, "species.ozone", ozone_names, COUNT(ozone_names)) ||
              get_zero_triple(c, s, "scattering", "species.ozone",
                              "vksky's ozone only absorbs; put scattering on rayleigh or mie") ||
              get_array(c, s, "absorption", "species.ozone", coeff, 3, a->ozone_absorption, NULL) ||
              parse_density(c, s, "species.ozone", &a->ozone_density)))
        return 2;
    return 0;
}

static int parse_sun(const ctx *c, const cJSON *sun)
{
    static const char *const names[] = {"elevation_deg", "azimuth_deg", "illuminance", "angular_radius_deg",
                                        "limb_darkening", "disc", SCENE_SUN_PLACE_FIELDS};
    options *o = c->o;
    return check_fields(c, sun, "sun", names, COUNT(names)) || scene_sun_parse(c->file, sun, o) ||
           get_number(c, sun, "elevation_deg", "sun", flag_range("--sun-elevation", false), &o->view.sun_elevation_deg) ||
           get_number(c, sun, "azimuth_deg", "sun", flag_range("--sun-azimuth", false), &o->view.sun_azimuth_deg) ||
           get_array(c, sun, "illuminance", "sun", flag_range("--sun-illuminance", false), 3,
                     o->atmosphere.sun_illuminance, NULL) ||
           get_number(c, sun, "angular_radius_deg", "sun", flag_range("--sun-angular-radius", false),
                      &o->sun_angular_radius_deg) ||
           get_number(c, sun, "limb_darkening", "sun", flag_range("--limb-darkening", false), &o->limb_darkening) ||
           get_bool(c, sun, "disc", "sun", &o->sun_disc) ? 2 : 0;
}

static int parse_camera(const ctx *c, const cJSON *cam)
{
    static const char *const names[] = {"altitude_km", "yaw_deg", "pitch_deg", "fov_deg"};
    sky_view *v = &c->o->view;
    return check_fields(c, cam, "camera", names, COUNT(names)) ||
           get_number(c, cam, "altitude_km", "camera", flag_range("--altitude", false), &v->altitude_km) ||
           get_number(c, cam, "yaw_deg", "camera", flag_range("--yaw", false), &v->yaw_deg) ||
           get_number(c, cam, "pitch_deg", "camera", flag_range("--pitch", false), &v->pitch_deg) ||
           get_number(c, cam, "fov_deg", "camera", flag_range("--fov", false), &v->fov_deg) ? 2 : 0;
}

static int parse_output(const ctx *c, const cJSON *out)
{
    static const char *const names[] = {"width", "height", "exposure_ev", "tonemap", "bloom"};
    options *o = c->o;
    return check_fields(c, out, "output", names, COUNT(names)) ||
           get_int(c, out, "width", "output", flag_range("--width", true), &o->width) ||
           get_int(c, out, "height", "output", flag_range("--height", true), &o->height) ||
           get_number(c, out, "exposure_ev", "output", flag_range("--exposure", false), &o->view.exposure_ev) ||
           get_word(c, out, "tonemap", "output", tonemap_words, COUNT(tonemap_words), &o->view.tonemap) ||
           get_bool(c, out, "bloom", "output", &o->view.bloom) ? 2 : 0;
}

static int get_size(const ctx *c, const cJSON *q, const char *key, const char *flag, int *w, int *h)
{
    double v[2] = {*w, *h};
    if (get_array(c, q, key, "quality", flag_range(flag, true), 2, v, NULL)) return 2;
    *w = (int)v[0], *h = (int)v[1];
    return 0;
}

static int parse_quality(const ctx *c, const cJSON *q)
{
    static const char *const names[] = {
        "preset", "sky_mode", "sky_pass", "steps", "max_steps", "steps_ramp_km", "step_distribution", "sample_offset",
        "skyview_lut", "skyview_steps", "transmittance_lut", "transmittance_steps", "multiscatter_lut",
        "multiscatter_directions", "multiscatter_steps", "lut_format", "render_scale", "bloom_mips"};
    options *o = c->o;
    sky_view *v = &o->view;
    sky_lut_quality *lut = &o->lut;
    if (check_fields(c, q, "quality", names, COUNT(names))) return 2;
    /* The preset first: the knob fields override it. */
    int preset = -1;
    if (get_word(c, q, "preset", "quality", preset_words, COUNT(preset_words), &preset)) return 2;
    if (preset >= 0) {
        const quality_config *qc = quality_preset(preset_words[preset]);
        quality_apply(qc, v, lut, &o->render_scale, &o->bloom_mips);
        o->quality = qc->name;
    }
    int mode = (int)v->mode, pass = (int)v->pass_kind, f32 = lut->lut_f32 ? 1 : 0;
    int dirs = lut->multiscatter_sqrt_dirs * lut->multiscatter_sqrt_dirs;
    range max_steps = flag_range("--max-steps", true);
    max_steps.min = 0;   /* 0: a fixed count (the dump writes it) */
    if (get_word(c, q, "sky_mode", "quality", mode_words, COUNT(mode_words), &mode) ||
        get_word(c, q, "sky_pass", "quality", pass_words, COUNT(pass_words), &pass) ||
        get_int(c, q, "steps", "quality", flag_range("--steps", true), &v->steps) ||
        get_int(c, q, "max_steps", "quality", max_steps, &v->max_steps) ||
        get_number(c, q, "steps_ramp_km", "quality", flag_range("--steps-ramp", false), &v->steps_ramp_km) ||
        get_number(c, q, "step_distribution", "quality", flag_range("--step-distribution", false), &v->step_distribution) ||
        get_number(c, q, "sample_offset", "quality", flag_range("--sample-offset", false), &v->sample_offset) ||
        get_size(c, q, "skyview_lut", "--skyview-lut", &lut->skyview_width, &lut->skyview_height) ||
        get_int(c, q, "skyview_steps", "quality", flag_range("--skyview-steps", true), &v->skyview_steps) ||
        get_size(c, q, "transmittance_lut", "--transmittance-lut", &lut->transmittance_width, &lut->transmittance_height) ||
        get_int(c, q, "transmittance_steps", "quality", flag_range("--transmittance-steps", true), &lut->transmittance_steps) ||
        get_int(c, q, "multiscatter_lut", "quality", flag_range("--multiscatter-lut", true), &lut->multiscatter_size) ||
        get_int(c, q, "multiscatter_directions", "quality", flag_range("--multiscatter-dirs", true), &dirs) ||
        get_int(c, q, "multiscatter_steps", "quality", flag_range("--multiscatter-steps", true), &lut->multiscatter_steps) ||
        get_word(c, q, "lut_format", "quality", lut_format_words, COUNT(lut_format_words), &f32) ||
        get_number(c, q, "render_scale", "quality", flag_range("--render-scale", false), &o->render_scale) ||
        get_int(c, q, "bloom_mips", "quality", flag_range("--bloom-mips", true), &o->bloom_mips))
        return 2;
    int root = (int)(sqrt((double)dirs) + 0.5);
    if (root * root != dirs)
        return fail(c, "quality.multiscatter_directions",
                    "%d is not a perfect square; expected 1, 4, 9, ..., 4096 directions (as --multiscatter-dirs)", dirs);
    v->mode = (sky_mode_choice)mode;
    v->pass_kind = (sky_pass_kind)pass;
    lut->lut_f32 = f32 == 1;
    lut->multiscatter_sqrt_dirs = root;
    if (v->max_steps != 0 && v->max_steps < v->steps)
        return fail(c, cJSON_GetObjectItemCaseSensitive(q, "max_steps") ? "quality.max_steps" : "quality.steps",
                    "max_steps %d is below steps %d; expected max_steps >= steps, or max_steps 0 (a fixed count)",
                    v->max_steps, v->steps);
    return 0;
}

/* ---- loading ----------------------------------------------------------------------------------- */

static int read_all(const char *path, const char *shown, char **text, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "vksky: --scene: cannot read '%s': %s\n", shown, strerror(errno));
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
        fprintf(stderr, "vksky: --scene: cannot read '%s': out of memory\n", shown);
        return 2;
    }
    if (err) {
        fprintf(stderr, "vksky: --scene: cannot read '%s': %s\n", shown, strerror(err));
        free(buf);
        return 2;
    }
    if (n > SCENE_MAX_BYTES) {
        fprintf(stderr, "vksky: --scene: '%s' is larger than %d bytes; expected a scene (a small JSON file)\n", shown,
                SCENE_MAX_BYTES);
        free(buf);
        return 2;
    }
    buf[n] = '\0';
    *text = buf, *len = n;
    return 0;
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

static int syntax_error(const ctx *c, const char *text, size_t len, const char *why_at)
{
    size_t at = why_at && why_at >= text && why_at <= text + len ? (size_t)(why_at - text) : len;
    int line, column;
    line_column(text, at, &line, &column);
    bool at_end = true;
    for (size_t i = at; i < len; ++i) at_end = at_end && blank(text[i]);
    if (at < len && text[at] == '\0') {
        fprintf(stderr, "vksky: %s:%d:%d: a NUL byte; expected JSON text\n", c->file, line, column);
        return 2;
    }
    if (at_end) {
        fprintf(stderr, "vksky: %s:%d:%d: syntax error: unexpected end of the file (an unclosed object, array or "
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
    printable(shown, sizeof shown, near);
    fprintf(stderr, "vksky: %s:%d:%d: syntax error near '%s'; expected JSON (no comments, no trailing commas, "
                    "strings in double quotes)\n", c->file, line, column, shown);
    return 2;
}

int scene_load(const char *path, options *o)
{
    static const char *const names[] = {"description", "planet", "species", "multiple_scattering", "sun", "camera",
                                        "output", "quality"};
    ctx c = {.o = o};
    printable(c.file, sizeof c.file, path);
    char *text = NULL;
    size_t len = 0;
    if (read_all(path, c.file, &text, &len)) return 2;
    int rc = 2;
    cJSON *root = NULL;
    size_t first = 0;
    while (first < len && blank(text[first])) ++first;
    const char *nul = memchr(text, '\0', len);
    if (first == len) {
        fprintf(stderr, "vksky: %s: empty file; expected a JSON object (see scenes/README.md)\n", c.file);
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
        fprintf(stderr, "vksky: %s: the top level is %s; expected a JSON object {...} (see scenes/README.md)\n",
                c.file, type_of(root));
        goto done;
    }
    const cJSON *description = cJSON_GetObjectItemCaseSensitive(root, "description");
    if (check_fields(&c, root, "", names, COUNT(names))) goto done;
    if (description && !cJSON_IsString(description)) {
        fail(&c, "description", "expected a string, got %s", type_of(description));
        goto done;
    }
    free(loaded_description);
    loaded_description = description ? strdup(description->valuestring) : NULL;
    const cJSON *section;
    if (get_object(&c, root, "planet", "", &section) || (section && parse_planet(&c, section))) goto done;
    if (get_object(&c, root, "species", "", &section) || (section && parse_species(&c, section))) goto done;
    if (get_bool(&c, root, "multiple_scattering", "", &o->multiple_scattering)) goto done;
    if (get_object(&c, root, "sun", "", &section) || (section && parse_sun(&c, section))) goto done;
    if (get_object(&c, root, "camera", "", &section) || (section && parse_camera(&c, section))) goto done;
    if (get_object(&c, root, "output", "", &section) || (section && parse_output(&c, section))) goto done;
    if (get_object(&c, root, "quality", "", &section) || (section && parse_quality(&c, section))) goto done;
    rc = 0;
done:
    cJSON_Delete(root);
    free(text);
    return rc;
}

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

/* The simplest form that is exactly the profile: exponential, tent, or the two layers. */
static void dump_density(builder *b, cJSON *species, const model_density_profile *p)
{
    cJSON *d = obj(b, species, "density");
    double x, y;
    if (!d) return;
    if (model_profile_as_exponential(p, &x)) {
        str(b, d, "profile", "exponential");
        num(b, d, "scale_height_km", x);
    } else if (model_profile_as_tent(p, &x, &y)) {
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
    str(&b, root, "description", o->scene_path && loaded_description ? loaded_description : description);

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

    boolean(&b, root, "multiple_scattering", o->multiple_scattering);

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
    num(&b, output, "exposure_ev", v->exposure_ev);
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

    char *text = b.ok ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    if (!text) {
        fprintf(stderr, "vksky: --dump-scene: out of memory\n");
        return 1;
    }
    int rc = fputs(text, out) < 0 || fputc('\n', out) == EOF || fflush(out) != 0 ? 1 : 0;
    if (rc) fprintf(stderr, "vksky: --dump-scene: cannot write the scene: %s\n", strerror(errno));
    cJSON_free(text);
    return rc;
}
