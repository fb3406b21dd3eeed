#include "app/cli/options_composite.h"
#include "app/cli/bad_value.h"
#include "app/quality/ap_trade_table.h"
#include "app/cli/help.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct composite_flag {
    const char *name;
    bool takes_value;
    const char *help;
} composite_flag;

static const composite_flag composite_flags[] = {
    {"--composite", true, "FILE.exr  apply the atmosphere to a rendered image: a multilayer EXR with <ViewLayer>.Combined.RGBA and <ViewLayer>.Position.XYZ (or .Depth.Z) (Blender's names), or the beauty with --position or --depth; writes the composite and its AOV layers to --render FILE.exr (docs/aerial_perspective.md)"},
    {"--position", true, "FILE.exr   with --composite: the world-position pass as its own file (X,Y,Z, or R,G,B read as X,Y,Z)"},
    {"--view-layer", true, "NAME     with --composite: the view layer whose Combined and Position (or Depth) passes are used; needed when the file has several (Composite, the compositor's output, only when named)"},
    {"--depth", true, "FILE.exr      with --composite: camera-space depth (Z, <ViewLayer>.Depth.Z or R; distance along the view axis) instead of a position pass; needs the camera's orientation and fov"},
    {"--beauty-layer", true, "NAME   with --composite: the beauty's layer (channels NAME.R, .G, .B, .A)"},
    {"--position-layer", true, "NAME with --composite: the position's layer (NAME.X, .Y, .Z or NAME.R, .G, .B)"},
    {"--world-unit", true, "M        with --composite: metres per world unit (default 1)"},
    {"--world-up", true, "y|z        with --composite: the world's up axis (default z); the ground is the plane up = 0"},
    {"--ground-altitude", true, "KM with --composite: altitude of the world's ground plane (default 0)"},
    {"--camera-position", true, "X,Y,Z with --composite: camera position in world units, when the EXR has no worldToCamera; --yaw/--pitch/--fov give its orientation (sky pixels)"},
    {"--aerial-perspective", true, "M march | volume | auto: camera->point by a march per pixel (accurate) or Hillaire's froxel volume (fast; docs/aerial_perspective.md); auto: the cheapest measured one within --max-error, else the march (default auto)"},
    {"--ap-volume-size", true, "WxHxD  the froxel volume's size (default 32x32x32; 1 to 512 each)"},
    {"--ap-volume-range", true, "KM   the froxel volume's depth range (default 32; farther points are marched)"},
    {"--ap-volume-slices", true, "linear|quadratic the froxel volume's slice spacing (default quadratic, Hillaire's)"},
    {"--aovs", false, "              with --render FILE.exr (a plain sky render): also write the layers sky, sun_disk, transmittance, rayleigh, mie"},
};
enum { COMPOSITE_FLAG_COUNT = sizeof composite_flags / sizeof composite_flags[0] };

void composite_options_print_help(FILE *out)
{
    /* In --help's columns (app/help), as a section after the table's groups. */
    help_entry entries[COMPOSITE_FLAG_COUNT];
    for (int i = 0; i < COMPOSITE_FLAG_COUNT; ++i)
        entries[i] = (help_entry){composite_flags[i].name, composite_flags[i].takes_value, composite_flags[i].help};
    help_print_section(out, "compositing",
                       "       vksky --composite render.exr --render out.exr [options]   (docs/aerial_perspective.md)\n"
                       "       vksky --composite beauty.exr --position position.exr --render out.exr [options]\n",
                       entries, COMPOSITE_FLAG_COUNT);
}

static int bad(const char *flag, const char *what, const char *value)
{
    fprintf(options_report_stream(), "vksky: %s: %s%s%s\n", flag, value ? "'" : "", value ? value : "", what);
    return 2;
}

static bool parse_double(const char *text, double *out)
{
    errno = 0;
    char *end = NULL;
    double v = strtod(text, &end);
    if (end == text || *end != '\0' || errno == ERANGE || !isfinite(v)) return false;
    *out = v;
    return true;
}

