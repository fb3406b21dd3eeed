/* Contexts: the host's device adopted, or vksky's own (include/vksky.h). */
#include "lib/lib_internal.h"
#include "gpu/pipeline_cache.h"
#include "sky/limits.h"
#include <stdlib.h>

void vksky_get_device_requirements(vksky_device_requirements *out)
{
    if (!out) return;
    sky_limit_needs n;
    sky_limits_needed(true, &n);   /* the shared memory of the single pass, the most vksky uses */
    *out = (vksky_device_requirements){.synchronization2 = true, .dynamic_rendering = true, .maintenance4 = true,
                                       .vulkan_memory_model = true, .vulkan_memory_model_device_scope = true,
                                       .max_compute_work_group_invocations = n.compute_work_group_invocations,
                                       .max_per_stage_descriptor_storage_images = n.per_stage_storage_images,
                                       .max_compute_shared_memory_size = n.compute_shared_memory,
                                       .max_push_constants_size = n.push_constants};
}

/* The device's limits against the pipelines' needs (sky/limits.h): 0, or the line to the callback and -1. */
static int check_limits(vksky_context *c, const char *call)
{
    char why[256];
    if (sky_limits_apply(&c->gpu, why, sizeof why) == 0) return 0;
    lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR, "%s: %s", call, why);
    return -1;
}

