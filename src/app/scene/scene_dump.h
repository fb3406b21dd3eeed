/* Scene files: --dump-scene, the effective options (defaults, scene, flags) printed as a scene file in the schema
 * of scene.h; loading the dump back reproduces the same options. */
#ifndef VKSKY_APP_SCENE_DUMP_H
#define VKSKY_APP_SCENE_DUMP_H
#include "app/cli/options_struct.h"
#include <stdio.h>

/* Print the scene *o describes as JSON (the schema in scene.h, every field present). 0: ok; 1: out of memory. */
int scene_dump(const options *o, FILE *out);
#endif
