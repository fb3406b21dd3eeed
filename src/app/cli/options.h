/* Command-line options: parsing and validation. Every bad input is one line on stderr naming the flag and the
 * accepted values; the caller exits with status 2. */
#ifndef VKSKY_APP_OPTIONS_H
#define VKSKY_APP_OPTIONS_H
#include "app/cli/options_struct.h"
#include "sky/renderer.h"
#include <stdbool.h>
#include <stdio.h>

/* The options' scene features for the renderer. */
sky_features options_features(const options *o);
double options_sun_radius_rad(const options *o);

/* Every field at its default: no flag, no scene (Hillaire 2020 Table 1, 1280x720, the lesson's knobs). */
void options_defaults(options *o);
/* 0: ok; 2: bad input (message printed). */
int options_parse(options *o, int argc, char **argv);
/* The same, with the quality choice (--quality auto, --max-error) made for a set of scene classes (quality.h)
 * instead of the view's own: a sequence's frames keep one configuration (sequence.c). 0: the view's class. */
int options_parse_for_classes(options *o, int argc, char **argv, unsigned quality_classes);

/* A sequence frame's options: the base's flags and scene (as read before anything was derived from them) with the
 * animated flags set to their values, then finished as a parse finishes: no text, no second reading of the scene
 * file, no device probe. names[k]: a numeric flag, or "--time" with values[k] in decimal hours. Without an animation
 * the base itself. 0 ok, 2 bad (one line printed). */
int options_frame(const options *base, const char *const *names, const double *values, int count, options *out);
/* F5 in the window: the scene file read again and the command line's flags applied over it, as at start-up (a
 * --sun-elevation given there keeps its value whatever the file now says). 0 ok, 2 bad (one line printed; *fresh
 * then holds nothing to use). */
int options_reload(const options *o, options *fresh);
/* A copy that owns what it points to (a sequence's unresolved options): released apart from src. 0 ok, 1 out of
 * memory (one line printed). */
int options_copy(options *dst, const options *src);
/* What a parse allocated (a sequence's unresolved options); the options stay usable as values. */
void options_release(options *o);

void options_print_help(FILE *out);
#endif
