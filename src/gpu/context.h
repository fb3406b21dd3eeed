/* Vulkan context: instance, device, one graphics+compute queue, validation with synchronization validation.
 * Knows nothing of skies. */
#ifndef VKSKY_GPU_CONTEXT_H
#define VKSKY_GPU_CONTEXT_H
#include <volk.h>
#include <stdbool.h>
#include <stdio.h>

/* Always-on check: prints file:line, the call and the VkResult name, then exits with status 1 (a runtime
 * failure, not a user error). Swapchain results are handled where they occur, never through this. */
#define VK_CHECK(call)                                                                                      \
    do {                                                                                                    \
        VkResult vk_check_result_ = (call);                                                                 \
        if (vk_check_result_ != VK_SUCCESS) gpu_fail_vk(__FILE__, __LINE__, #call, vk_check_result_);       \
    } while (0)

typedef struct gpu_context_desc {
    bool validation;              /* Khronos validation layer + synchronization validation */
    int device_index;             /* -1: pick (discrete > integrated > virtual > CPU) */
    const char *const *instance_extensions;   /* extra (e.g. from GLFW) */
    unsigned instance_extension_count;
    bool want_swapchain;
} gpu_context_desc;

typedef struct gpu_context {
    VkInstance instance;
    VkPhysicalDevice physical;
    VkPhysicalDeviceProperties props;
    VkPhysicalDeviceMemoryProperties memory;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;
    VkCommandPool command_pool;
    VkDebugUtilsMessengerEXT messenger;
    bool validation;
    bool debug_utils;             /* names and labels available */
    bool timestamps;              /* queue supports timestamps */
    double timestamp_period_ns;
    VkPipelineCache pipeline_cache;          /* VK_NULL_HANDLE unless gpu_pipeline_cache_open made one */
    struct gpu_cache_file *cache_file;       /* where it is saved (gpu/pipeline_cache.c) */
    double instance_ms, device_ms;           /* wall time of gpu_context_create's two halves (--timings) */
    bool instance_reused;                    /* the device probe's instance (gpu_device_type), not a new one */
    bool surface_maintenance1;    /* instance: VK_EXT_surface_maintenance1 (+ get_surface_capabilities2) enabled */
    bool present_fences;          /* device: VK_EXT_swapchain_maintenance1 enabled (present fences, docs §6) */
    bool memory_model_device_scope;   /* vulkanMemoryModel + ...DeviceScope enabled (bloom_spd.comp needs both) */
} gpu_context;

/* Returns 0 on success; -1 with a message on stderr (no device, validation layer missing, ...). */
int gpu_context_create(gpu_context *ctx, const gpu_context_desc *desc);
void gpu_context_destroy(gpu_context *ctx);
/* Prints the physical devices with their indices (for --list-devices). Returns 0 or -1. */
int gpu_list_devices(FILE *out);
/* The type of the device gpu_context_create would pick for device_index (-1: the default choice), from a bare
 * instance; 0, or -1 (no message) if there is none. For choices made before the context exists (--quality auto). */
int gpu_device_type(int device_index, VkPhysicalDeviceType *type);

/* Messages the validation layer reported so far (every one is also printed to stderr). */
unsigned gpu_validation_message_count(void);

void gpu_set_name(const gpu_context *ctx, VkObjectType type, uint64_t handle, const char *name);
void gpu_label_begin(const gpu_context *ctx, VkCommandBuffer cmd, const char *name);
void gpu_label_end(const gpu_context *ctx, VkCommandBuffer cmd);

/* One-shot command buffer: begin, then submit and wait for a fence. */
VkCommandBuffer gpu_begin_commands(const gpu_context *ctx);
void gpu_submit_and_wait(const gpu_context *ctx, VkCommandBuffer cmd);

const char *gpu_result_name(VkResult r);
_Noreturn void gpu_fail_vk(const char *file, int line, const char *call, VkResult r);
#endif
