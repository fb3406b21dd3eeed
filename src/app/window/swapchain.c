/* The swapchain's life: format choice, (re)creation at the surface's size with oldSwapchain, the images' views
 * and "render finished" semaphores, destruction. Presentation itself (acquire, submit, present) is the window
 * loop's (window.c, whose top comment explains why each image owns its semaphore). */
#include <volk.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "app/window/swapchain.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* An 8-bit sRGB format lets the hardware encode; a UNORM one makes the spine tell the tone map to encode sRGB
 * itself (frame.c checks the format). Anything else: the surface's first format. VKSKY_SWAPCHAIN_UNORM=1 (a test
 * knob: ctest window_dither) prefers the UNORM formats, so that the tone map's own encoding, and its dither on the
 * encoded value, reach a swapchain too. */
VkSurfaceFormatKHR swapchain_choose_format(const gpu_context *ctx, VkSurfaceKHR surface)
{
    VkSurfaceFormatKHR formats[64];
    uint32_t n = 64;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx->physical, surface, &n, formats));
    static const VkFormat preferred[] = {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_UNORM,
                                         VK_FORMAT_R8G8B8A8_UNORM};
    const char *unorm = getenv("VKSKY_SWAPCHAIN_UNORM");
    size_t first = unorm && !strcmp(unorm, "1") ? 2 : 0;
    for (size_t p = first; p < sizeof preferred / sizeof preferred[0]; ++p)
        for (uint32_t i = 0; i < n; ++i)
            if (formats[i].format == preferred[p] && formats[i].colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
                return formats[i];
    return formats[0];
}

/* The semaphores' lifetime (docs/synchronization.md §6): a render-finished semaphore may be destroyed only once
 * the presentation engine's wait on it is over. With VK_EXT_swapchain_maintenance1 each present's fence says so;
 * without it nothing in core Vulkan does for a retired swapchain, and the caller's vkDeviceWaitIdle() is the
 * fallback that implementations honour in practice. */
static void swapchain_wait_presents(swapchain *sc, const gpu_context *ctx)
{
    for (uint32_t i = 0; i < sc->count; ++i)
        if (sc->present_pending[i]) {
            VK_CHECK(vkWaitForFences(ctx->device, 1, &sc->present_done[i], VK_TRUE, UINT64_MAX));
            sc->present_pending[i] = false;
        }
}

VkFence swapchain_present_fence(swapchain *sc, const gpu_context *ctx, uint32_t image)
{
    if (!ctx->present_fences) return VK_NULL_HANDLE;
    if (sc->present_pending[image]) {   /* the image's previous present: its fence must be unsignalled to reuse */
        VK_CHECK(vkWaitForFences(ctx->device, 1, &sc->present_done[image], VK_TRUE, UINT64_MAX));
        VK_CHECK(vkResetFences(ctx->device, 1, &sc->present_done[image]));
    }
    sc->present_pending[image] = true;
    return sc->present_done[image];
}

static void swapchain_destroy_views(swapchain *sc, const gpu_context *ctx)
{
    swapchain_wait_presents(sc, ctx);
    for (uint32_t i = 0; i < sc->count; ++i) {
        vkDestroyImageView(ctx->device, sc->views[i], NULL);
        vkDestroySemaphore(ctx->device, sc->render_finished[i], NULL);
        if (sc->present_done[i]) vkDestroyFence(ctx->device, sc->present_done[i], NULL);
        sc->present_done[i] = VK_NULL_HANDLE;
    }
    sc->count = 0;
}

static VkExtent2D swapchain_extent(GLFWwindow *window, const VkSurfaceCapabilitiesKHR *caps)
{
    if (caps->currentExtent.width != UINT32_MAX) return caps->currentExtent;
    int w, h;
    glfwGetFramebufferSize(window, &w, &h);
    VkExtent2D e = {(uint32_t)w, (uint32_t)h};
    e.width = e.width < caps->minImageExtent.width ? caps->minImageExtent.width : e.width;
    e.width = e.width > caps->maxImageExtent.width ? caps->maxImageExtent.width : e.width;
    e.height = e.height < caps->minImageExtent.height ? caps->minImageExtent.height : e.height;
    e.height = e.height > caps->maxImageExtent.height ? caps->maxImageExtent.height : e.height;
    return e;
}

