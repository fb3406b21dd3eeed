/* See gpu/queue_choice.h and docs/synchronization.md §10. */
#include "gpu/queue_choice.h"
#include "gpu/fail.h"

int gpu_queue_choose_compute(const VkQueueFamilyProperties *families, uint32_t count, uint32_t graphics_family,
                             bool one_queue, uint32_t *family, uint32_t *index)
{
    const VkQueueFlags gc = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    /* A dedicated compute family first: the hardware's own compute queues, the ones that overlap graphics work. */
    for (uint32_t i = 0; i < count; ++i)
        if ((families[i].queueFlags & gc) == VK_QUEUE_COMPUTE_BIT && families[i].queueCount > 0) {
            *family = i, *index = 0;
            return 0;
        }
    *family = graphics_family;
    if (families[graphics_family].queueCount >= 2) {
        *index = 1;   /* a second queue of the graphics family: no ownership transfer, still two queues */
        return 0;
    }
    *index = 0;       /* tests: the graphics queue itself (VKSKY_ASYNC_ONE_QUEUE=1) */
    return one_queue ? 0 : -1;
}

uint32_t gpu_queue_infos(uint32_t graphics_family, uint32_t compute_family, uint32_t compute_index,
                         VkDeviceQueueCreateInfo infos[2], const float *priorities)
{
    if (compute_family != graphics_family) {
        infos[1] = (VkDeviceQueueCreateInfo){.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                             .queueFamilyIndex = compute_family, .queueCount = 1,
                                             .pQueuePriorities = priorities};
        return 2;
    }
    infos[0].queueCount = compute_index + 1;   /* 2 for a second queue of the graphics family */
    return 1;
}

VkSemaphore gpu_timeline_create(VkDevice device, const VkAllocationCallbacks *allocator)
{
    VkSemaphoreTypeCreateInfo type = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO,
                                      .semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE, .initialValue = 0};
    VkSemaphoreCreateInfo info = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, .pNext = &type};
    VkSemaphore s;
    VK_CHECK(vkCreateSemaphore(device, &info, allocator, &s));
    return s;
}
