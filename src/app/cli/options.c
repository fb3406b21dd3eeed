#include "app/cli/options.h"
#include "app/cli/bad_value.h"
#include "app/cli/flags.h"
#include "app/cli/options_sunvis.h"
#include "app/cli/options_projection.h"
#include "app/quality/quality.h"
#include "app/scene/scene.h"
#include "app/cli/options_tooling.h"
#include "app/cli/options_sequence.h"
#include "app/cli/options_throughput.h"
#include "app/cli/help.h"
#include "app/scene/light.h"
#include "gpu/context.h"
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>


sky_features options_features(const options *o)
{
    sky_features f = sky_features_default();
    for (int i = 0; i < 3; ++i) f.ground_albedo[i] = o->ground_albedo[i];
    f.mie_phase = o->mie_phase;
    f.limb_darkening = o->limb_darkening;
    f.sun_disc = o->sun_disc;
    f.multiple_scattering = o->multiple_scattering;
    f.sun_disc_power = o->units == OPTIONS_UNITS_PHOTOMETRIC;
    return f;
}

double options_sun_radius_rad(const options *o) { return o->sun_angular_radius_deg * 3.14159265358979323846 / 180.0; }

void options_print_help(FILE *out)
{
    help_entry entries[flags_count];
    for (int i = 0; i < flags_count; ++i)
        entries[i] = (help_entry){flags_table[i].name, flags_table[i].kind != ARG_NONE, flags_table[i].help};
    help_print(out, entries, flags_count);
}

static int bad(const char *flag_name, const char *what)
{
    fprintf(options_report_stream(), "vksky: %s: %s\n", flag_name, what);
    return 2;
}

static int parse_number(const flag *f, const char *text, double *out)
{
    char msg[256];
    const char *expect = f->kind == ARG_INT ? "an integer" : "a number";
    errno = 0;
    char *end = NULL;
    double v = strtod(text, &end);
    if (end == text || *end != '\0' || errno == ERANGE || isnan(v) || isinf(v) ||
        (f->kind == ARG_INT && v != floor(v))) {
        snprintf(msg, sizeof msg, "'%s' is not %s; expected %s in [%g, %g]", text, expect, expect, f->min, f->max);
        return bad(f->name, msg);
    }
    if (v < f->min || v > f->max) {
        snprintf(msg, sizeof msg, "%s is out of range; expected %s in [%g, %g]", text, expect, f->min, f->max);
        return bad(f->name, msg);
    }
    *out = v;
    return 0;
}

/* Scale a species' coefficients (relative to the Table 1 values). */
static void scale3(double v[3], double factor)
{
    for (int i = 0; i < 3; ++i) v[i] *= factor;
}

/* "WxH" with both in the flag's range. */
static int parse_size(const flag *f, const char *text, int *w, int *h)
{
    char *end = NULL;
    long a = strtol(text, &end, 10);
    if (end == text || (*end != 'x' && *end != 'X')) goto fail;
    const char *second = end + 1;
    long b = strtol(second, &end, 10);
    if (end == second || *end != '\0' || a < f->min || b < f->min || a > f->max || b > f->max) goto fail;
    *w = (int)a, *h = (int)b;
    return 0;
fail:;
    char msg[200];
    snprintf(msg, sizeof msg, "'%s' is not a size; expected WxH with W and H integers in [%g, %g]", text, f->min, f->max);
    return bad(f->name, msg);
}

/* "R,G,B": three numbers, each in the flag's range. */
static int parse_triple(const flag *f, const char *text, double out[3])
{
    const flag one = {f->name, ARG_DOUBLE, f->min, f->max, NULL};
    const char *p = text;
    for (int i = 0; i < 3; ++i) {
        const char *comma = strchr(p, ',');
        size_t n = comma && i < 2 ? (size_t)(comma - p) : strlen(p);
        char part[64];
        if ((i < 2 && !comma) || (i == 2 && comma) || n >= sizeof part) {
            char msg[200];
            snprintf(msg, sizeof msg, "'%s' is not R,G,B; expected three numbers in [%g, %g] separated by commas", text,
                     f->min, f->max);
            return bad(f->name, msg);
        }
        memcpy(part, p, n);
        part[n] = '\0';
        if (parse_number(&one, part, &out[i])) return 2;
        p += n + 1;
    }
    return 0;
}

