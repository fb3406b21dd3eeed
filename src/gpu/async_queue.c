/* The async compute queue: see gpu/async_queue.h and docs/synchronization.md §10. */
#include "gpu/async_queue.h"
#include "gpu/barrier.h"

int gpu_async_choose(gpu_context *ctx, const VkQueueFamilyProperties *families, uint32_t count, bool one_queue)
{
    const VkQueueFlags gc = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    /* A dedicated compute family first: the hardware's own compute queues, the ones that overlap graphics work. */
    for (uint32_t i = 0; i < count; ++i)
        if ((families[i].queueFlags & gc) == VK_QUEUE_COMPUTE_BIT && families[i].queueCount > 0) {
            ctx->compute_family = i, ctx->compute_index = 0;
            return 0;
        }
    ctx->compute_family = ctx->queue_family;
    if (families[ctx->queue_family].queueCount >= 2) {
        ctx->compute_index = 1;   /* a second queue of the main family: no ownership transfer, still two queues */
        return 0;
    }
    if (one_queue) {
        ctx->compute_index = 0;   /* tests: the main queue itself (VKSKY_ASYNC_ONE_QUEUE=1) */
        return 0;
    }
    gpu_report(ctx, 2,
               "--async-luts needs a second queue: this device has no compute-only queue family and its one "
               "graphics+compute family has %u queue; run without --async-luts",
               families[ctx->queue_family].queueCount);
    return -1;
}

uint32_t gpu_async_queue_infos(const gpu_context *ctx, VkDeviceQueueCreateInfo infos[2], const float *priorities)
{
    if (ctx->compute_family != ctx->queue_family) {
        infos[1] = (VkDeviceQueueCreateInfo){.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                             .queueFamilyIndex = ctx->compute_family, .queueCount = 1,
                                             .pQueuePriorities = priorities};
        return 2;
    }
    infos[0].queueCount = ctx->compute_index + 1;   /* 2 for a second queue of the main family */
    return 1;
}

static VkSemaphore timeline(const gpu_context *ctx, const char *name)
{
    VkSemaphoreTypeCreateInfo type = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO,
                                      .semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE, .initialValue = 0};
    VkSemaphoreCreateInfo info = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, .pNext = &type};
    VkSemaphore s;
    VK_CHECK(vkCreateSemaphore(ctx->device, &info, ctx->allocator, &s));
    gpu_set_name(ctx, VK_OBJECT_TYPE_SEMAPHORE, (uint64_t)s, name);
    return s;
}

void gpu_async_open(gpu_context *ctx)
{
    vkGetDeviceQueue(ctx->device, ctx->compute_family, ctx->compute_index, &ctx->compute_queue);
    if (ctx->compute_queue != ctx->queue)
        gpu_set_name(ctx, VK_OBJECT_TYPE_QUEUE, (uint64_t)(uintptr_t)ctx->compute_queue, "async compute queue");
    VkCommandPoolCreateInfo pinfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                     .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                     .queueFamilyIndex = ctx->compute_family};
    VK_CHECK(vkCreateCommandPool(ctx->device, &pinfo, ctx->allocator, &ctx->compute_pool));
    gpu_set_name(ctx, VK_OBJECT_TYPE_COMMAND_POOL, (uint64_t)ctx->compute_pool, "async compute command pool");
    ctx->compute_done = timeline(ctx, "compute_done timeline");
    ctx->graphics_done = timeline(ctx, "graphics_done timeline");
}

void gpu_async_close(gpu_context *ctx)
{
    if (!ctx->compute_pool) return;
    vkDestroySemaphore(ctx->device, ctx->compute_done, ctx->allocator);
    vkDestroySemaphore(ctx->device, ctx->graphics_done, ctx->allocator);
    vkDestroyCommandPool(ctx->device, ctx->compute_pool, ctx->allocator);
    ctx->compute_pool = VK_NULL_HANDLE, ctx->compute_queue = VK_NULL_HANDLE;
    ctx->compute_done = ctx->graphics_done = VK_NULL_HANDLE;
}

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
