/* --async-luts: the LUT passes on the context's compute queue, the frame on the graphics queue, ordered by two
 * timeline semaphores; with another queue family, the LUTs change owner (release on the compute queue, acquire on
 * the graphics queue). docs/synchronization.md §10 is this file's lesson. */
#include "sky/submit.h"
#include "gpu/async_queue.h"
#include <time.h>

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

VkCommandBuffer sky_renderer_submit_luts_async(sky_renderer *r, bool force)
{
    gpu_context *ctx = r->ctx;
    if (ctx->graphics_value == 0 && ctx->compute_value == 0) gpu_async_trace_queues(ctx);
    if (!force && !sky_renderer_luts_dirty(r)) return VK_NULL_HANDLE;
    VkCommandBuffer luts = gpu_begin_compute_commands(ctx);
    frame_record_luts_compute(r, luts);
    r->lut_acquire_pending = gpu_async_other_family(ctx);
    if (!r->lut_acquire_pending)
        gpu_barrier_trace_note("qfot none: the compute queue is of the graphics family (%u): no ownership "
                               "transfer; the compute_done wait orders the LUT writes before the frame",
                               ctx->queue_family);
    /* WAR across queues: the previous frames sampled the LUTs on the graphics queue; the LUT passes overwrite them
     * only once those frames are done (their graphics_done value), at the compute shader stage. */
    ++ctx->compute_value;
    gpu_async_submit(ctx, ctx->compute_queue, "compute", luts, "graphics_done",
                     ctx->graphics_value ? ctx->graphics_done : VK_NULL_HANDLE, ctx->graphics_value,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, "compute_done", ctx->compute_done, ctx->compute_value,
                     VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_NULL_HANDLE);
    return luts;
}

/* RAW across queues: the frame's first LUT readers (the sky-view LUT's compute pass, the sky's compute or fragment
 * shaders) wait for the LUT passes' value; with another family the acquire barriers sit at that point with these
 * destination stages, so the wait covers their layout transition too. */
uint32_t sky_async_frame_semaphores(gpu_context *ctx, bool waits_luts, VkSemaphoreSubmitInfo *wait,
                                    VkSemaphoreSubmitInfo *signal)
{
    char stage[96];
    VkPipelineStageFlags2 readers = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    *signal = (VkSemaphoreSubmitInfo){.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO,
                                      .semaphore = ctx->graphics_done, .value = ++ctx->graphics_value,
                                      .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
    uint32_t n = 0;
    if (waits_luts) {
        bool drop = gpu_barrier_drops("compute_done.wait");
        gpu_stage_string(readers, stage, sizeof stage);
        gpu_barrier_trace_note("semaphore compute_done.wait queue=graphics value>=%llu stage=%s%s",
                               (unsigned long long)ctx->compute_value, stage, drop ? " DROPPED" : "");
        if (!drop) {
            *wait = (VkSemaphoreSubmitInfo){.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO,
                                            .semaphore = ctx->compute_done, .value = ctx->compute_value,
                                            .stageMask = readers};
            n = 1;
        }
    }
    gpu_barrier_trace_note("semaphore graphics_done.signal queue=graphics value=%llu stage=ALL_COMMANDS",
                           (unsigned long long)ctx->graphics_value);
    return n;
}

double sky_renderer_render_async(sky_renderer *r, const frame_desc *f)
{
    gpu_context *ctx = r->ctx;
    double t0 = now_ms();
    VkCommandBuffer luts = sky_renderer_submit_luts_async(r, f->force_luts);
    VkCommandBuffer cmd = gpu_begin_commands(ctx);
    frame_desc g = *f;
    g.force_luts = false;   /* recorded above, on the compute queue */
    frame_record(r, cmd, &g);
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkFenceCreateInfo finfo = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence;
    VK_CHECK(vkCreateFence(ctx->device, &finfo, ctx->allocator, &fence));
    VkSemaphoreSubmitInfo wait, signal;
    uint32_t waits = sky_async_frame_semaphores(ctx, luts != VK_NULL_HANDLE, &wait, &signal);
    VkCommandBufferSubmitInfo c = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 info = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .waitSemaphoreInfoCount = waits,
                          .pWaitSemaphoreInfos = &wait, .commandBufferInfoCount = 1, .pCommandBufferInfos = &c,
                          .signalSemaphoreInfoCount = 1, .pSignalSemaphoreInfos = &signal};
    VK_CHECK(vkQueueSubmit2(ctx->queue, 1, &info, fence));
    VK_CHECK(vkWaitForFences(ctx->device, 1, &fence, VK_TRUE, UINT64_MAX));
    double wall = now_ms() - t0;
    vkDestroyFence(ctx->device, fence, ctx->allocator);
    vkFreeCommandBuffers(ctx->device, ctx->command_pool, 1, &cmd);
    /* The graphics frame waited for the LUTs: the compute submission is done too. */
    if (luts) vkFreeCommandBuffers(ctx->device, ctx->compute_pool, 1, &luts);
    if (r->desc.readback) {
        gpu_buffer_invalidate(ctx, &r->readback_linear);
        gpu_buffer_invalidate(ctx, &r->readback_display);
    }
    return wall;
}
