/* --bench's report, one format for its two hosts (app/runs/headless.c over the renderer, app/runs/bench_host.c over
 * include/vksky.h): per-pass GPU medians, then the frame's. No src/sky or src/lib header (bench_host.c is an API host:
 * tests/layering_test.sh). */
#ifndef VKSKY_APP_RUNS_BENCH_REPORT_H
#define VKSKY_APP_RUNS_BENCH_REPORT_H
#include <stdbool.h>

/* What a benchmark measured over n frames (each array n long; sorted in place when printed). */
typedef struct bench_figures {
    int n;                       /* 0: cut short (a stop, a failure): nothing printed */
    bool timed;                  /* the queue has timestamps: the pass lines and the frame's GPU time */
    bool multiscatter;           /* the variant has the multi-scattering LUT */
    double *lut_ms[2];           /* the transmittance and multi-scattering LUT passes, of frames that rebuild them */
    int pass_count;
    const char *const *names;    /* the passes of a steady-state frame, in order */
    double *const *per_pass;     /* their GPU ms per frame (a repeated pass's runs added up) */
    double *gpu_total, *wall;    /* a steady-state frame's GPU and wall ms */
    double cpu_per_frame;        /* the process's CPU ms per steady-state frame */
    double *luts_wall;           /* the wall ms of frames that rebuild the LUTs */
    bool async;                  /* those LUTs on the compute queue (--async-luts) */
} bench_figures;
/* The median of v[0..n) (sorted in place). */
double bench_median(double *v, int n);
/* The report on stdout: "pass NAME gpu_ms", "frame gpu_ms .. wall_ms ..", "frame cpu_ms", "frame_luts wall_ms". */
void bench_report_print(const bench_figures *b);
/* --bench with --render and a sequence: the frames to disk, timed. */
void bench_report_sequence(int frames, int outputs, double wall_s, double cpu_ms, int slots, int threads);
#endif
