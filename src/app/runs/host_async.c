/* --async-luts as a host of include/vksky.h (host_async.h). The trace lines are the CLI's own path's
 * (gpu/async_queue.c, sky/async_luts.c), so a trace reads the same whichever host recorded it. */
#include "app/runs/host_async.h"
#include <stdlib.h>
#include <string.h>

/* The stages as --trace-barriers names them. */
#define LUT_READERS (VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT)
#define LUT_READERS_NAME "COMPUTE_SHADER|FRAGMENT_SHADER"

static VkSemaphore timeline(VkDevice device)
{
    VkSemaphoreTypeCreateInfo type = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO,
                                      .semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE};
    VkSemaphoreCreateInfo info = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, .pNext = &type};
    VkSemaphore s = VK_NULL_HANDLE;
    return vkCreateSemaphore(device, &info, NULL, &s) == VK_SUCCESS ? s : VK_NULL_HANDLE;
}

int host_async_create(host_async *a, vksky_context *ctx, uint32_t compute_index, FILE *trace)
{
    vksky_context_handles k;
    vksky_context_get_handles(ctx, &k);
    const char *drop = getenv("VKSKY_DROP_BARRIER");
    *a = (host_async){.device = k.device, .compute_queue = k.compute_queue, .family = k.queue_family,
                      .compute_family = k.compute_queue_family, .compute_index = compute_index, .trace = trace,
                      .drop = drop && *drop ? drop : NULL};
    VkCommandPoolCreateInfo pinfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                     .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                     .queueFamilyIndex = k.compute_queue_family};
    VkCommandBufferAllocateInfo ainfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                         .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    bool ok = k.compute_queue && vkCreateCommandPool(a->device, &pinfo, NULL, &a->pool) == VK_SUCCESS &&
              (ainfo.commandPool = a->pool, vkAllocateCommandBuffers(a->device, &ainfo, &a->cmd) == VK_SUCCESS) &&
              (a->compute_done = timeline(a->device)) && (a->graphics_done = timeline(a->device));
    if (!ok) {
        fprintf(stderr, "vksky: cannot make the compute queue's command buffer and timeline semaphores\n");
        host_async_destroy(a);
        return 1;
    }
    return 0;
}

void host_async_destroy(host_async *a)
{
    if (!a->device) return;
    if (a->compute_done) vkDestroySemaphore(a->device, a->compute_done, NULL);
    if (a->graphics_done) vkDestroySemaphore(a->device, a->graphics_done, NULL);
    if (a->pool) vkDestroyCommandPool(a->device, a->pool, NULL);   /* frees its command buffer */
    *a = (host_async){0};
}

/* A semaphore wait of ours: traced, and left out when VKSKY_DROP_BARRIER names it. Returns whether to wait. */
static bool semaphore_wait(const host_async *a, const char *name, const char *queue, uint64_t value, const char *stage)
{
    bool drop = a->drop && !strcmp(a->drop, name);
    if (a->trace)
        fprintf(a->trace, "semaphore %s queue=%s value>=%llu stage=%s%s\n", name, queue, (unsigned long long)value,
                stage, drop ? " DROPPED" : "");
    return !drop;
}

int host_async_luts(host_async *a, vksky_renderer *r, bool force, bool *waits)
{
    return host_async_luts_list(a, &r, 1, force, waits);
}

int host_async_luts_list(host_async *a, vksky_renderer *const *rs, uint32_t n, bool force, bool *waits)
{
    *waits = false;
    if (a->trace && a->graphics_value == 0 && a->compute_value == 0)
        fprintf(a->trace, "queues graphics=%u:0 compute=%u:%u%s\n", a->family, a->compute_family, a->compute_index,
                a->compute_family != a->family
                    ? " (another family: exclusive images change owner, release + acquire)"
                    : " (the same family: no ownership transfer, the timeline semaphore is enough)");
    bool stale = force;
    for (uint32_t k = 0; k < n && !stale; ++k) stale = vksky_renderer_luts_stale(rs[k]);
    if (!stale) return 0;
    if (a->trace) fputs("commands\n", a->trace);   /* the compute queue's command buffer */
    VkCommandBufferBeginInfo binfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                      .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    bool recorded = false;
    /* The earlier LUT submission is done: the frame that waited for it was waited for (one frame at a time). */
    if (vkResetCommandBuffer(a->cmd, 0) != VK_SUCCESS || vkBeginCommandBuffer(a->cmd, &binfo) != VK_SUCCESS) return 1;
    for (uint32_t k = 0; k < n; ++k) {   /* every renderer's LUT passes in the one compute submission */
        bool one = false;
        if (vksky_record_luts(rs[k], a->cmd, force, &one) != VKSKY_SUCCESS) return 1;
        recorded |= one;
    }
    if (vkEndCommandBuffer(a->cmd) != VK_SUCCESS) return 1;
    if (a->trace && a->compute_family == a->family)
        fprintf(a->trace, "qfot none: the compute queue is of the graphics family (%u): no ownership transfer; the "
                          "compute_done wait orders the LUT writes before the frame\n", a->family);
    /* WAR across queues: the earlier frames sampled the LUTs on the graphics queue; the LUT passes overwrite them
     * only once those frames are done (their graphics_done value), at the compute shader stage. */
    bool wait = a->graphics_value &&
                semaphore_wait(a, "graphics_done.wait", "compute", a->graphics_value, "COMPUTE_SHADER");
    ++a->compute_value;
    if (a->trace)
        fprintf(a->trace, "semaphore compute_done.signal queue=compute value=%llu stage=ALL_COMMANDS\n",
                (unsigned long long)a->compute_value);
    VkSemaphoreSubmitInfo w = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = a->graphics_done,
                               .value = a->graphics_value, .stageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT};
    VkSemaphoreSubmitInfo s = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = a->compute_done,
                               .value = a->compute_value, .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
    VkCommandBufferSubmitInfo c = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = a->cmd};
    VkSubmitInfo2 info = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .waitSemaphoreInfoCount = wait ? 1 : 0,
                          .pWaitSemaphoreInfos = &w, .commandBufferInfoCount = 1, .pCommandBufferInfos = &c,
                          .signalSemaphoreInfoCount = 1, .pSignalSemaphoreInfos = &s};
    VkResult vr = vkQueueSubmit2(a->compute_queue, 1, &info, VK_NULL_HANDLE);
    if (vr != VK_SUCCESS) {
        fprintf(stderr, "vksky: the LUTs' submission to the compute queue failed (VkResult %d)\n", (int)vr);
        return 1;
    }
    *waits = recorded;
    return 0;
}

uint32_t host_async_frame(host_async *a, bool waits, VkSemaphoreSubmitInfo *wait, VkSemaphoreSubmitInfo *signal)
{
    /* RAW across queues: the frame's first LUT readers wait for the LUT passes' value. */
    *signal = (VkSemaphoreSubmitInfo){.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = a->graphics_done,
                                      .value = ++a->graphics_value, .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
    uint32_t n = 0;
    if (waits && semaphore_wait(a, "compute_done.wait", "graphics", a->compute_value, LUT_READERS_NAME)) {
        *wait = (VkSemaphoreSubmitInfo){.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = a->compute_done,
                                        .value = a->compute_value, .stageMask = LUT_READERS};
        n = 1;
    }
    if (a->trace)
        fprintf(a->trace, "semaphore graphics_done.signal queue=graphics value=%llu stage=ALL_COMMANDS\n",
                (unsigned long long)a->graphics_value);
    return n;
}
