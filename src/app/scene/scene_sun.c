/* Scene fields for the sun by date and place (scene_sun.h). */
#include "app/scene/scene_sun.h"
#include "app/cli/bad_value.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

static int bad(const char *file, const char *field, const char *msg)
{
    fprintf(options_report_stream(), "vksky: %s: sun.%s: %s\n", file, field, msg);
    return 2;
}

/* A number field in [lo, hi]; absent: untouched, *set false. */
static int number(const char *file, const cJSON *sun, const char *key, double lo, double hi, double *out, bool *set)
{
    const cJSON *j = cJSON_GetObjectItemCaseSensitive(sun, key);
    if (set) *set = false;
    if (!j) return 0;
    char msg[120];
    if (!cJSON_IsNumber(j) || !isfinite(j->valuedouble)) {
        snprintf(msg, sizeof msg, "expected a number in [%g, %g]", lo, hi);
        return bad(file, key, msg);
    }
    if (j->valuedouble < lo || j->valuedouble > hi) {
        snprintf(msg, sizeof msg, "%.17g is out of range; expected a number in [%g, %g]", j->valuedouble, lo, hi);
        return bad(file, key, msg);
    }
    *out = j->valuedouble;
    if (set) *set = true;
    return 0;
}

static int text(const char *file, const cJSON *sun, const char *key, sun_place *p,
                int (*parse)(sun_place *, const char *, const char *))
{
    const cJSON *j = cJSON_GetObjectItemCaseSensitive(sun, key);
    if (!j) return 0;
    if (!cJSON_IsString(j))
        return bad(file, key, !strcmp(key, "date") ? "expected a string \"YYYY-MM-DD\"" : "expected a string \"HH:MM[:SS]\"");
    char what[200];
    snprintf(what, sizeof what, "%s: sun.%s", file, key);
    return parse(p, what, j->valuestring);
}

int scene_sun_parse(const char *file, const cJSON *sun, options *o)
{
    sun_place *p = &o->place;
    double ignored = 0.0;
    if (text(file, sun, "date", p, sun_place_parse_date) || text(file, sun, "time", p, sun_place_parse_time) ||
        number(file, sun, "utc_offset_h", -SUN_PLACE_OFFSET_MAX_H, SUN_PLACE_OFFSET_MAX_H, &p->when.utc_offset_h, NULL) ||
        number(file, sun, "latitude_deg", -90, 90, &p->where.latitude_deg, &p->has_latitude) ||
        number(file, sun, "longitude_deg", -180, 180, &p->where.longitude_deg, &p->has_longitude) ||
        number(file, sun, "elevation_m", SUN_PLACE_ELEVATION_MIN_M, SUN_PLACE_ELEVATION_MAX_M, &p->where.elevation_m, NULL) ||
        number(file, sun, "computed_elevation_deg", -90, 90, &ignored, NULL) ||
        number(file, sun, "computed_azimuth_deg", -360, 360, &ignored, NULL))
        return 2;
    const char *angle = cJSON_GetObjectItemCaseSensitive(sun, "elevation_deg") ? "elevation_deg"
                        : cJSON_GetObjectItemCaseSensitive(sun, "azimuth_deg") ? "azimuth_deg" : NULL;
    if (angle && sun_place_any(p)) {
        fprintf(options_report_stream(), "vksky: %s: sun.%s: not with sun.date/time/latitude_deg/longitude_deg; give the sun either by "
                        "angles or by date and place\n", file, angle);
        return 2;
    }
    return 0;
}

bool scene_sun_by_place(const options *o) { return sun_place_any(&o->place); }

bool scene_sun_dump(cJSON *sun, const options *o)
{
    if (!sun_place_any(&o->place)) return true;
    const sun_place *p = &o->place;
    char date[16], time[16];
    sun_place_format_date(p, date);
    sun_place_format_time(p, time);
    return cJSON_AddStringToObject(sun, "date", date) && cJSON_AddStringToObject(sun, "time", time) &&
           cJSON_AddNumberToObject(sun, "utc_offset_h", p->when.utc_offset_h) &&
           cJSON_AddNumberToObject(sun, "latitude_deg", p->where.latitude_deg) &&
           cJSON_AddNumberToObject(sun, "longitude_deg", p->where.longitude_deg) &&
           cJSON_AddNumberToObject(sun, "elevation_m", p->where.elevation_m) &&
           cJSON_AddNumberToObject(sun, "computed_elevation_deg", o->view.sun_elevation_deg) &&
           cJSON_AddNumberToObject(sun, "computed_azimuth_deg", o->view.sun_azimuth_deg);
}
