/* Versions, result names, messages (include/vksky.h). */
#include "lib/lib_internal.h"
#include <stdarg.h>
#include <stdio.h>

uint32_t vksky_abi_version(void) { return VKSKY_ABI_VERSION; }

const char *vksky_version_string(void) { return VKSKY_VERSION; }

const char *vksky_result_name(vksky_result result)
{
    switch (result) {
    case VKSKY_SUCCESS: return "VKSKY_SUCCESS";
    case VKSKY_ERROR_INVALID_ARGUMENT: return "VKSKY_ERROR_INVALID_ARGUMENT";
    case VKSKY_ERROR_ABI_MISMATCH: return "VKSKY_ERROR_ABI_MISMATCH";
    case VKSKY_ERROR_UNSUPPORTED: return "VKSKY_ERROR_UNSUPPORTED";
    case VKSKY_ERROR_VULKAN: return "VKSKY_ERROR_VULKAN";
    case VKSKY_ERROR_OUT_OF_MEMORY: return "VKSKY_ERROR_OUT_OF_MEMORY";
    case VKSKY_ERROR_IO: return "VKSKY_ERROR_IO";
    case VKSKY_ERROR_PARSE: return "VKSKY_ERROR_PARSE";
    case VKSKY_ERROR_DEVICE_LOST: return "VKSKY_ERROR_DEVICE_LOST";
    }
    return "VKSKY_RESULT_UNKNOWN";
}

void lib_message(vksky_message_fn fn, void *user, vksky_severity severity, const char *format, ...)
{
    if (!fn) return;
    char text[512];
    va_list args;
    va_start(args, format);
    vsnprintf(text, sizeof text, format, args);
    va_end(args);
    fn(user, severity, text);
}

void lib_gpu_message(void *user, int severity, const char *text)
{
    const vksky_context *c = user;
    if (c->message) c->message(c->message_user, (vksky_severity)severity, text);
}

vksky_result lib_result_from_vk(VkResult r)
{
    switch (r) {
    case VK_SUCCESS: return VKSKY_SUCCESS;
    case VK_ERROR_OUT_OF_HOST_MEMORY:
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
    case VK_ERROR_OUT_OF_POOL_MEMORY:
    case VK_ERROR_FRAGMENTED_POOL: return VKSKY_ERROR_OUT_OF_MEMORY;
    case VK_ERROR_DEVICE_LOST: return VKSKY_ERROR_DEVICE_LOST;
    case VK_ERROR_FEATURE_NOT_PRESENT:
    case VK_ERROR_FORMAT_NOT_SUPPORTED:
    case VK_ERROR_EXTENSION_NOT_PRESENT:
    case VK_ERROR_LAYER_NOT_PRESENT:
    case VK_ERROR_INCOMPATIBLE_DRIVER: return VKSKY_ERROR_UNSUPPORTED;
    default: return VKSKY_ERROR_VULKAN;
    }
}
