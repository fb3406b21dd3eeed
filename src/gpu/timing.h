/* GPU timestamps around passes (median over frames is the caller's business). */
#ifndef VKSKY_GPU_TIMING_H
#define VKSKY_GPU_TIMING_H
#include "gpu/context.h"

#define GPU_TIMER_MAX 32
typedef struct gpu_timer {
    VkQueryPool pool;
    const char *names[GPU_TIMER_MAX];
    uint32_t count;          /* passes recorded this frame */
    bool enabled;
} gpu_timer;

void gpu_timer_create(const gpu_context *ctx, gpu_timer *t);
void gpu_timer_destroy(const gpu_context *ctx, gpu_timer *t);
/* Reset at the start of a frame's command buffer. */
void gpu_timer_reset(gpu_timer *t, VkCommandBuffer cmd);
/* Returns the slot; pair with gpu_timer_end. No-op when timestamps are unavailable. */
uint32_t gpu_timer_begin(gpu_timer *t, VkCommandBuffer cmd, const char *name);
void gpu_timer_end(gpu_timer *t, VkCommandBuffer cmd, uint32_t slot);
/* After the fence: milliseconds of each recorded pass (count entries). Returns the count. */
uint32_t gpu_timer_read(const gpu_context *ctx, gpu_timer *t, double *ms_out);
#endif
