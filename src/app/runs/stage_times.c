/* Stage timings of a pipelined run (stage_times.h). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "app/runs/stage_times.h"
#include "io/atomic_file.h"
#include <time.h>

static _Atomic long long stage_us[STAGE_COUNT], stage_cpu_us[STAGE_COUNT];
static double begin_ms, commit_before_ms;

static double clock_ms(clockid_t id)
{
    struct timespec t;
    clock_gettime(id, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

stage_mark stage_mark_now(void) { return (stage_mark){clock_ms(CLOCK_MONOTONIC), clock_ms(CLOCK_THREAD_CPUTIME_ID)}; }

void stage_add_since(stage_kind k, stage_mark start)
{
    stage_mark now = stage_mark_now();
    stage_us[k] += (long long)((now.wall_ms - start.wall_ms) * 1e3);
    stage_cpu_us[k] += (long long)((now.cpu_ms - start.cpu_ms) * 1e3);
}

void stage_begin(void)
{
    for (int k = 0; k < STAGE_COUNT; ++k) stage_us[k] = stage_cpu_us[k] = 0;
    begin_ms = clock_ms(CLOCK_MONOTONIC);
    commit_before_ms = io_atomic_commit_ms();
}

void stage_report(FILE *out, const char *what, int units, const char *unit, int encoders, int threads)
{
    static const char *const names[STAGE_COUNT] = {
        "produce    (options, scene, record, submit; slot waits included)",
        "slot wait  (ring.slot_free / ring.drain: the producer waits for a consumer or the GPU)",
        "gpu wait   (ring.gpu_done: a consumer waits for the frame's fence)",
        "convert    (EXR pixels to output units, on the encode threads)",
        "write      (header, pack, compress, write, fsync, rename)"};
    double wall = clock_ms(CLOCK_MONOTONIC) - begin_ms, commit = io_atomic_commit_ms() - commit_before_ms;
    int n = units > 0 ? units : 1;
    fprintf(out, "vksky: timings of the %s (ms summed over threads, the calling thread's CPU; %d %s%s, %d encoder%s x "
                 "%d thread%s):\n", what, units, unit, units == 1 ? "" : "s", encoders, encoders == 1 ? "" : "s",
            threads, threads == 1 ? "" : "s");
    fprintf(out, "  %-90s %10s %9s %10s %9s\n", "stage", "wall", "per", "cpu", "per");
    for (int k = 0; k < STAGE_COUNT; ++k)
        fprintf(out, "  %-90s %10.1f %9.2f %10.1f %9.2f\n", names[k], (double)stage_us[k] * 1e-3,
                (double)stage_us[k] * 1e-3 / n, (double)stage_cpu_us[k] * 1e-3, (double)stage_cpu_us[k] * 1e-3 / n);
    fprintf(out, "  %-90s %10.1f %9.2f\n", "... of the writes: commit (fsync, close, rename; wall)", commit, commit / n);
    fprintf(out, "  %-90s %10.1f %9.2f  (%.2f %ss/s)\n", "the run (wall)", wall, wall / n,
            wall > 0 ? 1e3 * n / wall : 0.0, unit);
}
