/* The scene's sun by date and place: sun.date ("YYYY-MM-DD"), sun.time ("HH:MM[:SS]"), sun.utc_offset_h,
 * sun.latitude_deg, sun.longitude_deg, sun.elevation_m, the same as --date ... (app/sun_place), and the output-only
 * sun.computed_elevation_deg / computed_azimuth_deg that --dump-scene writes (accepted as numbers, recomputed). */
#ifndef VKSKY_APP_SCENE_SUN_H
#define VKSKY_APP_SCENE_SUN_H
#include "app/cli/options_struct.h"
#include <cjson/cJSON.h>

/* The field names this adds to the sun object's accepted list. */
#define SCENE_SUN_PLACE_FIELDS "date", "time", "utc_offset_h", "latitude_deg", "longitude_deg", "elevation_m", \
                               "computed_elevation_deg", "computed_azimuth_deg"
/* Read those fields of `sun` into o->place (file: the printable file name for messages). A sun given both by angles
 * (elevation_deg/azimuth_deg) and by date is refused. 0 ok, 2 bad (one line printed). */
int scene_sun_parse(const char *file, const cJSON *sun, options *o);
/* Whether the dump writes the sun by date and place (then without elevation_deg/azimuth_deg). */
bool scene_sun_by_place(const options *o);
/* Add the date, place and the computed sun to the dump's sun object; false when out of memory. */
bool scene_sun_dump(cJSON *sun, const options *o);
#endif