static void swapchain_create_views(swapchain *sc, const gpu_context *ctx)
{
    sc->count = SWAPCHAIN_MAX_IMAGES;
    VK_CHECK(vkGetSwapchainImagesKHR(ctx->device, sc->handle, &sc->count, sc->images));
    VkSemaphoreCreateInfo sinfo = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    for (uint32_t i = 0; i < sc->count; ++i) {
        VkImageViewCreateInfo vinfo = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = sc->images[i],
                                       .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = sc->format.format,
                                       .subresourceRange = gpu_color_range(0, 1)};
        VK_CHECK(vkCreateImageView(ctx->device, &vinfo, NULL, &sc->views[i]));
        VK_CHECK(vkCreateSemaphore(ctx->device, &sinfo, NULL, &sc->render_finished[i]));
        if (ctx->present_fences) {
            VkFenceCreateInfo finfo = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
            VK_CHECK(vkCreateFence(ctx->device, &finfo, NULL, &sc->present_done[i]));
        }
        sc->present_pending[i] = false;
        char name[48];
        snprintf(name, sizeof name, "swapchain image %u", i);
        gpu_set_name(ctx, VK_OBJECT_TYPE_IMAGE, (uint64_t)sc->images[i], name);
        gpu_set_name(ctx, VK_OBJECT_TYPE_IMAGE_VIEW, (uint64_t)sc->views[i], name);
        snprintf(name, sizeof name, "render finished %u", i);
        gpu_set_name(ctx, VK_OBJECT_TYPE_SEMAPHORE, (uint64_t)sc->render_finished[i], name);
    }
}

/* (Re)create the swapchain at the surface's current size. Returns false while the surface has no area
 * (minimised). The caller has waited for the device to go idle: no command buffer still uses the old images or
 * views. The old images' semaphores are destroyed after their present fences where the device has them; without,
 * the idle device is the fallback (a present's semaphore wait belongs to the presentation engine, which core
 * Vulkan does not promise is over when the queue is idle: docs/synchronization.md §6). */
bool swapchain_create(swapchain *sc, const gpu_context *ctx, VkSurfaceKHR surface, GLFWwindow *window, bool report)
{
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx->physical, surface, &caps));
    VkExtent2D extent = swapchain_extent(window, &caps);
    if (extent.width == 0 || extent.height == 0) return false;
    uint32_t count = caps.minImageCount + 1;   /* one spare: acquire need not wait for the oldest present */
    if (caps.maxImageCount && count > caps.maxImageCount) count = caps.maxImageCount;
    if (count > SWAPCHAIN_MAX_IMAGES) count = SWAPCHAIN_MAX_IMAGES;
    sc->can_copy = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
    VkSwapchainKHR old = sc->handle;
    VkSwapchainCreateInfoKHR info = {
        .sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR, .surface = surface, .minImageCount = count,
        .imageFormat = sc->format.format, .imageColorSpace = sc->format.colorSpace, .imageExtent = extent,
        .imageArrayLayers = 1,
        .imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (sc->can_copy ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0),
        .imageSharingMode = VK_SHARING_MODE_EXCLUSIVE, .preTransform = caps.currentTransform,
        .compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, .presentMode = VK_PRESENT_MODE_FIFO_KHR,  /* always there */
        .clipped = VK_TRUE, .oldSwapchain = old,
    };
    if (!(caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR))
        info.compositeAlpha = VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR;
    VK_CHECK(vkCreateSwapchainKHR(ctx->device, &info, NULL, &sc->handle));
    swapchain_destroy_views(sc, ctx);
    if (old) vkDestroySwapchainKHR(ctx->device, old, NULL);
    sc->extent = extent;
    swapchain_create_views(sc, ctx);
    gpu_set_name(ctx, VK_OBJECT_TYPE_SWAPCHAIN_KHR, (uint64_t)sc->handle, "swapchain");
    if (report) printf("swapchain %ux%u images %u\n", extent.width, extent.height, sc->count);
    return true;
}

void swapchain_destroy(swapchain *sc, const gpu_context *ctx)
{
    swapchain_destroy_views(sc, ctx);
    if (sc->handle) vkDestroySwapchainKHR(ctx->device, sc->handle, NULL);
}
