/* The pipeline cache's directory and the --timings report (see app/runs/startup.h). */
#include "app/runs/startup.h"
#include "app/runs/sequence_frames.h"
#include "gpu/pipeline_cache.h"
#include "io/atomic_file.h"
#include "sky/shaders.h"
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

/* One run's figures: milliseconds of wall time, -1 where not measured. Times "at" are CLOCK_MONOTONIC instants. */
static struct {
    double main_at, before_main, context_at, setup_at;
    double instance, device, cache_open, cache_close, pipelines;
    int variant_builds, lut_cache;
    bool cache_used, instance_reused, kept;
    double frame_begin, frame_end, frame, gpu_luts, gpu_readback, gpu_total;
    bool gpu_timed, frame_done, outputs_done;
    double outputs, outputs_at, commit_before, write;
} t = {.gpu_luts = -1, .gpu_readback = -1};

/* Process start (exec) to now, from the kernel's record of the start (/proc/self/stat's 22nd field, clock ticks
 * since boot, CLOCK_BOOTTIME's origin): the loader and the shared libraries before main. Truncated to a tick (10 ms
 * at USER_HZ 100), so it reads up to one tick long; 0 where /proc is not there. */
static double since_exec_ms(void)
{
    FILE *f = fopen("/proc/self/stat", "r");
    if (!f) return 0.0;
    char buf[1024];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = 0;
    char *p = strrchr(buf, ')');   /* the command name may hold spaces and parentheses */
    unsigned long long ticks = 0;
    /* After ") ": state (3), then fields 4 .. 21, then starttime (22). */
    if (!p || sscanf(p + 2, "%*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %*u %*u %*d %*d %*d %*d %*d %*d %llu",
                     &ticks) != 1)
        return 0.0;
    long hz = sysconf(_SC_CLK_TCK);
    struct timespec b;
    clock_gettime(CLOCK_BOOTTIME, &b);
    double ms = b.tv_sec * 1e3 + b.tv_nsec * 1e-6 - (double)ticks * 1e3 / (double)(hz > 0 ? hz : 100);
    return ms > 0.0 && ms < 60e3 ? ms : 0.0;
}

void startup_begin(void)
{
    t.main_at = now_ms();
    t.before_main = since_exec_ms();
}

bool startup_keep_for_exit(const options *o, int status)
{
#ifdef VKSKY_SANITIZE
    (void)o, (void)status;
    return false;   /* a sanitizer build: LeakSanitizer checks every run, so everything is destroyed */
#else
    const char *env = getenv("VKSKY_TEARDOWN");
    bool full = env && env[0] && strcmp(env, "0") != 0;
    t.kept = !full && status == 0 && !o->validate && o->output_count > 0 && o->bench_frames == 0 &&
             !sequence_active(o) && !o->skip_existing && !o->async_luts;
    return t.kept;
#endif
}

void startup_exit(int status)
{
    if (!t.kept) return;
    fflush(NULL);
    _exit(status);
}

void startup_open_cache(gpu_context *ctx, const options *o)
{
    t.instance = ctx->instance_ms, t.device = ctx->device_ms, t.instance_reused = ctx->instance_reused;
    double start = now_ms();
    t.context_at = start - t.instance - t.device;   /* called straight after gpu_context_create */
    char dir[PATH_MAX];
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    /* XDG: a relative $XDG_CACHE_HOME is invalid and ignored. */
    int n = -1;
    if (xdg && xdg[0] == '/') n = snprintf(dir, sizeof dir, "%s/vksky", xdg);
    else if (home && home[0]) n = snprintf(dir, sizeof dir, "%s/.cache/vksky", home);
    t.cache_used = !o->no_cache && n > 0 && n < (int)sizeof dir;
    gpu_pipeline_cache_open(ctx, t.cache_used ? dir : NULL, sky_shaders_key());
    t.cache_open = now_ms() - start;
    t.setup_at = start + t.cache_open;
}

void startup_close_cache(gpu_context *ctx)
{
    double start = now_ms();
    gpu_pipeline_cache_close(ctx);
    t.cache_close = now_ms() - start;
}

void startup_frame_begin(void)
{
    if (t.frame_done) return;
    t.frame_begin = now_ms();
}

