/* The async compute queue (--async-luts): which queue, its command pool, and the two timeline semaphores that
 * order its submissions against the main queue's. Knows nothing of skies; docs/synchronization.md §10. */
#ifndef VKSKY_GPU_ASYNC_QUEUE_H
#define VKSKY_GPU_ASYNC_QUEUE_H
#include "gpu/context.h"

/* Picks the compute queue: a family with compute and without graphics (a dedicated compute family: its work may
 * overlap the graphics queue's), else a second queue of the main family, else (one_queue, tests) the main queue
 * itself. Returns 0, or -1 with a message naming what the device lacks. */
int gpu_async_choose(gpu_context *ctx, const VkQueueFamilyProperties *families, uint32_t count, bool one_queue);
/* The VkDeviceQueueCreateInfos the choice needs (infos[0] is the main family's); returns how many. */
uint32_t gpu_async_queue_infos(const gpu_context *ctx, VkDeviceQueueCreateInfo infos[2], const float *priorities);
/* After vkCreateDevice: the queue, a command pool on its family, the two timelines. Close destroys them. */
void gpu_async_open(gpu_context *ctx);
void gpu_async_close(gpu_context *ctx);
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
