/* --projection and --quiet (see options_projection.h). */
#include "app/cli/options_projection.h"
#include "app/cli/bad_value.h"
#include "app/scene/light.h"
#include "sky/projection.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

static const char *const projection_words[] = {"perspective", "equirect", "cubemap", "fisheye"};

const char *options_projection_name(int projection)
{
    return projection >= 0 && projection < 4 ? projection_words[projection] : projection_words[0];
}

int options_projection_apply(options *o, const char *flag_name, const char *value)
{
    if (!strcmp(flag_name, "--quiet")) {
        o->quiet = true;
        return 0;
    }
    for (int i = 0; i < 4; ++i)
        if (!strcmp(value, projection_words[i])) {
            o->view.projection = i;
            return 0;
        }
    fprintf(options_report_stream(),
            "vksky: --projection: unknown value '%s'; expected perspective, equirect, cubemap or fisheye\n", value);
    return 2;
}

void options_sun_at_camera(const options *o, double out[3]) { light_sun_at_camera(o, out); }

/* Whether the command line names this flag (alone or as --flag=value). */
static bool given(int argc, char **argv, const char *flag)
{
    size_t n = strlen(flag);
    for (int i = 1; i < argc; ++i)
        if (!strncmp(argv[i], flag, n) && (argv[i][n] == '\0' || argv[i][n] == '=')) return true;
    return false;
}

int options_projection_finish(options *o, int argc, char **argv)
{
    int p = o->view.projection;
    if (o->dump_scene && p != SKY_PROJECTION_PERSPECTIVE) {
        /* The sun as a separate light (beside a --no-sun-disc map): what the EXR header's vksky:sunDirection and
         * vksky:sunIlluminance say. On stderr: stdout stays pure scene JSON; environment maps only (a perspective
         * dump's stderr stays empty, as scripts and the fuzzers expect of a run that exits 0). */
        double d[3];
        projection_dir_from_angles(o->view.sun_azimuth_deg, o->view.sun_elevation_deg, d);
        double e[3], c[3];
        light_sun(o, e);
        options_sun_at_camera(o, c);
        fprintf(options_report_stream(),
                "vksky: sun direction %.6f %.6f %.6f (+Y up, OpenEXR latlong axes), illuminance %g %g %g at the "
                "top of the atmosphere, %.6g %.6g %.6g at the camera\n", d[0], d[1], d[2], e[0], e[1], e[2],
                c[0], c[1], c[2]);
    }
    if (p == SKY_PROJECTION_PERSPECTIVE) return 0;
    const char *name = projection_words[p];
    /* An environment map looks every way at once: the camera's orientation and field of view do not apply (its
     * altitude does). */
    if (given(argc, argv, "--yaw") || given(argc, argv, "--pitch") || given(argc, argv, "--fov"))
        fprintf(options_report_stream(),
                "vksky: note: --projection %s ignores --yaw, --pitch and --fov (the map covers every "
                "direction; --altitude applies)\n", name);
    int w, h;
    projection_image_size((sky_projection)p, o->width, o->height, &w, &h);
    if (given(argc, argv, "--height") && h != o->height)
        fprintf(options_report_stream(),
                "vksky: note: --projection %s makes the image %dx%d from --width %d; --height ignored\n", name,
                w, h, o->width);
    if (p == SKY_PROJECTION_EQUIRECT && o->width < 2) {
        fprintf(options_report_stream(),
                "vksky: --width: %d is too small for an equirect map; expected 2 or more\n", o->width);
        return 2;
    }
    o->width = w, o->height = h;
    /* Bloom spreads a lens's glare over neighbouring pixels; on a map that lights a scene it would smear light into
     * directions it does not come from. Off, always (docs/readme/envmap.md). */
    if (p == SKY_PROJECTION_EQUIRECT || p == SKY_PROJECTION_CUBEMAP) o->view.bloom = false;
    return 0;
}