/* One of a fixed list of words; returns its index or -1 (message printed). */
static int parse_word(const char *flag_name, const char *text, const char *const *words, int count)
{
    for (int i = 0; i < count; ++i)
        if (!strcmp(text, words[i])) return i;
    char msg[256];
    int n = snprintf(msg, sizeof msg, "unknown value '%s'; expected ", text);
    for (int i = 0; i < count && n < (int)sizeof msg; ++i)
        n += snprintf(msg + n, sizeof msg - (size_t)n, "%s%s", words[i], i + 2 < count ? ", " : i + 1 < count ? " or " : "");
    bad(flag_name, msg);
    return -1;
}

static bool has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n > e && strcasecmp(path + n - e, ext) == 0;
}

/* One flag's value: x for a numeric flag (value may then be NULL), the text for the others. */
static int apply_value(options *o, const flag *f, const char *value, double x)
{
    const char *n = f->name;
    int handled = options_tooling_apply(o, n, value, x);   /* the sun by date and place, --list-scenes */
    if (handled >= 0) return handled;
    handled = options_sequence_apply(o, n, value, x);   /* --animate, --frame-count, --frame-range */
    if (handled >= 0) return handled;
    handled = options_throughput_apply(o, n, value, x);   /* --threads, --exr-compression */
    if (handled >= 0) return handled;
    if (!strcmp(n, "--render")) {
        if (!has_extension(value, ".exr") && !has_extension(value, ".png"))
            return bad(n, "unknown output type; expected a file name ending in .exr or .png");
        if (o->output_count == OPTIONS_MAX_OUTPUTS) return bad(n, "given too often; at most 4 outputs");
        o->outputs[o->output_count++] = value;
    } else if (!strcmp(n, "--width")) o->width = (int)x;
    else if (!strcmp(n, "--height")) o->height = (int)x;
    else if (!strcmp(n, "--sun-elevation")) o->view.sun_elevation_deg = x;
    else if (!strcmp(n, "--sun-azimuth")) o->view.sun_azimuth_deg = x;
    else if (!strcmp(n, "--altitude")) o->view.altitude_km = x;
    else if (!strcmp(n, "--yaw")) o->view.yaw_deg = x;
    else if (!strcmp(n, "--pitch")) o->view.pitch_deg = x;
    else if (!strcmp(n, "--fov")) o->view.fov_deg = x;
    else if (!strcmp(n, "--exposure")) o->view.exposure_ev = x, o->exposure_ev100 = x, o->exposure_given = true;
    else if (!strcmp(n, "--tonemap")) {
        if (!strcmp(value, "clamp")) o->view.tonemap = VKSKY_TONEMAP_CLAMP;
        else if (!strcmp(value, "reinhard")) o->view.tonemap = VKSKY_TONEMAP_REINHARD;
        else if (!strcmp(value, "aces")) o->view.tonemap = VKSKY_TONEMAP_ACES;
        else {
            char msg[200];
            snprintf(msg, sizeof msg, "unknown operator '%s'; expected clamp, reinhard or aces", value);
            return bad(n, msg);
        }
    } else if (!strcmp(n, "--no-bloom")) o->view.bloom = false;
    else if (!strcmp(n, "--no-dither")) o->view.no_dither = true;
    else if (!strcmp(n, "--steps")) o->view.steps = (int)x;
    else if (!strcmp(n, "--quality")) {
        static const char *const w[] = {"low", "medium", "high", "ultra", "lesson", "cpu", "auto"};
        int k = parse_word(n, value, w, 7);
        if (k < 0) return 2;
        o->quality = w[k];
    } else if (!strcmp(n, "--bloom-res")) {
        static const char *const w[] = {"half", "quarter"};
        int k = parse_word(n, value, w, 2);
        if (k < 0) return 2;
        o->bloom_quarter = k == 1;
    } else if (!strcmp(n, "--bloom-downsample")) {
        static const char *const w[] = {"levels", "single-pass"};
        int k = parse_word(n, value, w, 2);
        if (k < 0) return 2;
        o->bloom_downsample = (bloom_downsample_kind)k;
    } else if (!strcmp(n, "--post-pass")) {
        static const char *const w[] = {"fragment", "compute", "auto"};
        int k = parse_word(n, value, w, 3);
        if (k < 0) return 2;
        o->post_pass = (post_pass_kind)k;
    } else if (!strcmp(n, "--max-error")) o->max_error = x;
    else if (!strcmp(n, "--max-color-error")) o->max_color_error = x;
    else if (!strcmp(n, "--max-steps")) o->view.max_steps = (int)x;
    else if (!strcmp(n, "--steps-ramp")) o->view.steps_ramp_km = x;
    else if (!strcmp(n, "--sample-offset")) o->view.sample_offset = x;
    else if (!strcmp(n, "--step-distribution")) o->view.step_distribution = x;
    else if (!strcmp(n, "--sky-mode")) {
        static const char *const w[] = {"march", "skyview", "auto", "fill"};
        int k = parse_word(n, value, w, 4);
        if (k < 0) return 2;
        o->view.mode = (sky_mode_choice)k;
    } else if (!strcmp(n, "--sky-pass")) {
        static const char *const w[] = {"fragment", "compute", "auto"};
        int k = parse_word(n, value, w, 3);
        if (k < 0) return 2;
        o->view.pass_kind = (sky_pass_kind)k;
    } else if (!strcmp(n, "--lut-format")) {
        static const char *const w[] = {"f16", "f32"};
        int k = parse_word(n, value, w, 2);
        if (k < 0) return 2;
        o->lut.lut_f32 = k == 1;
    } else if (!strcmp(n, "--skyview-lut")) {
        if (parse_size(f, value, &o->lut.skyview_width, &o->lut.skyview_height)) return 2;
    } else if (!strcmp(n, "--transmittance-lut")) {
        if (parse_size(f, value, &o->lut.transmittance_width, &o->lut.transmittance_height)) return 2;
    } else if (!strcmp(n, "--skyview-steps")) o->view.skyview_steps = (int)x;
    else if (!strcmp(n, "--transmittance-steps")) o->lut.transmittance_steps = (int)x;
    else if (!strcmp(n, "--multiscatter-lut")) o->lut.multiscatter_size = (int)x;
    else if (!strcmp(n, "--multiscatter-dirs")) {
        int root = (int)(sqrt(x) + 0.5);
        if (root * root != (int)x) return bad(n, "not a perfect square; expected 1, 4, 9, ..., 4096 directions");
        o->lut.multiscatter_sqrt_dirs = root;
    } else if (!strcmp(n, "--multiscatter-steps")) o->lut.multiscatter_steps = (int)x;
    else if (!strcmp(n, "--bloom-mips")) o->bloom_mips = (int)x;
    else if (!strcmp(n, "--render-scale")) o->render_scale = x;
    else if (!strcmp(n, "--mie-g")) o->atmosphere.mie_g = x;
    else if (!strcmp(n, "--rayleigh-scale")) o->scales[0] = x;
    else if (!strcmp(n, "--mie-scale")) o->scales[1] = x;
    else if (!strcmp(n, "--ozone-scale")) o->scales[2] = x;
    else if (!strcmp(n, "--scene")) {
        if (o->scene_path) return bad(n, "given twice; expected one scene (later flags override its fields)");
        o->scene_path = options_tooling_scene_path(value);   /* a shipped scene's name -> its file */
        if (!o->scene_path || scene_load(o->scene_path, o) != 0) return 2;
    } else if (!strcmp(n, "--dump-scene")) o->dump_scene = true;
    else if (!strcmp(n, "--ground-albedo")) {
        if (parse_triple(f, value, o->ground_albedo)) return 2;
    } else if (!strcmp(n, "--sun-illuminance")) {
        if (parse_triple(f, value, o->atmosphere.sun_illuminance)) return 2;
    } else if (!strcmp(n, "--mie-phase")) {
        static const char *const w[] = {"hg", "cornette-shanks", "henyey-greenstein"};
        int k = parse_word(n, value, w, 3);
        if (k < 0) return 2;
        o->mie_phase = k == 1;
    } else if (!strcmp(n, "--sun-visibility")) {
        int k = parse_word(n, value, sunvis_words, SUNVIS_WORD_COUNT);
        if (k < 0) return 2;
        o->atmosphere.sun_visibility = k;
    } else if (!strcmp(n, "--sun-angular-radius")) o->sun_angular_radius_deg = x;
    else if (!strcmp(n, "--limb-darkening")) o->limb_darkening = x;
    else if (!strcmp(n, "--no-sun-disc")) o->sun_disc = false;
    else if (!strcmp(n, "--units")) {   /* physical light (issue 32): app/scene/light.c */
        if (!strcmp(value, "photometric")) o->units = OPTIONS_UNITS_PHOTOMETRIC;
        else if (!strcmp(value, "relative")) o->units = OPTIONS_UNITS_RELATIVE;
        else return bad(n, "unknown units; expected photometric or relative");
    } else if (!strcmp(n, "--exr-type")) {
        if (!strcmp(value, "auto")) o->exr_type = OPTIONS_EXR_AUTO;
        else if (!strcmp(value, "half")) o->exr_type = OPTIONS_EXR_HALF;
        else if (!strcmp(value, "float")) o->exr_type = OPTIONS_EXR_FLOAT;
        else return bad(n, "unknown type; expected half, float or auto");
    } else if (!strcmp(n, "--auto-exposure")) o->auto_exposure = true;
    else if (!strcmp(n, "--sun-lux")) light_set_sun_lux(o, x);
    else if (!strcmp(n, "--no-multiscatter")) o->multiple_scattering = false;
    else if (!strcmp(n, "--trace-passes")) o->trace_passes = true;
    else if (!strcmp(n, "--no-cache")) o->no_cache = true;
    else if (!strcmp(n, "--timings")) o->timings = true;
    else if (!strcmp(n, "--reference")) o->reference = true;
    else if (!strcmp(n, "--path-trace")) o->path_trace = true;
    else if (!strcmp(n, "--samples")) o->path_samples = (int)x;
    else if (!strcmp(n, "--spectral")) o->spectral = (int)x;
    else if (!strcmp(n, "--irradiance")) o->irradiance = true;
    else if (!strcmp(n, "--tilt")) o->tilt_deg = x;
    else if (!strcmp(n, "--tilt-azimuth")) {
        o->tilt_azimuth_deg = x;
        o->tilt_azimuth_set = true;
    }
    else if (!strcmp(n, "--bench")) o->bench_frames = (int)x;
    else if (!strcmp(n, "--frames")) o->frames = (int)x;
    else if (!strcmp(n, "--screenshot")) {
        if (!has_extension(value, ".png")) return bad(n, "expected a file name ending in .png");
        o->screenshot = value;
    } else if (!strcmp(n, "--validate")) o->validate = true;
    else if (!strcmp(n, "--async-luts")) o->async_luts = true;
    else if (!strcmp(n, "--trace-barriers")) o->trace_barriers = true;
    else if (!strcmp(n, "--list-devices")) o->list_devices = true;
    else if (!strcmp(n, "--device")) o->device_index = (int)x;
    else if (!strcmp(n, "--projection") || !strcmp(n, "--quiet")) return options_projection_apply(o, n, value);
    else if (!strcmp(n, "--help")) o->help = true;
    else if (!strcmp(n, "--version")) o->version = true;
    return 0;
}

