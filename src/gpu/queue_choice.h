/* Which queue --async-luts gets, and the device's queue create infos for it (below gpu/context.c, which calls it
 * before vkCreateDevice; gpu/async_queue.c is the rest of the async queue, above the context). */
#ifndef VKSKY_GPU_QUEUE_CHOICE_H
#define VKSKY_GPU_QUEUE_CHOICE_H
#include <volk.h>
#include <stdbool.h>

/* A family with compute and without graphics (a dedicated compute family: its work may overlap the graphics
 * queue's), else a second queue of the graphics family, else (one_queue, tests) the graphics queue itself. Returns 0
 * with *family and *index, or -1: the device has none of these. */
int gpu_queue_choose_compute(const VkQueueFamilyProperties *families, uint32_t count, uint32_t graphics_family,
                             bool one_queue, uint32_t *family, uint32_t *index);
/* The VkDeviceQueueCreateInfos for the graphics queue (infos[0], filled in by the caller) and the compute queue;
 * returns how many. */
uint32_t gpu_queue_infos(uint32_t graphics_family, uint32_t compute_family, uint32_t compute_index,
                         VkDeviceQueueCreateInfo infos[2], const float *priorities);
/* A timeline semaphore (initial value 0). */
VkSemaphore gpu_timeline_create(VkDevice device, const VkAllocationCallbacks *allocator);
#endif
