/* Shipped scenes by name: `--scene mars` finds mars.json in the installed data directory (found relative to the
 * running binary, so an installed tree can be moved: <prefix>/bin/vksky -> <prefix>/share/vksky/scenes) and then in
 * the source tree the binary was built from. `--list-scenes` lists them with the first sentence of each
 * description. */
#ifndef VKSKY_APP_SCENE_FIND_H
#define VKSKY_APP_SCENE_FIND_H
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* A --scene value that names a shipped scene rather than a file: no '/', no ".json" ending, not an existing file. */
bool scene_is_name(const char *value);
/* The path of the shipped scene NAME (out, n bytes); false with one line on stderr naming the directories searched and
 * the shipped names when there is none. */
bool scene_find(const char *name, char *out, size_t n);
/* --list-scenes: "NAME  first sentence of the description" per shipped scene, in name order; 0 ok, 1 none found. */
int scene_list(FILE *out);
#endif
