/* The command line's device for the hosts of include/vksky.h that make their own (the headless run,
 * app/runs/headless.c; the composite, app/runs/composite_app.c): validation, --device, --async-luts' compute queue, the
 * pipeline cache, the device's limits checked, VKSKY_WEAKEN_BARRIER / VKSKY_DROP_BARRIER; adopted by a vksky context
 * with the command line's message callback, names and labels, LUT cache directory and barrier trace. The host itself
 * then sees only the context. */
#ifndef VKSKY_APP_RUNS_HOST_DEVICE_H
#define VKSKY_APP_RUNS_HOST_DEVICE_H
#include "app/cli/options.h"
#include <volk.h>
#include <vksky.h>

typedef struct host_device host_device;

/* *dev and *ctx made: 0; else 1 or 2 after one line on stderr (nothing left to destroy). *compute_index: --async-luts'
 * compute queue within its family (host_async_create). Installs the stop handler (app/runs/stop.h). */
int host_device_open(const options *o, host_device **dev, vksky_context **ctx, uint32_t *compute_index);
/* A device the command line made (gpu/context.h) adopted by a new vksky context: its queues (and --async-luts'
 * compute queue), pipeline cache, enabled features, message callback, names and labels, LUT cache directory. 0, or 1
 * (nothing left to destroy). The window's too (app/window/window_api.c). */
struct gpu_context;
int host_device_adopt(const struct gpu_context *g, vksky_context **out);
/* How a run ends: timings, --timings' report on stderr (after the teardown); keep, the context, device and instance
 * left to the process's exit (startup_keep_for_exit: one image, validation off), only the pipeline cache saved. */
typedef struct host_device_end {
    bool timings, keep;
} host_device_end;
/* Destroys the context (after every renderer of it), then the device (not with end.keep). Validation messages fail a
 * run that succeeded; a stop asked for by a signal gives its status (stop_status). */
int host_device_close(host_device *dev, vksky_context *ctx, int status, host_device_end end);
#endif
