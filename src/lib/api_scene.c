/* Scenes: values made by the CLI's own loader (include/vksky.h). */
#include "lib/lib_internal.h"
#include "app/scene/light.h"
#include "app/cli/bad_value.h"
#include "app/cli/options.h"
#include "app/runs/sequence_frames.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The command line's loaders and frame function report a bad value as one line on stderr (the CLI's contract) and
 * their notes (--max-error's pick) on stdout; the library hands that line to the host's callback instead and drops
 * the notes: it prints nothing (include/vksky.h). Both go through this thread's report and notes streams
 * (app/cli/bad_value.h), pointed at memory streams for the call, so the host's other threads keep their stderr and
 * stdout (pointing the process's streams at a capture took their lines too: the encode_frames flake,
 * tests/api/api_values_threads.c). */
typedef struct captured_lines {
    char *report;         /* the report stream's text (the caller frees it); NULL when nothing was written */
    size_t report_size;
    FILE *report_stream;
    char *notes;          /* the notes stream's text: dropped at the end */
    size_t notes_size;
    FILE *notes_stream;
} captured_lines;

static void capture_begin(captured_lines *c)
{
    *c = (captured_lines){0};
    c->report_stream = open_memstream(&c->report, &c->report_size);
    if (c->report_stream) options_report_to(c->report_stream);
    c->notes_stream = open_memstream(&c->notes, &c->notes_size);
    if (c->notes_stream) options_notes_to(c->notes_stream);
}

static void capture_end(captured_lines *c)
{
    options_report_to(NULL);
    options_notes_to(NULL);
    if (c->report_stream) fclose(c->report_stream);
    if (c->notes_stream) fclose(c->notes_stream);
    free(c->notes);
    c->notes = NULL;
}

/* The report's first line, without the CLI's "vksky: " and its newline, as the text of a message. */
static const char *capture_line(const captured_lines *c, int *length)
{
    const char *text = c->report ? c->report : "";
    if (!strncmp(text, "vksky: ", 7)) text += 7;
    *length = (int)strcspn(text, "\n");
    return text;
}

int lib_options_load(const char *path_or_name, options *o, char *why, size_t why_size)
{
    char *argv_store[] = {"vksky", "--quality", "low", "--scene", (char *)path_or_name, NULL};
    return lib_options_parse(path_or_name ? 5 : 3, argv_store, o, why, why_size);
}

int lib_options_parse(int argc, char *const *argv_store, options *o, char *why, size_t why_size)
{
    captured_lines capture;
    capture_begin(&capture);
    int rc = options_parse(o, argc, (char **)argv_store);
    /* An animated command line: a quality chosen by the scene serves every frame (the command line's sequence). */
    if (rc == 0 && o->animate_count > 0 && sequence_choose_quality(o) != 0) {
        options_release(o);
        rc = 2;
    }
    capture_end(&capture);
    int length;
    const char *line = capture_line(&capture, &length);
    snprintf(why, why_size, "%.*s", length, line);
    free(capture.report);
    o->argc = 0, o->argv = NULL;   /* the loader's argv was this function's */
    if (rc == 0 && o->unresolved) {
        /* A frame's values are set over these (vksky_scene_set_values); finishing them reads argv[0] only. */
        static char *const program[] = {"vksky", NULL};
        o->argc = 1, o->argv = (char **)program;
        o->unresolved->argc = 1, o->unresolved->argv = (char **)program;
    }
    return rc;
}

static vksky_scene *scene_new(void)
{
    vksky_scene *s = calloc(1, sizeof *s);
    return s;
}

/* A scene file that did not load (vksky_scene_load, vksky_scene_reload): the loader's own words tell an unreadable or
 * unknown file from a malformed one. */
static vksky_result load_failure(const char *why)
{
    return strstr(why, "cannot read") || strstr(why, "no scene") || strstr(why, "not found") ? VKSKY_ERROR_IO
                                                                                             : VKSKY_ERROR_PARSE;
}

vksky_result vksky_scene_create_earth(vksky_scene **out)
{
    if (!out) return VKSKY_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    vksky_scene *s = scene_new();
    if (!s) return VKSKY_ERROR_OUT_OF_MEMORY;
    char why[256];
    if (lib_options_load(NULL, &s->o, why, sizeof why) != 0) {
        free(s);
        return VKSKY_ERROR_PARSE;   /* the defaults always load; kept for a loader that one day checks more */
    }
    *out = s;
    return VKSKY_SUCCESS;
}

vksky_result vksky_scene_load(const char *path_or_name, vksky_message_fn message, void *message_user,
                              vksky_scene **out)
{
    if (out) *out = NULL;
    if (!path_or_name || !*path_or_name || !out) {
        lib_message(message, message_user, VKSKY_SEVERITY_ERROR, "vksky_scene_load: a path or a scene name is required");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    vksky_scene *s = scene_new();
    if (!s) return VKSKY_ERROR_OUT_OF_MEMORY;
    char why[512];
    if (lib_options_load(path_or_name, &s->o, why, sizeof why) != 0) {
        lib_message(message, message_user, VKSKY_SEVERITY_ERROR, "%s", why);
        free(s);
        return load_failure(why);
    }
    *out = s;
    return VKSKY_SUCCESS;
}

vksky_result vksky_scene_from_args(int argc, char *const *argv, vksky_message_fn message, void *message_user,
                                   vksky_scene **out)
{
    if (out) *out = NULL;
    if (argc < 1 || !argv || !out) {
        lib_message(message, message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_scene_from_args: argc >= 1 and argv (argv[0] the program's name) are required");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    vksky_scene *s = scene_new();
    if (!s) return VKSKY_ERROR_OUT_OF_MEMORY;
    char why[512];
    /* The command line's own parser: the same flags, ranges, scene file and quality resolution as `vksky`. */
    if (lib_options_parse(argc, argv, &s->o, why, sizeof why) != 0) {
        lib_message(message, message_user, VKSKY_SEVERITY_ERROR, "%s", why);
        free(s);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    s->from_args = true;
    *out = s;
    return VKSKY_SUCCESS;
}

vksky_result vksky_scene_copy(const vksky_scene *scene, vksky_scene **out)
{
    if (out) *out = NULL;
    if (!scene || !out) return VKSKY_ERROR_INVALID_ARGUMENT;
    vksky_scene *s = scene_new();
    if (!s) return VKSKY_ERROR_OUT_OF_MEMORY;
    *s = *scene;
    s->o.unresolved = NULL;
    if (scene->o.unresolved) {
        s->o.unresolved = malloc(sizeof *s->o.unresolved);
        if (!s->o.unresolved) {
            free(s);
            return VKSKY_ERROR_OUT_OF_MEMORY;
        }
        *s->o.unresolved = *scene->o.unresolved;
    }
    *out = s;
    return VKSKY_SUCCESS;
}

void vksky_scene_destroy(vksky_scene *scene)
{
    if (scene) options_release(&scene->o);
    free(scene);
}

/* Sends the captured line to the callback as an error; returns its text (up to the end of the capture). */
static const char *capture_report(const captured_lines *c, vksky_message_fn message, void *message_user)
{
    int length;
    const char *line = capture_line(c, &length);
    lib_message(message, message_user, VKSKY_SEVERITY_ERROR, "%.*s", length, line);
    return line;
}

vksky_result vksky_scene_set_values(vksky_scene *scene, uint32_t count, const char *const *flags,
                                    const double *values, vksky_message_fn message, void *message_user)
{
    if (!scene || (count && (!flags || !values)) || count > OPTIONS_MAX_ANIMATE) {
        lib_message(message, message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_scene_set_values: a scene, and %d flags at most with their values, are required",
                    OPTIONS_MAX_ANIMATE);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    const options *base = &scene->o;
    for (uint32_t k = 0; k < count; ++k) {
        bool animated = false;
        for (int a = 0; a < base->animate_count; ++a) animated = animated || !strcmp(flags[k], base->animate[a].flag_name);
        if (!animated || !base->unresolved || !isfinite(values[k])) {
            lib_message(message, message_user, VKSKY_SEVERITY_ERROR,
                        "vksky_scene_set_values: %s %g: accepted the flags the scene's command line animates "
                        "(--animate), with finite values", flags[k] ? flags[k] : "(null)", values[k]);
            return VKSKY_ERROR_INVALID_ARGUMENT;
        }
    }
    if (count == 0) return VKSKY_SUCCESS;
    /* The command line's own frame function (values, not text), its one-line complaint captured for the callback
     * (a frame's values are set per frame while the host's other threads run). */
    captured_lines capture;
    capture_begin(&capture);
    options f;
    int rc = options_frame(base, flags, values, (int)count, &f);
    capture_end(&capture);
    if (rc != 0) {
        capture_report(&capture, message, message_user);
        free(capture.report);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    free(capture.report);
    f.unresolved = scene->o.unresolved;   /* kept: the next frame's values are set over it too */
    scene->o = f;
    return VKSKY_SUCCESS;
}

vksky_result vksky_scene_set_sun(vksky_scene *scene, double azimuth_deg, double elevation_deg)
{
    if (!scene || !(azimuth_deg >= -360.0 && azimuth_deg <= 360.0) || !(elevation_deg >= -90.0 && elevation_deg <= 90.0))
        return VKSKY_ERROR_INVALID_ARGUMENT;
    scene->o.view.sun_azimuth_deg = azimuth_deg;
    scene->o.view.sun_elevation_deg = elevation_deg;
    return VKSKY_SUCCESS;
}

void vksky_scene_get_sun(const vksky_scene *scene, double *azimuth_deg, double *elevation_deg)
{
    if (azimuth_deg) *azimuth_deg = scene ? scene->o.view.sun_azimuth_deg : 0.0;
    if (elevation_deg) *elevation_deg = scene ? scene->o.view.sun_elevation_deg : 0.0;
}

double vksky_scene_ground_radius_m(const vksky_scene *scene)
{
    return scene ? scene->o.atmosphere.bottom_radius * 1000.0 : 0.0;
}

double vksky_scene_atmosphere_top_m(const vksky_scene *scene)
{
    return scene ? (scene->o.atmosphere.top_radius - scene->o.atmosphere.bottom_radius) * 1000.0 : 0.0;
}

double vksky_scene_sun_illuminance(const vksky_scene *scene)
{
    if (!scene) return 0.0;
    double sun[3];
    light_sun(&scene->o, sun);
    return 0.2126 * sun[0] + 0.7152 * sun[1] + 0.0722 * sun[2];
}

vksky_result vksky_scene_reload(vksky_scene *scene, vksky_message_fn message, void *message_user)
{
    if (!scene || !scene->from_args || !scene->o.scene_path || scene->o.animate_count > 0) {
        lib_message(message, message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_scene_reload: accepted a scene of vksky_scene_from_args whose command line names --scene "
                    "and animates nothing");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    /* The scene loader's one-line complaint goes to the callback, as vksky_scene_load's (lib_options_parse). */
    captured_lines capture;
    capture_begin(&capture);
    options fresh;
    int rc = options_reload(&scene->o, &fresh);
    capture_end(&capture);
    if (rc != 0) {
        vksky_result failed = load_failure(capture_report(&capture, message, message_user));
        free(capture.report);
        return failed;   /* the scene as it was */
    }
    free(capture.report);
    scene->o = fresh;
    return VKSKY_SUCCESS;
}
