/* The command-line flags: names, argument kinds, inclusive ranges and help lines, in one table that both the flag
 * parser (app/options) and the scene loader (app/scene: a field that has a flag has that flag's range) read, so
 * neither includes the other for it. A new flag is one row in flags.c plus its case in options.c's apply(). */
#ifndef VKSKY_APP_FLAGS_H
#define VKSKY_APP_FLAGS_H
#include <stdbool.h>
#include <stddef.h>

typedef enum { ARG_NONE, ARG_INT, ARG_DOUBLE, ARG_STRING, ARG_TRIPLE } arg_kind;   /* TRIPLE: "R,G,B" in [min, max] */

typedef struct flag {
    const char *name;
    arg_kind kind;
    double min, max;           /* inclusive range for numbers */
    const char *help;
} flag;

extern const flag flags_table[];
extern const int flags_count;

/* The flag named by the first name_len characters of `name` (a "--name=value" argument passes the length of its
 * "--name"); NULL if there is none. */
const flag *flags_find(const char *name, size_t name_len);

/* The inclusive range of a numeric flag; false if the flag is unknown or takes no range. */
bool flags_range(const char *flag_name, double *min, double *max);
#endif
