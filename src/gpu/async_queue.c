/* The async compute queue: see gpu/async_queue.h and docs/synchronization.md §10. */
#include "gpu/async_queue.h"
#include "gpu/barrier.h"

void gpu_async_trace_queues(const gpu_context *ctx)
{
    gpu_barrier_trace_note("queues graphics=%u:0 compute=%u:%u%s", ctx->queue_family, ctx->compute_family,
                           ctx->compute_index,
                           ctx->compute_family != ctx->queue_family
                               ? " (another family: exclusive images change owner, release + acquire)"
                               : " (the same family: no ownership transfer, the timeline semaphore is enough)");
}

bool gpu_async_other_family(const gpu_context *ctx)
{
    return ctx->compute_queue && ctx->compute_family != ctx->queue_family;
}

VkCommandBuffer gpu_begin_compute_commands(const gpu_context *ctx)
{
    gpu_barrier_trace_commands();
    VkCommandBufferAllocateInfo ainfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                         .commandPool = ctx->compute_pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                         .commandBufferCount = 1};
    VkCommandBuffer cmd;
    VK_CHECK(vkAllocateCommandBuffers(ctx->device, &ainfo, &cmd));
    VkCommandBufferBeginInfo binfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                      .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    VK_CHECK(vkBeginCommandBuffer(cmd, &binfo));
    return cmd;
}

void gpu_async_submit(const gpu_context *ctx, VkQueue queue, const char *queue_name, VkCommandBuffer cmd,
                      const char *wait_name, VkSemaphore wait, uint64_t wait_value, VkPipelineStageFlags2 wait_stage,
                      const char *signal_name, VkSemaphore signal, uint64_t signal_value,
                      VkPipelineStageFlags2 signal_stage, VkFence fence)
{
    char name[64], stage[160];
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkSemaphoreSubmitInfo w = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = wait,
                               .value = wait_value, .stageMask = wait_stage};
    VkSemaphoreSubmitInfo s = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = signal,
                               .value = signal_value, .stageMask = signal_stage};
    (void)ctx;
    bool waits = wait != VK_NULL_HANDLE;
    snprintf(name, sizeof name, "%s.wait", wait_name ? wait_name : "");
    if (waits) {
        gpu_stage_string(wait_stage, stage, sizeof stage);
        bool drop = gpu_barrier_drops(name);
        gpu_barrier_trace_note("semaphore %s queue=%s value>=%llu stage=%s%s", name, queue_name,
                               (unsigned long long)wait_value, stage, drop ? " DROPPED" : "");
        waits = !drop;
    }
    if (signal) {
        gpu_stage_string(signal_stage, stage, sizeof stage);
        gpu_barrier_trace_note("semaphore %s.signal queue=%s value=%llu stage=%s", signal_name, queue_name,
                               (unsigned long long)signal_value, stage);
    }
    VkCommandBufferSubmitInfo c = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 info = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2,
                          .waitSemaphoreInfoCount = waits ? 1 : 0, .pWaitSemaphoreInfos = &w,
                          .commandBufferInfoCount = 1, .pCommandBufferInfos = &c,
                          .signalSemaphoreInfoCount = signal ? 1 : 0, .pSignalSemaphoreInfos = &s};
    VK_CHECK(vkQueueSubmit2(queue, 1, &info, fence));
}
