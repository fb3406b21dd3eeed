/* --help, generated from the flag table (the parser passes its rows): grouped (output, camera, sun, atmosphere, quality,
 * diagnostics), "  --flag METAVAR" in one column and the description in the next, every description starting in the
 * same column, wrapped at HELP_COLUMNS. */
#ifndef VKSKY_APP_HELP_H
#define VKSKY_APP_HELP_H
#include <stdbool.h>
#include <stdio.h>

#define HELP_COLUMNS 100

/* One flag as the table holds it: its help text is "METAVAR  description" when it takes a value. */
typedef struct help_entry {
    const char *name;
    bool takes_value;
    const char *help;
} help_entry;

void help_print(FILE *out, const help_entry *flags, int count);
/* Flags outside the table (a mode's own, e.g. compositing) in the same columns: "\nTITLE:\n", the preamble as it is
 * (usage lines, or NULL), then the flags in the order given. */
void help_print_section(FILE *out, const char *title, const char *preamble, const help_entry *flags, int count);
/* The group a flag is listed under; NULL for a flag no group names (tests/help_test.sh fails on "other:"). */
const char *help_group_of(const char *flag_name);
#endif