/* Did the command line name one of these flags? (Its values, o->given: a reload asks without a command line.) */
static bool named_any(const options *o, const char *const *names, size_t count)
{
    for (int i = 0; i < o->given_count; ++i)
        for (size_t k = 0; k < count; ++k)
            if (!strcmp(o->given[i].flag->name, names[k])) return true;
    return false;
}

/* No --render, --bench, --reference or an informational flag: the window will open. (--render-scale is no --render:
 * a window with --render-scale starts from the window's preset, not from --quality auto.) */
static bool window_mode(const options *o)
{
    static const char *const headless[] = {"--render", "--bench", "--reference", "--help", "--version",
                                           "--list-devices", "--dump-scene", "--list-scenes"};
    return !named_any(o, headless, sizeof headless / sizeof headless[0]);
}

/* Will the run's device (--device N, or the default choice) be a CPU implementation? Asked of a bare instance,
 * only when --quality auto chooses: its measured tables differ by device kind. No device: the GPU table (the run
 * reports the missing device itself). A sequence: the GPU table on every device, so that its frames are the same
 * files wherever each job of a farm ran (docs/sequences.md). VKSKY_QUALITY_TABLE=cpu|gpu (tests) forces the answer. */
static bool device_is_cpu(const options *o)
{
    static const char *const sequence[] = {"--animate", "--frame-count", "--frame-range"};
    if (o->reference || o->help || o->version || o->list_devices) return false;   /* no device in this run */
    if (named_any(o, sequence, 3)) return false;
    const char *forced = getenv("VKSKY_QUALITY_TABLE");
    if (forced && *forced) return !strcmp(forced, "cpu");
    VkPhysicalDeviceType type;
    /* The probe's instance is the run's when their validation agrees (--validate is applied after this choice). */
    static const char *const validate[] = {"--validate"};
    bool validation = o->validate || named_any(o, validate, 1);
    return gpu_device_type_for(o->device_index, validation, &type) == 0 && type == VK_PHYSICAL_DEVICE_TYPE_CPU;
}

