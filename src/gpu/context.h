/* Vulkan context: instance, device, one graphics+compute queue, validation with synchronization validation.
 * Knows nothing of skies. */
#ifndef VKSKY_GPU_CONTEXT_H
#define VKSKY_GPU_CONTEXT_H
#include "gpu/fail.h"
#include <volk.h>
#include <stdbool.h>
#include <stdio.h>

typedef struct gpu_context_desc {
    bool validation;              /* Khronos validation layer + synchronization validation */
    int device_index;             /* -1: pick (discrete > integrated > virtual > CPU) */
    const char *const *instance_extensions;   /* extra (e.g. from GLFW) */
    unsigned instance_extension_count;
    bool want_swapchain;
    /* --async-luts: a second queue for compute work (gpu/async_queue.c). GPU_ASYNC_ONE_QUEUE (tests, env
     * VKSKY_ASYNC_ONE_QUEUE=1) puts the compute submissions on the main queue itself, so a single-queue device
     * (lavapipe) runs the same command buffers and timeline semaphores. */
    int async_compute;
} gpu_context_desc;
enum { GPU_ASYNC_OFF, GPU_ASYNC_ON, GPU_ASYNC_ONE_QUEUE };

/* A message from src/gpu or src/sky (a context's problem, a validation message): severity 0 info, 1 warning, 2 error,
 * 3 validation. Without one, messages go to stderr as "vksky: TEXT" (the CLI). */
typedef void (*gpu_message_fn)(void *user, int severity, const char *text);

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
    bool owns_device;             /* gpu_context_create made the instance and device; adopted: the host's */
    const VkAllocationCallbacks *allocator;   /* every vkCreate/vkDestroy of src/gpu and src/sky (gpu_allocator) */
    gpu_message_fn message;       /* NULL: stderr */
    void *message_user;
    unsigned validation_messages; /* this context's (gpu_validation_message_count: the process's) */
    /* The async compute queue (gpu/async_queue.c); compute_queue VK_NULL_HANDLE: none. Two timelines: `compute_done`
     * counts the compute queue's submissions, `graphics_done` the main queue's that wait for or follow them. */
    VkQueue compute_queue;
    uint32_t compute_family, compute_index;
    VkCommandPool compute_pool;
    VkSemaphore compute_done, graphics_done;
    uint64_t compute_value, graphics_value;   /* the last value signalled (submitted) on each */
} gpu_context;

/* The host's device, adopted (libvksky's vksky_context_create): no instance or device is created; vksky's Vulkan
 * function pointers come from the host's vkGetInstanceProcAddr (device calls through the loader's dispatch, right
 * for any device, so two contexts on two devices never clash). */
typedef struct gpu_adopt_desc {
    PFN_vkGetInstanceProcAddr get_instance_proc_addr;
    VkInstance instance;
    VkPhysicalDevice physical;
    VkDevice device;
    uint32_t queue_family, queue_index;
    const VkAllocationCallbacks *allocator;
    VkPipelineCache pipeline_cache;
    bool compute_queue;                       /* the host's compute queue for vksky_record_luts */
    uint32_t compute_family, compute_index;
    gpu_message_fn message;
    void *message_user;
} gpu_adopt_desc;

/* Returns 0 on success; -1 with a message on stderr (no device, validation layer missing, ...); -2: a bad
 * --device index. `message` (NULL: stderr) receives the messages instead, validation's included. */
int gpu_context_create(gpu_context *ctx, const gpu_context_desc *desc);
int gpu_context_create_with(gpu_context *ctx, const gpu_context_desc *desc, gpu_message_fn message, void *user,
                            const VkAllocationCallbacks *allocator);
/* 0, or a VkResult (VK_ERROR_INITIALIZATION_FAILED: the device is older than Vulkan 1.3), a message sent. */
VkResult gpu_context_adopt(gpu_context *ctx, const gpu_adopt_desc *desc);
/* The allocation callbacks of the context that owns `device` (NULL: Vulkan's default); set (NULL: forget) by the
 * context that makes or adopts the device. */
const VkAllocationCallbacks *gpu_allocator(VkDevice device);
void gpu_allocator_register(VkDevice device, const VkAllocationCallbacks *allocator);
/* Contexts alive in the process, own and adopted (a second one keeps device calls on the loader's dispatch). */
int gpu_context_live_count(void);
void gpu_context_live_add(int delta);
/* An adopted context's teardown (what vksky made on the host's device). */
void gpu_context_release(gpu_context *ctx);
/* One message through the context's callback, or stderr. */
void gpu_report(const gpu_context *ctx, int severity, const char *format, ...) __attribute__((format(printf, 3, 4)));
void gpu_context_destroy(gpu_context *ctx);
/* Prints the physical devices with their indices (for --list-devices). Returns 0 or -1. */
int gpu_list_devices(FILE *out);
/* The type of the device gpu_context_create would pick for device_index (-1: the default choice), from a bare
 * instance; 0, or -1 (no message) if there is none. For choices made before the context exists (--quality auto). */
int gpu_device_type(int device_index, VkPhysicalDeviceType *type);
/* The same from an instance with the validation layer on (synchronization validation included) when `validation`:
 * a run with --validate then adopts the probe's instance instead of making a second one (~20 ms of a 0.4 s validated
 * render on lavapipe). */
int gpu_device_type_for(int device_index, bool validation, VkPhysicalDeviceType *type);
/* What gpu_device_type's one probe cost, wall ms: the instance (and the Vulkan loader), the device enumeration. */
void gpu_probe_times(double *instance_ms, double *enumerate_ms);

/* Messages the validation layer reported so far (every one is also printed to stderr). */
unsigned gpu_validation_message_count(void);

/* The object's name (VK_EXT_debug_utils, when ctx->debug_utils), as "vksky." + name in lower case, '_' for spaces. */
void gpu_set_name(const gpu_context *ctx, VkObjectType type, uint64_t handle, const char *name);
void gpu_label_begin(const gpu_context *ctx, VkCommandBuffer cmd, const char *name);
void gpu_label_end(const gpu_context *ctx, VkCommandBuffer cmd);
/* A label around several passes (the API's "vksky.record" around a vksky_record), closed by gpu_label_end: no trace
 * line (the passes inside print theirs). */
void gpu_label_group_begin(const gpu_context *ctx, VkCommandBuffer cmd, const char *name);

/* One-shot command buffer: begin, then submit and wait for a fence. */
VkCommandBuffer gpu_begin_commands(const gpu_context *ctx);
void gpu_submit_and_wait(const gpu_context *ctx, VkCommandBuffer cmd);

#endif
