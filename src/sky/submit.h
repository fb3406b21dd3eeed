/* Submission and readback over a renderer: a recorded frame submitted and waited for (headless, tests), a LUT
 * copied to the host (tests). The window submits its own frames (app/window/window.c: frames in flight). */
#ifndef VKSKY_SKY_SUBMIT_H
#define VKSKY_SKY_SUBMIT_H
#include "sky/frame.h"

/* Records a frame, submits it, waits. Returns wall milliseconds from submit to fence. */
double sky_renderer_render(sky_renderer *r, const frame_desc *f);
/* The same with the LUT passes on the context's compute queue (--async-luts; sky/async_luts.c): called by
 * sky_renderer_render when the context has one. */
double sky_renderer_render_async(sky_renderer *r, const frame_desc *f);
/* Its two halves (the window, once their other caller, is a host of include/vksky.h now): the LUT passes recorded
 * and submitted on the compute queue when stale (or `force`), returning their command buffer (free it from ctx->compute_pool once
 * the frame that waited for it is done) or VK_NULL_HANDLE; then the frame's semaphores: `signal` (graphics_done, the
 * next value) and, returned as the count 0 or 1, `wait` (compute_done at the LUT readers' stages) when `waits_luts`. */
VkCommandBuffer sky_renderer_submit_luts_async(sky_renderer *r, bool force);
uint32_t sky_async_frame_semaphores(gpu_context *ctx, bool waits_luts, VkSemaphoreSubmitInfo *wait,
                                    VkSemaphoreSubmitInfo *signal);
/* After a frame that computed the LUTs on a LUT cache miss (sky/lut_cache.h): read them back and write the cache
 * file (sky_renderer_render calls it; a host that submits frames itself may). */
void sky_renderer_store_luts(sky_renderer *r);
/* Copy a LUT to the host as the GPU stores it (tests): which 0 transmittance, 1 multiscatter; RGBA texels, 16 bytes
 * each for R32G32B32A32_SFLOAT, 8 (half bits) for R16G16B16A16_SFLOAT; texels_out holds 16 bytes x the extent's
 * pixels. Returns the LUT's format (VK_FORMAT_UNDEFINED: no such LUT in this variant, nothing written). */
VkExtent2D sky_renderer_lut_extent(const sky_renderer *r, int which);
VkFormat sky_renderer_read_lut(sky_renderer *r, int which, void *texels_out);
#endif
