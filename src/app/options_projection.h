/* --projection and --quiet (issue 13): parsing, and what a projection makes of the other flags (the image size,
 * yaw/pitch/fov ignored, bloom off for equirect and cube maps). Hooks in app/options.c. */
#ifndef VKSKY_APP_OPTIONS_PROJECTION_H
#define VKSKY_APP_OPTIONS_PROJECTION_H
#include "app/options_struct.h"

/* One of this file's flags (--projection, --quiet): 0, or 2 with the message printed. */
int options_projection_apply(options *o, const char *flag_name, const char *value);
/* After every flag: the projection's image size and notes on flags it ignores (one stderr line each); 0 or 2. */
int options_projection_finish(options *o, int argc, char **argv);
/* The projection's name as --projection spells it. */
const char *options_projection_name(int projection);
#endif