static int finish(options *o, int argc, char **argv, bool exposure_flag);

int options_parse(options *o, int argc, char **argv) { return options_parse_for_classes(o, argc, argv, 0); }

void options_defaults(options *o)
{
    *o = (options){.view = sky_view_default(), .width = 1280, .height = 720, .device_index = -1,
                   .lut = sky_lut_quality_default(), .render_scale = 1.0, .bloom_mips = 5,
                   .scales = {1.0, 1.0, 1.0}, .path_samples = 4096, .sun_angular_radius_deg = 0.265,
                   .limb_darkening = 0.6, .sun_disc = true, .multiple_scattering = true, .post_pass = POST_PASS_AUTO};
    model_atmosphere_earth(&o->atmosphere);
}

/* A flag given as a value: a number parsed once (by the command line's parse), then applied as that number. */
static int apply_given(options *o, options_given *g)
{
    const flag *f = g->flag;
    bool numeric = f->kind == ARG_INT || f->kind == ARG_DOUBLE;
    if (numeric && !g->parsed) {
        if (parse_number(f, g->text, &g->number) != 0) return 2;
        g->parsed = true;
    }
    return apply_value(o, f, numeric ? NULL : g->text, g->number);
}

static int resolve(options *o, unsigned quality_classes, bool report);

