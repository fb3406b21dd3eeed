/* The command line's device adopted by a vksky context (host_device.h). */
#include "app/runs/host_device.h"
#include "app/runs/host_print.h"
#include "app/runs/startup.h"
#include "app/runs/stop.h"
#include "gpu/pipeline_cache.h"
#include "sky/limits.h"
#include <stdlib.h>
#include <string.h>

struct host_device {
    gpu_context gpu;
};

int host_device_open(const options *o, host_device **dev, vksky_context **ctx, uint32_t *compute_index)
{
    *dev = NULL, *ctx = NULL, *compute_index = 0;
    stop_install();   /* SIGINT/SIGTERM from here on: the output is not renamed into place; exit 130/143 */
    char why[200];
    if (!gpu_barrier_set_weaken(getenv("VKSKY_WEAKEN_BARRIER"), why, sizeof why)) {
        fprintf(stderr, "vksky: VKSKY_WEAKEN_BARRIER: %s\n", why);
        return 2;
    }
    host_device *d = calloc(1, sizeof *d);
    if (!d) {
        fprintf(stderr, "vksky: out of memory\n");
        return 1;
    }
    /* VKSKY_ASYNC_ONE_QUEUE=1 (tests): --async-luts on a device with one queue (lavapipe), both submissions on it. */
    const char *one_queue = getenv("VKSKY_ASYNC_ONE_QUEUE");
    gpu_context_desc desc = {.validation = o->validate, .device_index = o->device_index,
                             .async_compute = !o->async_luts ? GPU_ASYNC_OFF
                                              : one_queue && !strcmp(one_queue, "1") ? GPU_ASYNC_ONE_QUEUE
                                                                                    : GPU_ASYNC_ON};
    int rc = gpu_context_create(&d->gpu, &desc);
    if (rc != 0) {
        free(d);
        return rc == -2 ? 2 : 1;
    }
    gpu_context *g = &d->gpu;
    if (sky_limits_report(g) != 0) {   /* a limit under the pipelines' need (sky/limits.h): the line, exit 1 */
        gpu_context_destroy(g);
        free(d);
        return 1;
    }
    startup_open_cache(g, o);
    gpu_barrier_set_drop(getenv("VKSKY_DROP_BARRIER"));
    vksky_context *c = NULL;
    if (host_device_adopt(g, &c) != 0) {
        host_device_close(d, NULL, 1, (host_device_end){0});
        return 1;
    }
    /* The barrier trace covers the renderers' creation (their uploads), as the command line's own trace did. */
    if (o->trace_barriers) vksky_context_set_trace(c, VKSKY_TRACE_BARRIERS, host_print_trace, NULL);
    *dev = d, *ctx = c, *compute_index = g->compute_index;
    return 0;
}

int host_device_adopt(const struct gpu_context *g, vksky_context **out)
{
    vksky_context_desc cd = {
        .abi_version = VKSKY_ABI_VERSION, .get_instance_proc_addr = vkGetInstanceProcAddr, .instance = g->instance,
        .physical_device = g->physical, .device = g->device, .queue_family = g->queue_family, .queue_index = 0,
        .pipeline_cache = g->pipeline_cache, .message = host_print_message,
        /* --async-luts: the compute queue the device was made with (the main queue under VKSKY_ASYNC_ONE_QUEUE=1). */
        .compute_queue = g->compute_queue != VK_NULL_HANDLE, .compute_queue_family = g->compute_family,
        .compute_queue_index = g->compute_index};
    /* What the device creation enabled: the memory model too where the device has it (single-pass SPD). */
    vksky_device_requirements enabled = {.synchronization2 = true, .dynamic_rendering = true, .maintenance4 = true,
                                         .vulkan_memory_model = g->memory_model_device_scope,
                                         .vulkan_memory_model_device_scope = g->memory_model_device_scope};
    *out = NULL;
    vksky_context *c = NULL;
    if (vksky_context_create(&cd, &c) != VKSKY_SUCCESS || vksky_context_set_device_features(c, &enabled) != VKSKY_SUCCESS ||
        vksky_context_set_debug_utils(c, g->debug_utils) != VKSKY_SUCCESS ||   /* names, labels (captures) */
        vksky_context_set_cache_directory(c, gpu_cache_dir(g)) != VKSKY_SUCCESS) {
        vksky_context_destroy(c);
        return 1;
    }
    *out = c;
    return 0;
}

int host_device_close(host_device *dev, vksky_context *ctx, int status, host_device_end end)
{
    startup_outputs_done();   /* --timings: the files are done (if not said before); what follows is teardown */
    if (!end.keep) vksky_context_destroy(ctx);
    if (dev) {
        startup_close_cache(&dev->gpu);   /* saved even when the rest is left to the exit */
        if (!end.keep) {
            gpu_context_destroy(&dev->gpu);
            free(dev);
        }
    }
    if (end.timings) startup_report(stderr);   /* after the teardown: the cache's save is part of the run's cost */
    unsigned messages = gpu_validation_message_count();
    if (messages) {
        fprintf(stderr, "vksky: validation reported %u message%s\n", messages, messages == 1 ? "" : "s");
        if (status == 0) status = 1;
    }
    return stop_status(status);
}
