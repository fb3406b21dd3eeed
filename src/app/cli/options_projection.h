/* --projection and --quiet (issue 13): parsing, and what a projection makes of the other flags (the image size,
 * yaw/pitch/fov ignored, bloom off for equirect and cube maps). Hooks in app/cli/options.c. */
#ifndef VKSKY_APP_OPTIONS_PROJECTION_H
#define VKSKY_APP_OPTIONS_PROJECTION_H
#include "app/cli/options_struct.h"

/* One of this file's flags (--projection, --quiet): 0, or 2 with the message printed. */
int options_projection_apply(options *o, const char *flag_name, const char *value);
/* After every flag: the projection's image size and notes on flags it ignores (one stderr line each); 0 or 2. */
int options_projection_finish(options *o, int argc, char **argv);
/* The sun's illuminance reaching the camera: top-of-atmosphere illuminance x the transmittance along the sun's
 * direction from the camera's altitude (the CPU reference), 0 where the planet hides the sun. */
void options_sun_at_camera(const options *o, double out[3]);
/* The projection's name as --projection spells it. */
const char *options_projection_name(int projection);
#endif