/* The interactive window starts from the interactive preset, headless renders from --quality auto (resolve); a scene
 * file's quality section and the flags override either. */
static void window_preset(options *o)
{
    if (window_mode(o))
        quality_apply(quality_preset("low"), &o->view, &o->lut, &o->render_scale, &o->bloom_mips, &o->bloom_quarter);
}

int options_parse_for_classes(options *o, int argc, char **argv, unsigned quality_classes)
{
    options_defaults(o);
    o->argc = argc, o->argv = argv;
    const char *env = getenv("VKSKY_VALIDATION");
    if (env && strcmp(env, "") != 0 && strcmp(env, "0") != 0) o->validate = true;
    /* The command line read into values (each flag with its text, o->given), then three passes: --scene first (pass
     * -1), wherever it stands; then the quality preset (or --max-error's choice) sets the knobs, so that any knob flag,
     * wherever it stands, overrides it (resolve). */
    for (int i = 1; i < argc; ++i) {
        const char *arg = argv[i];
        const char *eq = strchr(arg, '=');
        size_t name_len = eq && !strncmp(arg, "--", 2) ? (size_t)(eq - arg) : strlen(arg);
        const flag *f = flags_find(arg, name_len);
        if (!f) {
            char msg[160];
            snprintf(msg, sizeof msg, "unknown %s; see vksky --help for the accepted flags",
                     arg[0] == '-' ? "flag" : "argument (flags start with --)");
            return bad(arg, msg);
        }
        const char *value = NULL;
        if (f->kind != ARG_NONE) {
            if (eq && name_len < strlen(arg)) value = eq + 1;
            else if (i + 1 < argc) value = argv[++i];
            else return bad(f->name, "missing value; see vksky --help");
        } else if (eq && name_len < strlen(arg)) {
            return bad(f->name, "takes no value");
        }
        if (o->given_count == OPTIONS_MAX_GIVEN) return bad(f->name, "one flag too many; at most 256 flags");
        options_given *g = &o->given[o->given_count++];
        *g = (options_given){.flag = f, .text = value};
    }
    /* The interactive window starts from its preset, under the scene file's quality section and the flags. */
    window_preset(o);
    for (int k = 0; k < o->given_count; ++k)
        if (!strcmp(o->given[k].flag->name, "--scene") && apply_given(o, &o->given[k]) != 0) return 2;
    return resolve(o, quality_classes, true);
}

