/* Progress of a long render on stderr (issue 13): a bar with an ETA, redrawn in place, when stderr is a terminal;
 * a plain "NN %" line every tenth of the work when it is not (logs, CI); nothing with --quiet. */
#ifndef VKSKY_APP_PROGRESS_H
#define VKSKY_APP_PROGRESS_H
#include <stdbool.h>
#include <stdio.h>

typedef struct progress {
    FILE *out;                 /* NULL: silent */
    bool terminal;
    const char *what;          /* "rendering sky.exr" */
    long total, done;
    double start_s;
    int last_decile;           /* plain lines: the last tenth reported */
} progress;

/* out NULL or quiet: every call does nothing. */
void progress_begin(progress *p, FILE *out, bool quiet, const char *what, long total);
void progress_update(progress *p, long done);
/* The final line (100 %, the time taken). */
void progress_end(progress *p);
#endif
