/* The async compute queue (--async-luts): its command buffers and submissions, ordered against the main queue's by
 * the context's two timeline semaphores (made by gpu/context.c with the queue, chosen by gpu/queue_choice.c). Knows nothing of skies; docs/synchronization.md §10. */
#ifndef VKSKY_GPU_ASYNC_QUEUE_H
#define VKSKY_GPU_ASYNC_QUEUE_H
#include "gpu/context.h"

/* A `queues` line in the barrier trace: which family and queue each submission goes to, and whether the LUTs change
 * owner. */
void gpu_async_trace_queues(const gpu_context *ctx);
/* True when the compute queue is of another family than the main queue: exclusive images then change owner. */
bool gpu_async_other_family(const gpu_context *ctx);

/* A one-time command buffer from the compute queue's pool (traced as a `commands` line). */
VkCommandBuffer gpu_begin_compute_commands(const gpu_context *ctx);
/* One submission on `queue` (the compute or the main queue): waits for timeline `wait` >= wait_value at wait_stage
 * (no wait when wait is VK_NULL_HANDLE), signals timeline `signal` = signal_value at signal_stage, and `fence`.
 * The wait and the signal are traced as `semaphore <wait_name>.wait ...` and `semaphore <signal_name>.signal ...`;
 * VKSKY_DROP_BARRIER=<wait_name>.wait leaves the wait out (the drop test of a semaphore wait). */
void gpu_async_submit(const gpu_context *ctx, VkQueue queue, const char *queue_name, VkCommandBuffer cmd,
                      const char *wait_name, VkSemaphore wait, uint64_t wait_value, VkPipelineStageFlags2 wait_stage,
                      const char *signal_name, VkSemaphore signal, uint64_t signal_value,
                      VkPipelineStageFlags2 signal_stage, VkFence fence);
#endif