int options_reload(const options *o, options *fresh)
{
    /* The defaults, the scene file as it is now on disk (the scene loader, as --scene read it at start-up), then the
     * command line's flags over it: the values the start-up parse kept (numbers as parsed then), not its text. */
    options_defaults(fresh);
    fresh->argc = o->argc, fresh->argv = o->argv;
    fresh->validate = o->validate;
    memcpy(fresh->given, o->given, (size_t)o->given_count * sizeof o->given[0]);
    fresh->given_count = o->given_count;
    window_preset(fresh);
    if (o->scene_path) {
        fresh->scene_path = o->scene_path;
        if (scene_load(o->scene_path, fresh) != 0) return 2;
    }
    if (resolve(fresh, 0, false) != 0) return 2;
    options_release(fresh);   /* an animated command line's frame base: a reload has no frames */
    return 0;
}

/* Passes 0 and 1 over the command line's values (the scene loaded), then what follows from them. `report`: print
 * --max-error's pick and its notes (the start-up parse does; a reload does not print them again). */
static int resolve(options *o, unsigned quality_classes, bool report)
{
    const char *scene_quality = NULL;
    /* The interactive window started from its preset (window_preset), headless renders start from --quality auto
     * (the measured front's point for the scene kind, chosen once the view is known); a scene and the flags override
     * either. */
    bool window = window_mode(o);
    const quality_config *picked = NULL;        /* --max-error's choice, reported once the options are final */
    double picked_error = 0.0;
    char picked_scene[96] = "";
    bool picked_cpu = false;                    /* the table it picked from: the CPU device's or the GPU's */
    for (int pass = 0; pass < 2; ++pass) {
    if (pass == 0) scene_quality = o->quality, o->quality = NULL;   /* the scene's preset: applied by scene_load */
    if (pass == 1) {
        if (options_tooling_resolve(o)) return 2;   /* the sun from a date and place, before --max-error reads it */
        if (o->quality && o->max_error > 0.0) return bad("--max-error", "not with --quality; give one or the other");
        /* auto: named, or the default of a headless run that names no quality (no --quality, --max-error or scene
         * file quality section). It is no preset a scene file can name, so a dump lists its knobs instead. */
        bool automatic = o->quality ? !strcmp(o->quality, "auto")
                                    : !window && o->max_error <= 0.0 && !o->scene_quality;
        const quality_config *q = o->quality && !automatic ? quality_preset(o->quality) : NULL;
        double measured = 0.0;
        unsigned classes = quality_classes ? quality_classes
                                           : quality_class_bit(o->view.altitude_km, o->view.sun_elevation_deg);
        if (automatic) {
            o->quality_cpu_device = device_is_cpu(o);
            q = quality_auto(classes, o->quality_cpu_device, &measured);
            o->quality = NULL;
            o->quality_auto = true;
            o->quality_classes = classes;
        } else if (o->max_error > 0.0) {
            picked_cpu = device_is_cpu(o);
            q = quality_pick(o->max_error, classes, picked_cpu, &measured);
            quality_class_names(classes, picked_scene, sizeof picked_scene);
            o->quality_classes = classes;
            if (!q) {
                char msg[240];
                snprintf(msg, sizeof msg, "no measured configuration reaches %g on a %s scene; try a larger budget or --quality ultra",
                         o->max_error, picked_scene);
                return bad("--max-error", msg);
            }
            picked = q, picked_error = measured;
        }
        /* --quality / --max-error replace the scene's whole quality section; without them the scene's preset (applied
         * by scene_load, under the scene's knobs) stays. */
        if (q) quality_apply(q, &o->view, &o->lut, &o->render_scale, &o->bloom_mips, &o->bloom_quarter);
        else o->quality = scene_quality;
    }
    for (int k = 0; k < o->given_count; ++k) {
        options_given *g = &o->given[k];
        const flag *f = g->flag;
        bool scene_flag = !strcmp(f->name, "--scene");
        bool first_pass_flag = !strcmp(f->name, "--quality") || !strcmp(f->name, "--max-error") ||
                               !strcmp(f->name, "--altitude") || !strcmp(f->name, "--sun-elevation") ||
                               !strcmp(f->name, "--dump-scene") || !strcmp(f->name, "--device") ||
                               !strcmp(f->name, "--reference") || !strcmp(f->name, "--help") ||
                               !strcmp(f->name, "--version") || !strcmp(f->name, "--list-devices") ||
                               options_tooling_first_pass(f->name);
        /* Pass -1 loaded the scene; pass 0 reads only what the choice depends on; pass 1 applies every flag except
         * the scene and the choice. */
        if (pass == 0 ? first_pass_flag : !scene_flag && strcmp(f->name, "--quality") && strcmp(f->name, "--max-error"))
            if (apply_given(o, g) != 0) return 2;
    }
    }
    /* A sequence's frames start from here: the flags and the scene read, nothing derived yet (options_frame). */
    if (o->animate_count > 0) {
        o->unresolved = malloc(sizeof *o);
        if (!o->unresolved) return bad("--animate", "out of memory");
        *o->unresolved = *o;
    }
    static const char *const exposure[] = {"--exposure"};
    bool exposure_flag = named_any(o, exposure, 1);   /* a scene's exposure gives way to --auto-exposure; the flag does not */
    /* A reload: the projection's notes about the command line were printed at start-up (argc 1, as a frame's). */
    char *no_args[] = {"vksky", NULL};
    if (finish(o, report ? o->argc : 1, report ? o->argv : no_args, exposure_flag)) {
        options_release(o);
        return 2;
    }
    /* The --max-error choice, reported only now: every flag has been read and accepted. An animated sequence's
     * frames render with the pick for every scene class they pass through (sequence_choose_quality parses again with
     * those classes), not with this base view's: that parse reports it, with the frames it serves. --quiet: none. */
    bool frames_pick = o->animate_count > 0 && !o->dump_scene;   /* --dump-scene: no frames, the base is all */
    if (!report || o->quiet || (quality_classes != 0) != frames_pick) picked = NULL;
    if (picked && frames_pick)
        fprintf(options_notes_stream(), "vksky: --max-error %g: picked '%s' for frames %d-%d (measured mean relative luminance error "
                "%.3g at worst on the frames' '%s' scenes)\n", o->max_error, picked->name, o->frame_first, o->frame_last,
                picked_error, picked_scene);
    else if (picked)
        fprintf(o->dump_scene ? options_report_stream() : options_notes_stream(), /* keep a --dump-scene's stdout pure JSON */
                "vksky: --max-error %g: picked '%s' (measured mean relative luminance error %.3g on the '%s' scene)\n",
                o->max_error, picked->name, picked_error, picked_scene);
    /* Issue 32: --max-error's promise is the luminance; the colour of the RGB renderer it picks for is measured too
     * (quality_color_table.h), and said beside the pick unless --max-color-error chooses the wavelengths. */
    if (picked && o->max_color_error <= 0.0 && !o->spectral) {
        double de = 0.0;
        for (int c = 0; c < QUALITY_SCENE_COUNT; ++c)
            if (o->quality_classes & (1u << c)) de = fmax(de, quality_color_error(0, c));
        fprintf(o->dump_scene ? options_report_stream() : options_notes_stream(), "vksky: note: --max-error bounds the luminance only; RGB's colour on "
                "the '%s' scene is within CIEDE2000 %.2f of the spectrum's (--max-color-error DE picks wavelengths)\n",
                picked_scene, de);
    }
    /* Issue 31: a promise from a table measured with other shaders or knobs is an estimate, and says so, beside the
     * pick (the same stream: a run that parses cleanly keeps stderr empty, docs/robustness.md). */
    const char *estimate = picked ? quality_table_estimate(picked_cpu) : NULL;
    if (estimate)
        fprintf(o->dump_scene ? options_report_stream() : options_notes_stream(), "vksky: note: --max-error: the %s table's rows are estimates (%s)\n",
                picked_cpu ? "CPU device" : "GPU", estimate);
    return 0;
}

