/* --async-luts as a host of include/vksky.h (issue 25 item 4; docs/synchronization.md §10): the LUT passes recorded by
 * vksky_record_luts into a command buffer of the host's compute queue, the frame by vksky_record into one of its
 * graphics queue, ordered by two timeline semaphores of the host's:
 *
 *   compute_done  the LUT passes' submission signals it; the frame's waits for that value where the LUTs are first
 *                 read (COMPUTE_SHADER | FRAGMENT_SHADER: vksky_luts.ready_stage): RAW across queues;
 *   graphics_done each frame signals it; the next LUT submission waits for it at COMPUTE_SHADER (the earlier frames
 *                 sampled the LUTs the passes overwrite): WAR across queues.
 *
 * Each wait is printed by --trace-barriers ("semaphore <name>.wait ...", as the CLI's own path printed it) and left out
 * by VKSKY_DROP_BARRIER=compute_done.wait / graphics_done.wait (tests/async_luts_test.sh). One frame at a time: the
 * host waits for each frame's fence before it records the next LUT passes. No src/sky or src/lib header
 * (tests/layering_test.sh). */
#ifndef VKSKY_APP_RUNS_HOST_ASYNC_H
#define VKSKY_APP_RUNS_HOST_ASYNC_H
#include <volk.h>
#include <vksky.h>
#include <stdio.h>

typedef struct host_async {
    VkDevice device;
    VkQueue compute_queue;
    uint32_t family, compute_family, compute_index;
    VkCommandPool pool;            /* the compute family's: the LUT passes' command buffer */
    VkCommandBuffer cmd;
    VkSemaphore compute_done, graphics_done;
    uint64_t compute_value, graphics_value;
    FILE *trace;                   /* --trace-barriers (NULL: none) */
    const char *drop;              /* VKSKY_DROP_BARRIER */
} host_async;

/* Over a context made with a compute queue (vksky_context_desc.compute_queue; its index `compute_index`). 0, or 1
 * (the line printed). */
int host_async_create(host_async *a, vksky_context *ctx, uint32_t compute_index, FILE *trace);
void host_async_destroy(host_async *a);
/* Before a frame: the LUT passes, when r's are stale or `force`, recorded and submitted on the compute queue (after
 * the earlier frames: graphics_done); *waits: whether the frame must wait for them. 0, or 1 (the line printed). */
int host_async_luts(host_async *a, vksky_renderer *r, bool force, bool *waits);
/* The same for n renderers whose frames share the next graphics submission (--spectral's wavelength groups): their
 * LUT passes in one compute submission, when any is stale or `force`. */
int host_async_luts_list(host_async *a, vksky_renderer *const *rs, uint32_t n, bool force, bool *waits);
/* The frame's submission semaphores: *wait (when `waits`: compute_done at the LUT readers) and *signal
 * (graphics_done's next value). Returns the number of waits (0 or 1). */
uint32_t host_async_frame(host_async *a, bool waits, VkSemaphoreSubmitInfo *wait, VkSemaphoreSubmitInfo *signal);
#endif