void startup_frame_end_values(double pipelines_ms, int variant_builds, int lut_cache, const char *const *names,
                              const double *ms, uint32_t n)
{
    if (t.frame_done) return;
    t.frame_end = now_ms();
    t.frame = t.frame_end - t.frame_begin;
    t.pipelines = pipelines_ms, t.variant_builds = variant_builds, t.lut_cache = lut_cache;
    t.commit_before = io_atomic_commit_ms();
    t.gpu_timed = n > 0;
    if (t.gpu_timed) t.gpu_luts = t.gpu_readback = 0;
    for (uint32_t k = 0; k < n; ++k) {
        const char *name = names[k];
        size_t len = strlen(name);
        if (len > 4 && !strcmp(name + len - 4, "_lut")) t.gpu_luts += ms[k];
        if (!strcmp(name, "readback")) t.gpu_readback += ms[k];
        t.gpu_total += ms[k];
    }
    t.frame_done = true;
}

void startup_outputs_done(void)
{
    if (!t.frame_done || t.outputs_done) return;
    double now = now_ms();
    t.write = io_atomic_commit_ms() - t.commit_before;
    t.outputs = now - t.frame_end;
    t.outputs_at = now;
    t.outputs_done = true;
}

void startup_report(FILE *out)
{
    if (!t.frame_done) {
        fprintf(out, "vksky: timings (wall ms): instance %.1f, device %.1f; no first image broken down (banded renders "
                     "and --bench are not)\n", t.instance, t.device);
        return;
    }
    startup_outputs_done();
    double end = now_ms(), probe_instance, probe_enumerate;
    gpu_probe_times(&probe_instance, &probe_enumerate);
    double total = end - t.main_at + t.before_main;
    double options = t.context_at - t.main_at - probe_instance - probe_enumerate;
    double setup = t.frame_begin - t.setup_at - t.pipelines;
    fprintf(out, "vksky: timings of the first image (wall ms):\n");
    fprintf(out, "  exec       %8.1f  (process start to main: loader, shared libraries; read to the kernel's tick, "
                 "10 ms)\n", t.before_main);
    fprintf(out, "  options    %8.1f  (flags, scene file, checks)\n", options);
    if (probe_instance + probe_enumerate > 0.0)
        fprintf(out, "  probe      %8.1f  (the device's type for --quality auto: Vulkan loader and instance %.1f, "
                     "devices %.1f)\n", probe_instance + probe_enumerate, probe_instance, probe_enumerate);
    fprintf(out, "  instance   %8.1f%s\n", t.instance, t.instance_reused ? "  (the device probe's, reused)" : "");
    fprintf(out, "  device     %8.1f\n", t.device);
    fprintf(out, "  cache      %8.1f  (pipeline cache %s: read; saved in teardown)\n", t.cache_open,
            t.cache_used ? "on disk" : "off");
    fprintf(out, "  pipelines  %8.1f  (with the renderer's resources; variant built %d time%s)\n", t.pipelines,
            t.variant_builds, t.variant_builds == 1 ? "" : "s");
    fprintf(out, "  setup      %8.1f  (the rest before the first frame: the library's context, the scene parsed "
                 "again, LUT cache read)\n", setup);
    /* Indexed by the renderer's SKY_LUT_CACHE_* (sky/renderer.h). */
    static const char *const lut_cache[] = {"off", "hit: uploaded, not computed", "computed", "computed and stored",
                                            "computed, not stored"};
    fprintf(out, "  LUT cache  %s\n", lut_cache[t.lut_cache]);
    if (t.gpu_timed)
        fprintf(out, "  LUTs       %8.2f  (GPU timestamps, inside the frame)\n", t.gpu_luts);
    else
        fprintf(out, "  LUTs            -    (no GPU timestamps on this device)\n");
    fprintf(out, "  frame      %8.1f  (record, submit to fence: LUTs, passes and readback copy; GPU passes %.2f; the "
                 "LUT, sky and far tone map pipelines made at their first use)\n", t.frame, t.gpu_total);
    if (t.gpu_timed) fprintf(out, "  readback   %8.2f  (GPU copy to host memory, inside the frame)\n", t.gpu_readback);
    fprintf(out, "  encode     %8.1f  (pixels to file bytes)\n", t.outputs - t.write);
    fprintf(out, "  write      %8.1f  (fsync, close, rename)\n", t.write);
    fprintf(out, "  teardown   %8.1f  (after the files: pipeline cache saved %.1f; renderer, device and instance %s)\n",
            end - t.outputs_at, t.cache_close, t.kept ? "left to the exit (validation off)" : "destroyed");
    fprintf(out, "  total      %8.1f  (process start to this report: the sum of the lines above but LUTs and "
                 "readback)\n", total);
}
