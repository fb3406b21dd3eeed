/* The frame spine (frame.c): every pass of a frame in order, with every barrier between them, recorded over the
 * renderer's resources into a command buffer. */
#ifndef VKSKY_SKY_FRAME_H
#define VKSKY_SKY_FRAME_H
#include "sky/renderer.h"

/* An image the tone map writes that the renderer does not own (a swapchain image). */
typedef struct frame_target {
    VkImage image;
    VkImageView view;
    VkExtent2D extent;
    gpu_usage before;            /* GPU_USAGE_ACQUIRED for a swapchain image */
    gpu_usage after;             /* GPU_USAGE_PRESENT for a swapchain image */
    gpu_buffer *capture;         /* non-NULL: also copy the image into this host buffer (4 bytes a pixel) */
    /* The library's host image (vksky_record): the host's own use before and after (stage, access, layout) instead
     * of before/after; traced as host.color.to_attachment and host.color.to_after. */
    bool host_uses;
    gpu_usage_info host_before, host_after;
    /* With host_uses, on a renderer of desc.host_storage_tonemap and the compute post chain: the compute tone map
     * writes the view as a storage image (R8G8B8A8_UNORM, sRGB encoded in the shader), traced as
     * host.color.to_compute_tonemap and host.color.compute_to_after. No capture. */
    bool storage;
} frame_target;

typedef struct frame_desc {
    const sky_view *view;
    bool force_luts;             /* recompute the LUTs even if they are up to date (benchmarks) */
    const frame_target *target;  /* NULL: the renderer's own display image (headless) */
    gpu_timer *timer;            /* NULL: the renderer's timer (one per frame in flight otherwise) */
    bool follows_frame;          /* another frame was recorded before this one into the same command buffer
                                    (VKSKY_FRAMES): its readback copies wrote the buffers this frame's rewrite */
    uint32_t meter_slot;         /* auto exposure (view->auto_exposure): the meter's result slot this frame writes and
                                    its tone map reads, one per frame in flight (< VKSKY_METER_SLOTS) */
    uint32_t meter_first_row, meter_rows;   /* the HDR rows the meter counts (a band's own, without the rows it
                                               shares with its neighbours); meter_rows 0: every row */
    const struct spectral_sum_step *sum;   /* a spectral group's frame (readback renderers): its composite added into
                                              the GPU's sum (sky/spectral_sum.h) in place of the readback copies */
} frame_desc;
void frame_record(sky_renderer *r, VkCommandBuffer cmd, const frame_desc *f);
/* A frame's first step alone (the composite frame's too): the LUT passes and their barriers, when the atmosphere
 * changed (or `force`); afterwards the LUTs are readable by compute and fragment shaders. */
/* `next`: the batch of the point after the LUTs, which receives their last barrier (one call per point); NULL:
 * flushed here. */
void frame_record_luts(sky_renderer *r, VkCommandBuffer cmd, bool force, gpu_barrier_batch *next);
/* A frame of its own (tests): LUT `img` (named `name`, last made readable by a LUT pass) copied into the host buffer
 * `buffer`, and back to the sampled layout for later frames. */
void frame_record_lut_readback(sky_renderer *r, VkCommandBuffer cmd, const gpu_image *img, const char *name,
                               VkBuffer buffer);
/* The library's LUT-only frame: the LUTs when stale, the sky-view LUT for f->view; afterwards all of them are
 * readable by compute and fragment shaders (the host's). */
void frame_record_luts_only(sky_renderer *r, VkCommandBuffer cmd, const frame_desc *f);
/* The LUT cache (sky/lut_cache.h): the cached LUTs copied from r->lut_staging in place of the LUT passes (their last
 * barrier into `next`, as frame_record_luts), and a frame of its own that copies them into the host buffer `buffer`
 * after they were computed, leaving them readable by shaders again. */
void frame_record_lut_cache_upload(sky_renderer *r, VkCommandBuffer cmd, gpu_barrier_batch *next);
void frame_record_lut_cache_readback(sky_renderer *r, VkCommandBuffer cmd, VkBuffer buffer);

/* --async-luts (sky/async_luts.c): the LUT passes into the compute queue's command buffer, closed by their last
 * barriers (write_to_sample, or the releases to the graphics family); the halves of the ownership transfer
 * (`release` on the compute queue, else the acquires, which the next frame's first point records). */
void frame_record_luts_compute(sky_renderer *r, VkCommandBuffer cmd);
void frame_add_lut_transfers(sky_renderer *r, gpu_barrier_batch *b, bool release);
#endif
