/* Scene files: reading and validating one field of the JSON (types, ranges, unknown and repeated fields) and the
 * one-line message naming the field when it is wrong. The loader (scene.c) walks the sections with these; the
 * dump (scene_dump.c) writes the same words back. Every reader returns 0 (ok, or the field is absent: the target
 * keeps its value) or 2 (message printed on stderr). */
#ifndef VKSKY_APP_SCENE_VALIDATE_H
#define VKSKY_APP_SCENE_VALIDATE_H
#include "app/cli/options_struct.h"
#include <cjson/cJSON.h>
#include <stdbool.h>
#include <stddef.h>

#define PATH_LEN 160

/* Ranges of the fields that have no command-line flag. */
#define RADIUS_MIN 1.0
#define RADIUS_MAX 1e6
#define COEFF_MAX 1000.0
#define HEIGHT_MIN 0.01
#define HEIGHT_MAX 1000.0

typedef struct scene_range {
    double min, max;
    bool integer;
    const char *flag;   /* the flag the range comes from (NULL: a scene-only field) */
} scene_range;

typedef struct scene_ctx {
    char file[PATH_LEN];   /* printable copy of the file name, for messages */
    options *o;
} scene_ctx;

/* The words of the enumerated fields, index = the value (static in the header so that COUNT sees their length). */
static const char *const tonemap_words[] = {"clamp", "reinhard", "aces"};          /* VKSKY_TONEMAP_* order */
static const char *const mode_words[] = {"march", "skyview", "auto", "fill"};       /* sky_mode_choice order */
static const char *const pass_words[] = {"fragment", "compute", "auto"};            /* sky_pass_kind order */
static const char *const lut_format_words[] = {"f16", "f32"};
static const char *const phase_words[] = {"henyey-greenstein", "cornette-shanks"};  /* options.mie_phase */
static const char *const preset_words[] = {"low", "medium", "high", "ultra", "lesson", "cpu"};
#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* A printable, bounded copy (control characters -> '?'): messages stay one line whatever the file holds. */
void scene_printable(char *dst, size_t n, const char *src);
/* "parent.key" (or "key" at the top level) into out[PATH_LEN], cut when too long. */
void scene_join(char *out, const char *parent, const char *key);
/* "vksky: FILE: path: message" on stderr; returns 2. */
int scene_fail(const scene_ctx *c, const char *path, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* "a number", "an object", ... for messages. */
const char *scene_type_of(const cJSON *j);
/* "a, b<last_sep>c" into out[n]. */
void scene_word_list(char *out, size_t n, const char *const *words, int count, const char *last_sep);

/* The range of a field that has a command-line flag: the flag's, from the flag table (aborts if the table has
 * none: a programming error); and of a scene-only field. */
scene_range scene_flag_range(const char *flag, bool integer);
scene_range scene_only_range(double min, double max);

/* Unknown and repeated fields of an object. */
int scene_check_fields(const scene_ctx *c, const cJSON *obj, const char *path, const char *const *names, int count);
/* Field `key` of `obj` (NULL if absent); its path in *path. */
const cJSON *scene_field(const cJSON *obj, const char *key, const char *parent, char *path);

int scene_get_object(const scene_ctx *c, const cJSON *obj, const char *key, const char *parent, const cJSON **out);
int scene_check_number(const scene_ctx *c, const cJSON *j, const char *path, scene_range r, double *out);
int scene_get_number(const scene_ctx *c, const cJSON *obj, const char *key, const char *parent, scene_range r,
                     double *out);
int scene_get_int(const scene_ctx *c, const cJSON *obj, const char *key, const char *parent, scene_range r, int *out);
/* An array of exactly n numbers in r; *given tells whether the field was there. */
int scene_get_array(const scene_ctx *c, const cJSON *obj, const char *key, const char *parent, scene_range r, int n,
                    double *out, bool *given);
int scene_get_bool(const scene_ctx *c, const cJSON *obj, const char *key, const char *parent, bool *out);
/* One of `words`: its index into *out. */
int scene_get_word(const scene_ctx *c, const cJSON *obj, const char *key, const char *parent, const char *const *words,
                   int count, int *out);
#endif
