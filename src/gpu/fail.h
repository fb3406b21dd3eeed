/* Failures below the API: a Vulkan call that failed, or a bug of ours (a barrier batch overflowing). The command-line
 * tool prints one line and exits 1 (a runtime failure, not a user error); the library arms a trap around each of its
 * calls and gets the failure back as a result code instead (src/lib). One unit below context and barrier, so both
 * report failures the same way. */
#ifndef VKSKY_GPU_FAIL_H
#define VKSKY_GPU_FAIL_H
#include <volk.h>
#include <setjmp.h>

/* Always-on check: prints file:line, the call and the VkResult name, then exits with status 1 (a runtime
 * failure, not a user error); with a gpu_trap armed on the thread (the library's calls), jumps back to it instead.
 * Swapchain results are handled where they occur, never through this. */
#define VK_CHECK(call)                                                                                      \
    do {                                                                                                    \
        VkResult vk_check_result_ = (call);                                                                 \
        if (vk_check_result_ != VK_SUCCESS) gpu_fail_vk(__FILE__, __LINE__, #call, vk_check_result_);       \
    } while (0)

/* Where a failing Vulkan call goes instead of exit(1): the library arms one around each API call that creates
 * (src/lib), gpu_fail_vk records the failure and jumps back, and the API destroys what was made and returns a result
 * code. Everything the failed call made is reachable from the object being created (handles are written into it
 * as they are made), so nothing leaks. */
typedef struct gpu_trap {
    jmp_buf jump;
    VkResult result;
    char message[256];        /* "vkCreateImage failed: VK_ERROR_OUT_OF_DEVICE_MEMORY (src/gpu/resources.c:40)" */
} gpu_trap;
void gpu_trap_arm(gpu_trap *trap);   /* NULL disarms */

const char *gpu_result_name(VkResult r);
_Noreturn void gpu_fail_vk(const char *file, int line, const char *call, VkResult r);
/* A failure that is no Vulkan call's (no memory type fits): as gpu_fail_vk, with its own text. */
_Noreturn void gpu_fail(VkResult r, const char *text);
#endif