vksky_result vksky_context_create(const vksky_context_desc *desc, vksky_context **out)
{
    if (out) *out = NULL;
    if (!desc || !out) return VKSKY_ERROR_INVALID_ARGUMENT;
    if (desc->abi_version != VKSKY_ABI_VERSION) {
        lib_message(desc->message, desc->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_context_create: abi_version %u; this library is ABI %u", desc->abi_version,
                    VKSKY_ABI_VERSION);
        return VKSKY_ERROR_ABI_MISMATCH;
    }
    if (!desc->get_instance_proc_addr || !desc->instance || !desc->physical_device || !desc->device) {
        lib_message(desc->message, desc->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_context_create: get_instance_proc_addr, instance, physical_device and device are required");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    vksky_context *c = calloc(1, sizeof *c);
    if (!c) return VKSKY_ERROR_OUT_OF_MEMORY;
    c->message = desc->message, c->message_user = desc->message_user;
    gpu_adopt_desc adopt = {
        .get_instance_proc_addr = desc->get_instance_proc_addr, .instance = desc->instance,
        .physical = desc->physical_device, .device = desc->device, .queue_family = desc->queue_family,
        .queue_index = desc->queue_index, .allocator = desc->allocator, .pipeline_cache = desc->pipeline_cache,
        .message = lib_gpu_message, .message_user = c, .compute_queue = desc->compute_queue,
        .compute_family = desc->compute_queue_family, .compute_index = desc->compute_queue_index};
    VkResult r = gpu_context_adopt(&c->gpu, &adopt);
    if (r != VK_SUCCESS) {
        free(c);
        return r == VK_ERROR_INITIALIZATION_FAILED ? VKSKY_ERROR_UNSUPPORTED : lib_result_from_vk(r);
    }
    if (check_limits(c, "vksky_context_create") != 0) {
        gpu_context_release(&c->gpu);
        free(c);
        return VKSKY_ERROR_UNSUPPORTED;
    }
    *out = c;
    return VKSKY_SUCCESS;
}

vksky_result vksky_context_set_device_features(vksky_context *context, const vksky_device_requirements *enabled)
{
    if (!context || !enabled) return VKSKY_ERROR_INVALID_ARGUMENT;
    if (!enabled->synchronization2 || !enabled->dynamic_rendering || !enabled->maintenance4) {
        lib_message(context->message, context->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_context_set_device_features: synchronization2, dynamic_rendering and maintenance4 are "
                    "required (vksky_get_device_requirements)");
        return VKSKY_ERROR_UNSUPPORTED;
    }
    if (context->renderers > 0) {
        lib_message(context->message, context->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_context_set_device_features: before the first renderer (its pipelines are chosen by them)");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    /* bloom_spd.comp's coherent device-scope accesses need both (gpu/context.h). */
    context->gpu.memory_model_device_scope = enabled->vulkan_memory_model && enabled->vulkan_memory_model_device_scope;
    /* The single pass only where its shared memory fits (else the per-level chain, an info line). */
    return check_limits(context, "vksky_context_set_device_features") == 0 ? VKSKY_SUCCESS : VKSKY_ERROR_UNSUPPORTED;
}

vksky_result vksky_context_set_debug_utils(vksky_context *context, bool enabled)
{
    if (!context) return VKSKY_ERROR_INVALID_ARGUMENT;
    if (context->renderers > 0) {
        lib_message(context->message, context->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_context_set_debug_utils: before the first renderer (its objects are named at creation)");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    /* The host's word for its instance; vksky's own instance: only where it enabled the extension. The functions
     * come through the host's vkGetInstanceProcAddr (gpu/context_adopt.c); without them nothing is called. */
    bool available = context->gpu.owns_device ? context->own_debug_utils : true;
    if (enabled && (!available || !vkSetDebugUtilsObjectNameEXT || !vkCmdBeginDebugUtilsLabelEXT ||
                    !vkCmdEndDebugUtilsLabelEXT)) {
        lib_message(context->message, context->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_context_set_debug_utils: the instance's VK_EXT_debug_utils functions are missing");
        return VKSKY_ERROR_UNSUPPORTED;
    }
    context->gpu.debug_utils = enabled;
    return VKSKY_SUCCESS;
}

vksky_result vksky_context_create_own(const vksky_own_device_desc *desc, vksky_context **out)
{
    if (out) *out = NULL;
    if (!desc || !out) return VKSKY_ERROR_INVALID_ARGUMENT;
    if (desc->abi_version != VKSKY_ABI_VERSION) {
        lib_message(desc->message, desc->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_context_create_own: abi_version %u; this library is ABI %u", desc->abi_version,
                    VKSKY_ABI_VERSION);
        return VKSKY_ERROR_ABI_MISMATCH;
    }
    vksky_context *c = calloc(1, sizeof *c);
    if (!c) return VKSKY_ERROR_OUT_OF_MEMORY;
    c->message = desc->message, c->message_user = desc->message_user;
    gpu_context_desc gd = {.validation = desc->validation, .device_index = desc->device_index,
                           .instance_extensions = desc->instance_extensions,
                           .instance_extension_count = desc->instance_extension_count,
                           .want_swapchain = desc->swapchain,
                           .async_compute = desc->compute_queue ? GPU_ASYNC_ON : GPU_ASYNC_OFF};
    gpu_trap trap;
    if (setjmp(trap.jump)) {
        /* A failing Vulkan call after the device was made (its command pool, the messenger). */
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR, "%s", trap.message);
        gpu_context_destroy(&c->gpu);
        free(c);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    int rc = gpu_context_create_with(&c->gpu, &gd, lib_gpu_message, c, NULL);
    gpu_trap_arm(NULL);
    if (rc != 0) {
        free(c);
        return rc == -2 ? VKSKY_ERROR_INVALID_ARGUMENT : VKSKY_ERROR_UNSUPPORTED;
    }
    c->own_debug_utils = c->gpu.debug_utils;
    if (check_limits(c, "vksky_context_create_own") != 0) {
        gpu_context_destroy(&c->gpu);
        free(c);
        return VKSKY_ERROR_UNSUPPORTED;
    }
    *out = c;
    return VKSKY_SUCCESS;
}

void vksky_context_destroy(vksky_context *context)
{
    if (!context) return;
    if (context->renderers > 0)
        lib_message(context->message, context->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_context_destroy: %d renderer%s still alive; destroy them first (the context is kept)",
                    context->renderers, context->renderers == 1 ? "" : "s");
    if (context->renderers > 0) return;
    gpu_cache_dir_attach(&context->gpu, NULL);
    gpu_context_destroy(&context->gpu);
    free(context);
}

vksky_result vksky_context_set_cache_directory(vksky_context *context, const char *directory)
{
    if (!context) return VKSKY_ERROR_INVALID_ARGUMENT;
    if (context->renderers > 0 || !gpu_cache_dir_attach(&context->gpu, directory)) {
        lib_message(context->message, context->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_context_set_cache_directory: %s", context->renderers > 0
                        ? "after a renderer was created (set it first)" : "the path is too long");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    return VKSKY_SUCCESS;
}

void vksky_context_get_handles(const vksky_context *context, vksky_context_handles *out)
{
    if (!out) return;
    *out = (vksky_context_handles){0};
    if (!context) return;
    *out = (vksky_context_handles){.instance = context->gpu.instance, .physical_device = context->gpu.physical,
                                   .device = context->gpu.device, .queue = context->gpu.queue,
                                   .queue_family = context->gpu.queue_family,
                                   .compute_queue = context->gpu.compute_queue,
                                   .compute_queue_family = context->gpu.compute_family};
}

uint32_t vksky_context_validation_message_count(const vksky_context *context)
{
    return context ? context->gpu.validation_messages : 0;
}

vksky_result vksky_context_set_trace(vksky_context *context, uint32_t what, vksky_trace_fn line, void *user)
{
    if (!context || (what & ~(uint32_t)(VKSKY_TRACE_BARRIERS | VKSKY_TRACE_PASSES))) return VKSKY_ERROR_INVALID_ARGUMENT;
    bool on = what && line;
    context->trace = (gpu_trace_sink){.line = on ? line : NULL, .user = user,
                                      .barriers = on && (what & VKSKY_TRACE_BARRIERS),
                                      .passes = on && (what & VKSKY_TRACE_PASSES)};
    return VKSKY_SUCCESS;
}

const gpu_trace_sink *lib_trace_begin(const vksky_context *c)
{
    /* A context with no trace of its own: the process-wide streams (NULL bound), never another context's sink. */
    return gpu_trace_bind(c->trace.line ? &c->trace : NULL);
}

void lib_trace_end(const gpu_trace_sink *was) { gpu_trace_bind(was); }
