/* The host's device adopted (gpu_context_adopt), and what every context shares: the allocation callbacks by device,
 * the count of live contexts, the debug names and labels. See gpu/context.h. */
#include "gpu/context.h"
#include "gpu/barrier.h"
#include <stdio.h>
#include <pthread.h>

/* Contexts of a process are few (a host's device or two, the tests' pairs): a small table, behind a lock because
 * different contexts may live on different threads. */
enum { MAX_DEVICES = 32 };
static struct { VkDevice device; const VkAllocationCallbacks *allocator; } allocators[MAX_DEVICES];
static pthread_mutex_t table_lock = PTHREAD_MUTEX_INITIALIZER;
static int live_count;

const VkAllocationCallbacks *gpu_allocator(VkDevice device)
{
    const VkAllocationCallbacks *found = NULL;
    pthread_mutex_lock(&table_lock);
    for (int i = 0; i < MAX_DEVICES; ++i)
        if (allocators[i].device == device) found = allocators[i].allocator;
    pthread_mutex_unlock(&table_lock);
    return found;
}

void gpu_allocator_register(VkDevice device, const VkAllocationCallbacks *allocator)
{
    pthread_mutex_lock(&table_lock);
    int slot = -1;
    for (int i = 0; i < MAX_DEVICES; ++i)
        if (allocators[i].device == device) slot = i;
    /* Only callbacks need a slot: a device without any finds none and gets NULL. */
    if (slot < 0 && allocator)
        for (int i = 0; i < MAX_DEVICES && slot < 0; ++i)
            if (!allocators[i].device) slot = i;
    if (slot >= 0) {
        allocators[slot].device = allocator ? device : VK_NULL_HANDLE;
        allocators[slot].allocator = allocator;
    }
    pthread_mutex_unlock(&table_lock);
}

int gpu_context_live_count(void)
{
    pthread_mutex_lock(&table_lock);
    int n = live_count;
    pthread_mutex_unlock(&table_lock);
    return n;
}

void gpu_context_live_add(int delta)
{
    pthread_mutex_lock(&table_lock);
    live_count += delta;
    pthread_mutex_unlock(&table_lock);
}

VkResult gpu_context_adopt(gpu_context *ctx, const gpu_adopt_desc *d)
{
    *ctx = (gpu_context){.instance = d->instance, .physical = d->physical, .device = d->device,
                         .queue_family = d->queue_family, .allocator = d->allocator, .message = d->message,
                         .message_user = d->message_user, .pipeline_cache = d->pipeline_cache};
    /* The host's loader entry, and every function through it: instance functions resolved for its instance,
     * device functions as the loader's dispatching entries (never volkLoadDevice: that would bind the process's
     * table to one device). */
    volkInitializeCustom(d->get_instance_proc_addr);
    volkLoadInstance(d->instance);
    if (!vkGetPhysicalDeviceProperties || !vkGetDeviceQueue || !vkCreateCommandPool) {
        gpu_report(ctx, 2, "the host's vkGetInstanceProcAddr gives no Vulkan 1.3 core functions");
        *ctx = (gpu_context){0};
        return VK_ERROR_INITIALIZATION_FAILED;
    }
    vkGetPhysicalDeviceProperties(ctx->physical, &ctx->props);
    if (ctx->props.apiVersion < VK_API_VERSION_1_3) {
        gpu_report(ctx, 2, "the host's device is Vulkan %u.%u; vksky needs 1.3", VK_API_VERSION_MAJOR(ctx->props.apiVersion),
                   VK_API_VERSION_MINOR(ctx->props.apiVersion));
        *ctx = (gpu_context){0};
        return VK_ERROR_INITIALIZATION_FAILED;
    }
    vkGetPhysicalDeviceMemoryProperties(ctx->physical, &ctx->memory);
    uint32_t qn = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(ctx->physical, &qn, NULL);
    VkQueueFamilyProperties qprops[16];
    if (qn > 16) qn = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(ctx->physical, &qn, qprops);
    if (d->queue_family >= qn ||
        (qprops[d->queue_family].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) !=
            (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT) ||
        d->queue_index >= qprops[d->queue_family].queueCount) {
        gpu_report(ctx, 2, "queue family %u, index %u: not a graphics+compute queue of the device", d->queue_family,
                   d->queue_index);
        *ctx = (gpu_context){0};
        return VK_ERROR_INITIALIZATION_FAILED;
    }
    ctx->timestamps = qprops[d->queue_family].timestampValidBits > 0 && ctx->props.limits.timestampPeriod > 0;
    ctx->timestamp_period_ns = ctx->props.limits.timestampPeriod;
    /* The features the host enabled cannot be read back from a VkDevice: the single-pass bloom's memory model is
     * not assumed (the per-level chain serves), names and labels are not given (the host's debug utils may be off). */
    vkGetDeviceQueue(ctx->device, d->queue_family, d->queue_index, &ctx->queue);
    if (d->compute_queue) {   /* the host's compute queue (vksky_record_luts): vksky records for it, never submits */
        if (d->compute_family >= qn || !(qprops[d->compute_family].queueFlags & VK_QUEUE_COMPUTE_BIT) ||
            d->compute_index >= qprops[d->compute_family].queueCount) {
            gpu_report(ctx, 2, "compute queue family %u, index %u: not a compute queue of the device",
                       d->compute_family, d->compute_index);
            *ctx = (gpu_context){0};
            return VK_ERROR_INITIALIZATION_FAILED;
        }
        ctx->compute_family = d->compute_family, ctx->compute_index = d->compute_index;
        vkGetDeviceQueue(ctx->device, d->compute_family, d->compute_index, &ctx->compute_queue);
    }
    gpu_allocator_register(ctx->device, ctx->allocator);
    VkCommandPoolCreateInfo pinfo = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
        .queueFamilyIndex = ctx->queue_family,
    };
    VkResult r = vkCreateCommandPool(ctx->device, &pinfo, ctx->allocator, &ctx->command_pool);
    if (r != VK_SUCCESS) {
        gpu_report(ctx, 2, "vkCreateCommandPool failed: %s", gpu_result_name(r));
        gpu_allocator_register(ctx->device, NULL);
        *ctx = (gpu_context){0};
        return r;
    }
    gpu_context_live_add(1);
    return VK_SUCCESS;
}

