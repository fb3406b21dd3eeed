/* --bench through the public API (bench_host.h). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "app/runs/bench_host.h"
#include "app/runs/bench_report.h"
#include "app/runs/cpu_time.h"
#include "app/runs/host_ring.h"
#include "app/runs/sequence_frames.h"
#include "app/runs/sequence_host.h"
#include "app/runs/stop.h"
#include "app/scene/light.h"
#include "io/encode_settings.h"
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* One frame, waited for (its LUTs into the cache on a miss, as every headless frame); its timed passes in t (count in
 * *n: 0 without timestamps). */
static int frame(host_commands *h, vksky_renderer *r, const host_view *v, double *wall, vksky_pass_timing *t,
                 uint32_t *n)
{
    if (host_commands_render(h, r, v, NULL, wall) || vksky_renderer_store_luts(r) != VKSKY_SUCCESS) return 1;
    if (vksky_renderer_get_timings(r, t, BENCH_MAX_PASSES, n) != VKSKY_SUCCESS || *n > BENCH_MAX_PASSES) *n = 0;
    return 0;
}

/* Per-pass GPU medians, then the frame: the benchmark's output format (app/runs/bench_report.h). */
static int bench(const options *o, host_commands *h, vksky_renderer *r)
{
    int n = o->bench_frames, status = 0;
    bench_figures b;
    if (bench_figures_begin(&b, n)) status = 1;
    vksky_pass_timing t[BENCH_MAX_PASSES];
    uint32_t c = 0;
    /* Warm-up: lavapipe compiles shaders at first use; GPUs ramp their clocks. Auto exposure (--auto-exposure, or a
     * photometric PNG among the outputs): the frames meter on the GPU, and the meter's passes are timed too. */
    host_view v = {.yaw_deg = o->view.yaw_deg, .pitch_deg = o->view.pitch_deg, .fov_deg = o->view.fov_deg,
                   .exposure = o->view.exposure_ev, .auto_exposure = o->auto_exposure || light_auto_exposure_wanted(o)};
    double w;
    for (int i = 0; i < 3 && !stop_requested() && status == 0; ++i) status = frame(h, r, &v, &w, t, &c);
    /* LUT passes, measured on their own (a frame recomputes them only when the atmosphere changes). */
    v.force_luts = true;
    for (int i = 0; i < n && !stop_requested() && status == 0; ++i) {
        status = frame(h, r, &v, &b.luts_wall[i], t, &c);
        for (uint32_t k = 0; k < c; ++k) bench_figures_lut_pass(&b, i, t[k].name, t[k].gpu_ms);
    }
    /* Steady-state frames. The process's CPU time over them too: on a CPU device (lavapipe) that is the frame's
     * work whatever else the machine runs, where wall and timestamp times grow with the machine's load. */
    v.force_luts = false;
    b.cpu_start = process_cpu_ms();
    for (int i = 0; i < n && !stop_requested() && status == 0; ++i) {
        status = frame(h, r, &v, &b.wall[i], t, &c);
        b.timed = b.timed && c > 0;
        for (uint32_t k = 0; k < c; ++k) bench_figures_pass(&b, i, t[k].name, t[k].gpu_ms);   /* names: the renderer's */
    }
    bench_report_print(&b, stop_requested() || status ? 0 : n);   /* the graceful stop: no figures from a cut-short run */
    bench_figures_end(&b);
    return status;
}

/* --bench with --render and a sequence (issue 27): the frames to disk, timed from the first frame's submit to the
 * last file (the renderer is warm: bench() ran first). */
static int bench_sequence(const options *o, vksky_context *ctx, vksky_scene *scene, vksky_renderer *r)
{
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    double cpu_start = process_cpu_ms();
    int status = sequence_host_render(o, ctx, scene, r, NULL, NULL);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double s = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    int frames = o->frame_last - o->frame_first + 1;
    if (status == 0)
        bench_report_sequence(frames, o->output_count, s, process_cpu_ms() - cpu_start, host_ring_slots_wanted(),
                              io_encode_threads());
    return status;
}

int bench_host_run(const options *o, vksky_context *ctx, vksky_scene *scene, vksky_renderer *r)
{
    host_commands h;
    int status = host_commands_create(&h, ctx) ? 1 : bench(o, &h, r);
    host_commands_destroy(&h);
    if (status == 0 && o->output_count > 0 && sequence_active(o) && !stop_requested())
        status = bench_sequence(o, ctx, scene, r);
    return status;
}
