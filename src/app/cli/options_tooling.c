/* Issue 14's flags (options_tooling.h). */
#include "app/cli/options_tooling.h"
#include "app/cli/bad_value.h"
#include "app/scene/scene_find.h"
#include <limits.h>
#include <stdio.h>
#include <string.h>

int options_tooling_apply(options *o, const char *n, const char *value, double x)
{
    sun_place *p = &o->place;
    if (!strcmp(n, "--sun-elevation") || !strcmp(n, "--sun-azimuth")) {
        if (!o->sun_angles_flag) o->sun_angles_flag = n;
        if (!strcmp(n, "--sun-elevation")) o->sun_elevation_flag = true;
        else o->sun_azimuth_flag = true;
        return -1;
    }
    bool place_flag = true;
    if (!strcmp(n, "--date")) {
        if (sun_place_parse_date(p, n, value)) return 2;
    } else if (!strcmp(n, "--time")) {
        if (sun_place_parse_time(p, n, value)) return 2;
    } else if (!strcmp(n, "--utc-offset")) p->when.utc_offset_h = x;
    else if (!strcmp(n, "--latitude")) p->where.latitude_deg = x, p->has_latitude = true;
    else if (!strcmp(n, "--longitude")) p->where.longitude_deg = x, p->has_longitude = true;
    else if (!strcmp(n, "--elevation-m")) p->where.elevation_m = x;
    else if (!strcmp(n, "--list-scenes")) o->list_scenes = true, place_flag = false;
    else return -1;
    if (place_flag) p->from_flags = true;
    return 0;
}

bool options_tooling_first_pass(const char *n)
{
    static const char *const names[] = {"--date", "--time", "--utc-offset", "--latitude", "--longitude", "--elevation-m",
                                        "--animate" /* time=FROM:TO gives the first frame's time */};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
        if (!strcmp(n, names[i])) return true;
    return false;
}

int options_tooling_resolve(options *o)
{
    if (o->sun_angles_flag && o->place.from_flags) {
        fprintf(options_report_stream(),
                "vksky: %s: not with --date/--time/--latitude/--longitude; give the sun either by angles or by "
                "date and place\n", o->sun_angles_flag);
        return 2;
    }
    if (!sun_place_any(&o->place)) return 0;
    double elevation, azimuth;
    if (sun_place_resolve(&o->place, &elevation, &azimuth)) return 2;
    if (!o->sun_elevation_flag) o->view.sun_elevation_deg = elevation;
    if (!o->sun_azimuth_flag) o->view.sun_azimuth_deg = azimuth;
    /* An angle flag overrides its angle of the scene's dated sun; the sun is then given by angles (and dumped so). */
    if (o->sun_angles_flag) sun_place_init(&o->place);
    return 0;
}

const char *options_tooling_scene_path(const char *value)
{
    static char path[PATH_MAX];
    if (!scene_is_name(value)) return value;
    return scene_find(value, path, sizeof path) ? path : NULL;
}
