#include "gpu/timing.h"

void gpu_timer_create(const gpu_context *ctx, gpu_timer *t)
{
    *t = (gpu_timer){.enabled = ctx->timestamps};
    if (!t->enabled) return;
    VkQueryPoolCreateInfo info = {.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                  .queryType = VK_QUERY_TYPE_TIMESTAMP, .queryCount = 2 * GPU_TIMER_MAX};
    VK_CHECK(vkCreateQueryPool(ctx->device, &info, gpu_allocator(ctx->device), &t->pool));
    gpu_set_name(ctx, VK_OBJECT_TYPE_QUERY_POOL, (uint64_t)t->pool, "pass timestamps");
}

void gpu_timer_destroy(const gpu_context *ctx, gpu_timer *t)
{
    if (t->pool) vkDestroyQueryPool(ctx->device, t->pool, gpu_allocator(ctx->device));
    *t = (gpu_timer){0};
}

void gpu_timer_reset(gpu_timer *t, VkCommandBuffer cmd)
{
    t->count = 0;
    if (t->enabled) vkCmdResetQueryPool(cmd, t->pool, 0, 2 * GPU_TIMER_MAX);
}

uint32_t gpu_timer_begin(gpu_timer *t, VkCommandBuffer cmd, const char *name)
{
    if (!t->enabled || t->count == GPU_TIMER_MAX) return UINT32_MAX;
    uint32_t slot = t->count++;
    t->names[slot] = name;
    /* ALL_COMMANDS: the stamp is taken once every earlier command has finished, so passes do not overlap. */
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, t->pool, 2 * slot);
    return slot;
}

void gpu_timer_end(gpu_timer *t, VkCommandBuffer cmd, uint32_t slot)
{
    if (slot == UINT32_MAX) return;
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, t->pool, 2 * slot + 1);
}

uint32_t gpu_timer_read(const gpu_context *ctx, gpu_timer *t, double *ms_out)
{
    if (!t->enabled || t->count == 0) return 0;
    uint64_t stamps[2 * GPU_TIMER_MAX];
    VK_CHECK(vkGetQueryPoolResults(ctx->device, t->pool, 0, 2 * t->count, sizeof stamps, stamps, sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    for (uint32_t i = 0; i < t->count; ++i)
        ms_out[i] = (double)(stamps[2 * i + 1] - stamps[2 * i]) * ctx->timestamp_period_ns * 1e-6;
    return t->count;
}
