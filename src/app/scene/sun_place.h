/* The sun from a date, a time and a place (--date, --time, --utc-offset, --latitude, --longitude, --elevation-m and
 * the scene's sun.date ... fields): text parsing, validation with one-line messages, and the mapping of NREL SPA's
 * compass azimuth onto vksky's --sun-azimuth.
 *
 * Azimuth convention: vksky's azimuth (--sun-azimuth, --yaw) turns clockwise seen from above: dir(az, el) =
 * (cos el cos az, sin el, cos el sin az) with +Y up and the camera's right = forward x +Y, so a larger azimuth lies to
 * the right of a camera looking at a smaller one. That is the compass's sense; so with yaw 0 looking north, vksky's
 * azimuth IS the compass azimuth (0 north, 90 east, 180 south, 270 west) and the mapping is the identity. */
#ifndef VKSKY_APP_SUN_PLACE_H
#define VKSKY_APP_SUN_PLACE_H
#include "model/solar_position.h"
#include <stdbool.h>

typedef struct sun_place {
    bool has_date, has_time, has_latitude, has_longitude;   /* all four are needed; offset and elevation default 0 */
    bool from_flags;             /* some of it came from the command line (not only a scene) */
    solar_moment when;           /* date, local clock time, utc_offset_h (delta_t_s: unused, the default is taken) */
    solar_place where;           /* latitude, longitude, elevation (pressure, temperature: unused, standard taken) */
} sun_place;

/* The accepted ranges (also the flags' table ranges). */
#define SUN_PLACE_OFFSET_MAX_H 18.0
#define SUN_PLACE_ELEVATION_MIN_M -500.0
#define SUN_PLACE_ELEVATION_MAX_M 100000.0

void sun_place_init(sun_place *p);   /* empty (a zeroed sun_place is empty too) */
bool sun_place_any(const sun_place *p);
/* "YYYY-MM-DD" (a real Gregorian date, years 1583-6000) and "HH:MM" or "HH:MM:SS" (00:00:00-23:59:59). On bad text:
 * one line on stderr naming `what` (a flag or a scene field) and what is accepted; returns 2. */
int sun_place_parse_date(sun_place *p, const char *what, const char *text);
int sun_place_parse_time(sun_place *p, const char *what, const char *text);
/* Write "YYYY-MM-DD" / "HH:MM:SS" (for --dump-scene). */
void sun_place_format_date(const sun_place *p, char out[16]);
void sun_place_format_time(const sun_place *p, char out[16]);
/* The sun's apparent elevation and vksky azimuth (= compass azimuth) for a complete date and place. When some but not
 * all of date, time, latitude and longitude are set: one line naming what is missing, returns 2. */
int sun_place_resolve(const sun_place *p, double *elevation_deg, double *azimuth_deg);
#endif