static bool parse_triple(const char *text, double out[3])
{
    char buf[256];
    if (strlen(text) >= sizeof buf) return false;
    strcpy(buf, text);
    char *parts[3], *save = NULL, *tok = strtok_r(buf, ",", &save);
    int n = 0;
    for (; tok && n < 3; tok = strtok_r(NULL, ",", &save)) parts[n++] = tok;
    if (n != 3 || tok) return false;
    for (int i = 0; i < 3; ++i)
        if (!parse_double(parts[i], &out[i])) return false;
    return true;
}

static int take(composite_options *co, const char *name, const char *value)
{
    if (!strncmp(name, "--ap-volume-", 12)) co->ap_shape_given = true;
    if (!strcmp(name, "--composite")) co->input = value;
    else if (!strcmp(name, "--position")) co->position = value;
    else if (!strcmp(name, "--beauty-layer")) co->beauty_layer = value;
    else if (!strcmp(name, "--position-layer")) co->position_layer = value;
    else if (!strcmp(name, "--view-layer")) co->view_layer = value;
    else if (!strcmp(name, "--depth")) co->depth = value;
    else if (!strcmp(name, "--world-unit")) {
        if (!parse_double(value, &co->world_unit_m) || !(co->world_unit_m >= 1e-9 && co->world_unit_m <= 1e9))
            return bad(name, "' is not a length; expected metres per world unit in [1e-9, 1e9]", value);
    } else if (!strcmp(name, "--world-up")) {
        if (!strcmp(value, "y") || !strcmp(value, "Y")) co->up_axis = 1;
        else if (!strcmp(value, "z") || !strcmp(value, "Z")) co->up_axis = 2;
        else return bad(name, "' is not an axis; expected y or z", value);
    } else if (!strcmp(name, "--ground-altitude")) {
        if (!parse_double(value, &co->ground_altitude_km) || fabs(co->ground_altitude_km) > 100.0)
            return bad(name, "' is not an altitude; expected km in [-100, 100]", value);
    } else if (!strcmp(name, "--camera-position")) {
        if (!parse_triple(value, co->camera_position) || fabs(co->camera_position[0]) > 1e15 ||
            fabs(co->camera_position[1]) > 1e15 || fabs(co->camera_position[2]) > 1e15)
            return bad(name, "' is not a position; expected X,Y,Z in world units (three finite numbers)", value);
        co->has_camera_position = true;
    } else if (!strcmp(name, "--aerial-perspective")) {
        if (!strcmp(value, "march")) co->aerial = AERIAL_MARCH;
        else if (!strcmp(value, "volume")) co->aerial = AERIAL_VOLUME;
        else if (!strcmp(value, "auto")) co->aerial = AERIAL_AUTO;
        else return bad(name, "' is not a method; expected march, volume or auto", value);
    } else if (!strcmp(name, "--ap-volume-size")) {
        char tail = 0;
        unsigned *z = co->ap_size;
        if (sscanf(value, "%ux%ux%u%c", &z[0], &z[1], &z[2], &tail) != 3 || z[0] < 1 || z[1] < 1 || z[2] < 1 ||
            z[0] > 512 || z[1] > 512 || z[2] > 512)
            return bad(name, "' is not a volume size; expected WxHxD froxels, 1 to 512 each (e.g. 32x32x32)", value);
    } else if (!strcmp(name, "--ap-volume-range")) {
        if (!parse_double(value, &co->ap_range_km) || !(co->ap_range_km >= 0.01 && co->ap_range_km <= 1000.0))
            return bad(name, "' is not a range; expected km in [0.01, 1000]", value);
    } else if (!strcmp(name, "--ap-volume-slices")) {
        if (!strcmp(value, "linear")) co->ap_distribution = 1.0;
        else if (!strcmp(value, "quadratic")) co->ap_distribution = 2.0;
        else return bad(name, "' is not a slice spacing; expected linear or quadratic", value);
    } else if (!strcmp(name, "--aovs")) co->aovs = true;
    return 0;
}

