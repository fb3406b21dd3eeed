/* Progress on stderr (see progress.h). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "app/runs/progress.h"
#include <time.h>
#include <unistd.h>

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void progress_begin(progress *p, FILE *out, bool quiet, const char *what, long total)
{
    *p = (progress){.out = quiet ? NULL : out, .what = what, .total = total > 0 ? total : 1, .start_s = now_s()};
    if (p->out) p->terminal = isatty(fileno(p->out));
    progress_update(p, 0);
}

/* "1h02m", "3m05s", "12s". */
static void format_duration(char *buf, size_t n, double s)
{
    long t = (long)(s + 0.5);
    if (t >= 3600) snprintf(buf, n, "%ldh%02ldm", t / 3600, t / 60 % 60);
    else if (t >= 60) snprintf(buf, n, "%ldm%02lds", t / 60, t % 60);
    else snprintf(buf, n, "%lds", t);
}

void progress_update(progress *p, long done)
{
    if (!p->out) return;
    p->done = done;
    double fraction = (double)done / (double)p->total, elapsed = now_s() - p->start_s;
    if (p->terminal) {
        enum { WIDTH = 30 };
        char bar[WIDTH + 1], eta[32] = "?";
        int fill = (int)(fraction * WIDTH);
        for (int i = 0; i < WIDTH; ++i) bar[i] = i < fill ? '#' : '.';
        bar[WIDTH] = '\0';
        /* The rate so far predicts the rest (bands cost about the same). */
        if (done > 0) format_duration(eta, sizeof eta, elapsed * (1.0 - fraction) / fraction);
        fprintf(p->out, "\rvksky: %s [%s] %3d %% ETA %s   ", p->what, bar, (int)(100.0 * fraction), eta);
        fflush(p->out);
        return;
    }
    int decile = (int)(10.0 * fraction);
    if (done == 0 || decile > p->last_decile) {
        if (done > 0 && done < p->total) fprintf(p->out, "vksky: %s: %d %%\n", p->what, 10 * decile);
        p->last_decile = decile;
    }
}

void progress_end(progress *p)
{
    if (!p->out) return;
    char took[32];
    format_duration(took, sizeof took, now_s() - p->start_s);
    if (p->terminal) progress_update(p, p->total), fputc('\n', p->out);
    fprintf(p->out, "vksky: %s: 100 %% in %s\n", p->what, took);
}
