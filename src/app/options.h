/* Command-line options: parsing and validation. Every bad input is one line on stderr naming the flag and the
 * accepted values; the caller exits with status 2. */
#ifndef VKSKY_APP_OPTIONS_H
#define VKSKY_APP_OPTIONS_H
#include "app/options_struct.h"
#include "sky/renderer.h"
#include <stdbool.h>
#include <stdio.h>

/* The options' scene features for the renderer. */
sky_features options_features(const options *o);
double options_sun_radius_rad(const options *o);

/* 0: ok; 2: bad input (message printed). */
int options_parse(options *o, int argc, char **argv);
void options_print_help(FILE *out);
#endif