/* What follows the flags: the sun from a date and place, the frame range, the density scales, the checks across
 * flags, the projection's image size, the exposure in the output's units. A sequence frame runs it again on its own
 * values (options_frame); argc 1 there: the projection's notes about the command line were printed once. */
static int finish(options *o, int argc, char **argv, bool exposure_flag)
{
    if (options_tooling_resolve(o) || options_sequence_resolve(o)) return 2;
    scale3(o->atmosphere.rayleigh_scattering, o->scales[0]);
    scale3(o->atmosphere.mie_scattering, o->scales[1]);
    scale3(o->atmosphere.mie_absorption, o->scales[1]);
    scale3(o->atmosphere.ozone_absorption, o->scales[2]);
    if (o->view.max_steps != 0 && o->view.max_steps < o->view.steps) {
        char msg[160];
        snprintf(msg, sizeof msg, "%d is below --steps %d; expected a maximum >= the minimum", o->view.max_steps, o->view.steps);
        return bad("--max-steps", msg);
    }
    if (options_projection_finish(o, argc, argv) != 0) return 2;
    if (o->auto_exposure && exposure_flag) return bad("--auto-exposure", "not with --exposure; give one or the other");
    /* --dump-scene writes the exposure as given: the caller dumps these options (main.c), nothing else runs. */
    if (!o->dump_scene || o->help || o->version) light_finish(o);
    return 0;
}

