/* The window's swapchain: its images, their views and per-image "render finished" semaphores (swapchain.c). */
#ifndef VKSKY_APP_SWAPCHAIN_H
#define VKSKY_APP_SWAPCHAIN_H
#include "gpu/resources.h"

#define SWAPCHAIN_MAX_IMAGES 8

typedef struct GLFWwindow GLFWwindow;

typedef struct swapchain {
    VkSwapchainKHR handle;
    VkSurfaceFormatKHR format;
    VkExtent2D extent;
    uint32_t count;
    VkImage images[SWAPCHAIN_MAX_IMAGES];
    VkImageView views[SWAPCHAIN_MAX_IMAGES];
    VkSemaphore render_finished[SWAPCHAIN_MAX_IMAGES];   /* per image: see the top of window.c */
    /* VK_EXT_swapchain_maintenance1 (ctx->present_fences): the fence of the image's last present, signalled once
     * the presentation engine's wait on render_finished is over (docs/synchronization.md §6). */
    VkFence present_done[SWAPCHAIN_MAX_IMAGES];
    bool present_pending[SWAPCHAIN_MAX_IMAGES];
    bool can_copy;                             /* TRANSFER_SRC usage: screenshots */
} swapchain;

/* An 8-bit sRGB surface format if there is one, else a UNORM one, else the surface's first. */
VkSurfaceFormatKHR swapchain_choose_format(const gpu_context *ctx, VkSurfaceKHR surface);
/* (Re)create sc (its format chosen) at the surface's current size; false while the surface has no area. The
 * caller has waited for the device to go idle. report: print "swapchain WxH images N" (the resize test). */
bool swapchain_create(swapchain *sc, const gpu_context *ctx, VkSurfaceKHR surface, GLFWwindow *window, bool report);
/* The fence for the next present of image (VK_NULL_HANDLE without present fences): the previous present's
 * fence waited for and reset, then marked pending. */
VkFence swapchain_present_fence(swapchain *sc, const gpu_context *ctx, uint32_t image);
/* The views, semaphores and the swapchain (the device idle). */
void swapchain_destroy(swapchain *sc, const gpu_context *ctx);
#endif