int composite_options_extract(composite_options *co, int *argc, char **argv)
{
    *co = (composite_options){.world_unit_m = 1.0, .up_axis = 2, .aerial = AERIAL_AUTO, .ap_size = {32, 32, 32},
                              .ap_range_km = 32.0, .ap_distribution = 2.0};
    const char *needs_composite = NULL;
    int out = 1;
    /* The whole command line, before this module's flags leave argv: the composite's header names them. Static:
     * one command line per process, still reachable at exit. */
    static char **saved;
    free(saved);
    saved = malloc(((size_t)*argc + 1) * sizeof *saved);
    if (saved) memcpy(saved, argv, ((size_t)*argc + 1) * sizeof *saved);
    co->argc_all = saved ? *argc : 0, co->argv_all = saved;
    for (int i = 1; i < *argc; ++i) {
        const char *a = argv[i];
        const composite_flag *f = NULL;
        for (int k = 0; k < COMPOSITE_FLAG_COUNT; ++k)
            if (!strcmp(a, composite_flags[k].name)) f = &composite_flags[k];
        if (!f) {
            /* A shared flag: kept for options_parse; noted where the composite needs to know it was given. The
             * next word is its value for every shared flag that takes one, and is kept with it. */
            if (!strcmp(a, "--yaw") || !strcmp(a, "--pitch")) co->has_orientation = true;
            if (!strcmp(a, "--fov")) co->has_fov = true;
            if (!strcmp(a, "--width") || !strcmp(a, "--height")) co->has_size = true;
            argv[out++] = argv[i];
            continue;
        }
        const char *value = NULL;
        if (f->takes_value) {
            if (i + 1 >= *argc) return bad(a, "needs a value (vksky --help)", NULL);
            value = argv[++i];
        }
        if (take(co, a, value) != 0) return 2;
        /* The aerial-perspective method and its volume apply to --aovs too (the same composite frame). */
        if (strcmp(a, "--composite") && strcmp(a, "--aovs") && strcmp(a, "--aerial-perspective") &&
            strncmp(a, "--ap-volume-", 12) && !needs_composite)
            needs_composite = a;
    }
    argv[out] = NULL;
    *argc = out;
    if (needs_composite && !co->input) return bad(needs_composite, "only with --composite", NULL);
    if (co->depth && (co->position || co->position_layer))
        return bad("--depth", "not with --position or --position-layer (one of a depth or a position pass)", NULL);
    if (co->input && co->aovs) return bad("--aovs", "not with --composite (its output always has the AOV layers)", NULL);
    if (co->input && co->has_size)
        return bad(co->has_size ? "--width/--height" : "", "not with --composite (the size is the input's)", NULL);
    return 0;
}

bool composite_auto_volume(const composite_options *co, double max_error, unsigned size[3], double *range_km,
                           double *distribution, char *why, size_t why_size)
{
    if (!(max_error > 0.0)) {
        snprintf(why, why_size, "no --max-error: the accurate march");
        return false;
    }
    /* The march, unless a measured volume shape (the one the flags gave, if any) is cheaper within the error. */
    const ap_trade *march = &ap_trade_table[0], *best = march;
    for (int i = 1; i < AP_TRADE_COUNT; ++i) {
        const ap_trade *t = &ap_trade_table[i];
        bool shape_ok = !co->ap_shape_given || (t->size[0] == co->ap_size[0] && t->size[1] == co->ap_size[1] &&
                                                t->size[2] == co->ap_size[2] && t->range_km == co->ap_range_km &&
                                                t->distribution == co->ap_distribution);
        if (shape_ok && t->err_mean <= max_error && t->gpu_ms < best->gpu_ms) best = t;
    }
    if (best == march) {
        snprintf(why, why_size, "no measured froxel volume%s is within --max-error %g (the march: %.2g): the march",
                 co->ap_shape_given ? " of the shape given" : "", max_error, march->err_mean);
        return false;
    }
    memcpy(size, best->size, sizeof best->size);
    *range_km = best->range_km, *distribution = best->distribution;
    snprintf(why, why_size, "--max-error %g allows the volume %ux%ux%u %s (measured error on its worst view class "
             "%.2g vs the march's %.2g; %.2f ms vs %.2f ms at 1080p on an H100)", max_error, size[0], size[1], size[2],
             best->distribution == 1.0 ? "linear" : "quadratic", best->err_mean, march->err_mean, best->gpu_ms,
             march->gpu_ms);
    return true;
}