int options_frame(const options *base, const char *const *names, const double *values, int count, options *out)
{
    if (!base->unresolved) {
        *out = *base;
        out->unresolved = NULL;   /* the base's to release */
        return 0;
    }
    *out = *base->unresolved;
    out->unresolved = NULL;
    bool exposure_flag = false;
    for (int i = 1; i < base->argc; ++i) exposure_flag = exposure_flag || !strncmp(base->argv[i], "--exposure", 10);
    for (int k = 0; k < count; ++k) {
        const flag *f = flags_find(names[k], strlen(names[k]));
        if (!f) return bad(names[k], "names no flag");   /* --animate checked it: not expected */
        if (!strcmp(names[k], "--time")) {   /* the clock's value: decimal hours to the millisecond */
            char text[16];
            sequence_time_text(values[k], text);
            if (apply_value(out, f, text, 0.0)) return 2;
        } else if (apply_value(out, f, NULL, values[k])) {
            return 2;
        }
        exposure_flag = exposure_flag || !strcmp(names[k], "--exposure");
    }
    char *no_args[] = {base->argv[0], NULL};
    return finish(out, 1, no_args, exposure_flag);
}

void options_release(options *o)
{
    free(o->unresolved);
    o->unresolved = NULL;
}

int options_copy(options *dst, const options *src)
{
    *dst = *src;
    if (!src->unresolved) return 0;
    dst->unresolved = malloc(sizeof *dst->unresolved);
    if (!dst->unresolved) {
        fprintf(options_report_stream(), "vksky: out of memory\n");
        return 1;
    }
    *dst->unresolved = *src->unresolved;
    return 0;
}
