/* --bench's figures and report, one for its two hosts (app/runs/headless.c over the renderer, app/runs/bench_host.c
 * over include/vksky.h): the LUT passes of frames that rebuild them, per-pass GPU medians of steady-state frames, the
 * frame's GPU, wall and CPU time. No src/sky or src/lib header (bench_host.c is an API host: tests/layering_test.sh). */
#ifndef VKSKY_APP_RUNS_BENCH_REPORT_H
#define VKSKY_APP_RUNS_BENCH_REPORT_H
#include <stdbool.h>

#define BENCH_MAX_PASSES 64

/* What a benchmark measured over n frames (each array n long). */
typedef struct bench_figures {
    int n;
    bool timed;                  /* the queue has timestamps: the pass lines and the frame's GPU time */
    bool multiscatter;           /* a multiscatter_lut pass was timed */
    bool async;                  /* the LUT-rebuilding frames had their LUTs on the compute queue (--async-luts) */
    double *lut_ms[2];           /* the transmittance and multi-scattering LUT passes, of frames that rebuild them */
    double *luts_wall;           /* the wall ms of those frames */
    int pass_count;
    const char *names[BENCH_MAX_PASSES];   /* a steady-state frame's passes, in order (the names are the timer's) */
    double *per_pass[BENCH_MAX_PASSES];    /* their GPU ms per frame (a repeated pass's runs added up) */
    double *gpu_total, *wall;    /* a steady-state frame's GPU and wall ms */
    double cpu_start;            /* the process's CPU ms when the steady-state frames began */
} bench_figures;

/* The median of v[0..n) (sorted in place): every benchmark's figure (tools/event_bench.c's too). */
double bench_median(double *v, int n);
/* Room for n frames. 0, or 1 (out of memory; bench_figures_end still frees what was made). */
int bench_figures_begin(bench_figures *b, int n);
/* A LUT-rebuilding frame's timed pass (the LUT passes are kept, others ignored). */
void bench_figures_lut_pass(bench_figures *b, int frame, const char *name, double ms);
/* A steady-state frame's timed pass (added to its pass's entry and to the frame's GPU total). */
void bench_figures_pass(bench_figures *b, int frame, const char *name, double ms);
/* The report on stdout ("pass NAME gpu_ms", "frame gpu_ms .. wall_ms ..", "frame cpu_ms", "frame_luts wall_ms") over
 * `frames` frames (0: a cut-short run, nothing printed); the arrays are sorted. */
void bench_report_print(bench_figures *b, int frames);
void bench_figures_end(bench_figures *b);
/* --bench with --render and a sequence: the frames to disk, timed. */
void bench_report_sequence(int frames, int outputs, double wall_s, double cpu_ms, int slots, int threads);
#endif
