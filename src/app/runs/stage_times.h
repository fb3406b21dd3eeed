/* Where a pipelined run's time goes, stage by stage (issue 27: --timings with a sequence or a banded render). Each
 * stage's wall time is summed over the threads that run it (several frames encode at once), so a stage's total
 * against the run's wall time says how many threads it kept busy, and what stays serial per frame caps frames/s. */
#ifndef VKSKY_APP_STAGE_TIMES_H
#define VKSKY_APP_STAGE_TIMES_H
#include <stdio.h>

typedef enum stage_kind {
    STAGE_PRODUCE,     /* the producer: a frame's options, scene, record and submit (its slot waits included) */
    STAGE_SLOT_WAIT,   /* ... of which waiting for a free slot (ring.slot_free, ring.drain) */
    STAGE_GPU_WAIT,    /* consumers waiting for a frame's fence (ring.gpu_done) */
    STAGE_CONVERT,     /* EXR pixels into output units (light_exr_pixels) */
    STAGE_WRITE,       /* the files: header, pack and compress, write, fsync, rename */
    STAGE_COUNT
} stage_kind;

/* A moment: wall time and the calling thread's CPU time. */
typedef struct stage_mark {
    double wall_ms, cpu_ms;
} stage_mark;
stage_mark stage_mark_now(void);
/* Adds the time since `start` (taken on this thread) to a stage: wall, and this thread's CPU time (not its helper
 * threads': with --threads 1 a frame's encode runs on the calling thread, so the CPU column is the whole cost). */
void stage_add_since(stage_kind k, stage_mark start);
/* The table on `out`: per stage, wall and CPU ms in all and per unit (`units` frames or bands, named by `unit`), the commit's
 * share of the writes (io_atomic_commit_ms), and the wall time since stage_begin. */
void stage_begin(void);
void stage_report(FILE *out, const char *what, int units, const char *unit, int encoders, int threads);
#endif
