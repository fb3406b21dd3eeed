/* The flags of issue 14's tooling that need more than a field: the sun from a date and place (--date, --time,
 * --utc-offset, --latitude, --longitude, --elevation-m), shipped scenes by name (--scene NAME, --list-scenes).
 * Hooks called by options.c; kept here so the shared parser changes by a few lines. */
#ifndef VKSKY_APP_OPTIONS_TOOLING_H
#define VKSKY_APP_OPTIONS_TOOLING_H
#include "app/cli/options_struct.h"

/* Apply one of these flags (x: its parsed number, for numeric ones): 0 ok, 2 bad value (message printed), -1 not one
 * of them (the caller applies it). Also notes --sun-elevation/--sun-azimuth (and returns -1 for them). */
int options_tooling_apply(options *o, const char *flag_name, const char *value, double x);
/* Flags the first parsing pass must see (the sun's elevation feeds --max-error's choice). */
bool options_tooling_first_pass(const char *flag_name);
/* After the flags: refuse a sun given both ways on the command line; a command-line sun by angles drops a scene's
 * date; a date and place sets the view's sun elevation and azimuth. 0 ok, 2 bad (message printed). */
int options_tooling_resolve(options *o);
/* The file for a --scene value: the value itself, or for a shipped scene's name its path (static storage); NULL
 * when a name matches no shipped scene (message printed). */
const char *options_tooling_scene_path(const char *value);
#endif