void gpu_context_release(gpu_context *ctx)
{
    if (ctx->command_pool) {
        /* The host's queue may still run vksky's one-time uploads: they were waited for, nothing is pending. */
        vkDestroyCommandPool(ctx->device, ctx->command_pool, ctx->allocator);
        gpu_context_live_add(-1);
    }
    gpu_allocator_register(ctx->device, NULL);
    *ctx = (gpu_context){0};
}

/* "vksky." and the name in lower case, each run of other characters one '_' ("transmittance LUT" ->
 * "vksky.transmittance_lut"): in a host's frame capture vksky's objects are told from the host's at a glance. */
static void vksky_object_name(const char *name, char *out, size_t size)
{
    size_t n = (size_t)snprintf(out, size, "vksky.");
    bool gap = false;
    for (const char *c = name; *c && n + 2 < size; ++c) {
        bool keep = (*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || (*c >= 'A' && *c <= 'Z') || *c == '.';
        if (!keep) {
            gap = true;
            continue;
        }
        if (gap && out[n - 1] != '.') out[n++] = '_';
        gap = false;
        out[n++] = (*c >= 'A' && *c <= 'Z') ? (char)(*c - 'A' + 'a') : *c;
    }
    out[n] = '\0';
}

void gpu_set_name(const gpu_context *ctx, VkObjectType type, uint64_t handle, const char *name)
{
    if (!ctx->debug_utils || !vkSetDebugUtilsObjectNameEXT) return;
    char full[128];
    vksky_object_name(name, full, sizeof full);
    VkDebugUtilsObjectNameInfoEXT info = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT,
        .objectType = type,
        .objectHandle = handle,
        .pObjectName = full,
    };
    vkSetDebugUtilsObjectNameEXT(ctx->device, &info);
}

void gpu_label_begin(const gpu_context *ctx, VkCommandBuffer cmd, const char *name)
{
    gpu_barrier_trace_pass(name);
    if (!ctx->debug_utils || !vkCmdBeginDebugUtilsLabelEXT) return;
    VkDebugUtilsLabelEXT label = {.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT, .pLabelName = name};
    vkCmdBeginDebugUtilsLabelEXT(cmd, &label);
}

void gpu_label_group_begin(const gpu_context *ctx, VkCommandBuffer cmd, const char *name)
{
    if (!ctx->debug_utils || !vkCmdBeginDebugUtilsLabelEXT) return;
    VkDebugUtilsLabelEXT label = {.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT, .pLabelName = name};
    vkCmdBeginDebugUtilsLabelEXT(cmd, &label);
}

void gpu_label_end(const gpu_context *ctx, VkCommandBuffer cmd)
{
    if (!ctx->debug_utils || !vkCmdEndDebugUtilsLabelEXT) return;
    vkCmdEndDebugUtilsLabelEXT(cmd);
}
