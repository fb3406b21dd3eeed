#include "gpu/fail.h"
#include <stdio.h>
#include <stdlib.h>

const char *gpu_result_name(VkResult r)
{
    switch (r) {
#define R(x) case x: return #x;
    R(VK_SUCCESS) R(VK_NOT_READY) R(VK_TIMEOUT) R(VK_INCOMPLETE) R(VK_ERROR_OUT_OF_HOST_MEMORY)
    R(VK_ERROR_OUT_OF_DEVICE_MEMORY) R(VK_ERROR_INITIALIZATION_FAILED) R(VK_ERROR_DEVICE_LOST)
    R(VK_ERROR_MEMORY_MAP_FAILED) R(VK_ERROR_LAYER_NOT_PRESENT) R(VK_ERROR_EXTENSION_NOT_PRESENT)
    R(VK_ERROR_FEATURE_NOT_PRESENT) R(VK_ERROR_INCOMPATIBLE_DRIVER) R(VK_ERROR_TOO_MANY_OBJECTS)
    R(VK_ERROR_FORMAT_NOT_SUPPORTED) R(VK_ERROR_SURFACE_LOST_KHR) R(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
    R(VK_SUBOPTIMAL_KHR) R(VK_ERROR_OUT_OF_DATE_KHR)
#undef R
    default: return "VK_RESULT_UNKNOWN";
    }
}

static _Thread_local gpu_trap *armed_trap;

void gpu_trap_arm(gpu_trap *trap) { armed_trap = trap; }

void gpu_fail(VkResult r, const char *text)
{
    gpu_trap *trap = armed_trap;
    if (trap) {
        armed_trap = NULL;   /* a failure while cleaning up after this one is the caller's to see, not a loop */
        trap->result = r;
        snprintf(trap->message, sizeof trap->message, "%s", text);
        longjmp(trap->jump, 1);
    }
    fprintf(stderr, "vksky: %s\n", text);
    exit(1);
}

void gpu_fail_vk(const char *file, int line, const char *call, VkResult r)
{
    char text[256];
    /* The call's name alone ("vkCreateImage"), its result, where: the line a host's log can act on. */
    int name_len = 0;
    while (call[name_len] && call[name_len] != '(') name_len++;
    if (armed_trap) snprintf(text, sizeof text, "%.*s failed: %s (%s:%d)", name_len, call, gpu_result_name(r), file, line);
    else snprintf(text, sizeof text, "%s:%d: %s failed: %s (%d)", file, line, call, gpu_result_name(r), (int)r);
    gpu_fail(r, text);
}
