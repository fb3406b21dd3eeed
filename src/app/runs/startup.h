/* What a run's start costs and what it keeps between runs (issue 27): the pipeline cache's directory and the
 * --timings report of where the first image's time went. */
#ifndef VKSKY_APP_STARTUP_H
#define VKSKY_APP_STARTUP_H
#include "app/cli/options_struct.h"
#include "gpu/context.h"

/* main's first line: the moment, and how long the process ran before it (the loader; the report's exec line). The
 * report's total counts from the process's start. */
void startup_begin(void);

/* Whether a finished run (status 0) may leave its renderer, device and instance to the process's exit instead of
 * destroying them: one image from the command line (no sequence, --bench or --async-luts) with validation off, where
 * the OS frees the memory and the kernel driver the device when the process ends, and the files and caches are
 * already written. The validation path (--validate, VKSKY_VALIDATION=1) and sanitizer builds destroy everything, so the
 * layer's object tracking and LeakSanitizer still see a clean teardown; VKSKY_TEARDOWN=1 asks for it too (an A/B of
 * the cut: tools/first_image.sh). */
bool startup_keep_for_exit(const options *o, int status);

/* main's last step: a run whose objects were left to the exit (startup_keep_for_exit) ends with _exit once stdout
 * and stderr are flushed, so the process skips the atexit handlers (the Vulkan driver's: its own teardown of the
 * device the run left, 53 ms of the first image's 282 on the H100's driver). The files were written, fsynced and
 * renamed before; the pipeline cache saved. Any other run returns and exits normally. */
void startup_exit(int status);

/* The pipeline cache for ctx: $XDG_CACHE_HOME/vksky or ~/.cache/vksky, none with --no-cache (or without either
 * variable). Pair with startup_close_cache before the context goes. */
void startup_open_cache(gpu_context *ctx, const options *o);
void startup_close_cache(gpu_context *ctx);

/* The first image, as the headless run renders it: call around its frame, then once its files are written (before
 * the next frame, or at the end). Later frames are not measured. The frame's end from a host of include/vksky.h
 * (vksky_renderer_get_stats, vksky_renderer_get_timings): the pipelines' ms, the variant builds, the LUT cache's state
 * (vksky_lut_cache_state) and the frame's timed passes (n 0: none). */
void startup_frame_begin(void);
void startup_frame_end_values(double pipelines_ms, int variant_builds, int lut_cache, const char *const *names,
                              const double *ms, uint32_t n);
void startup_outputs_done(void);

/* --timings: the breakdown on `out` (exec, options, probe, instance, device, cache, pipelines, setup, LUTs, frame,
 * readback, encode, write, teardown: the lines but LUTs and readback add up to the total), if a first image was
 * rendered (else the context's two figures); last, after the teardown (the cache's save is part of the run's cost). */
void startup_report(FILE *out);
#endif
