/* The frame spine: every pass of a frame in order, and every barrier between them.
 *
 * Read this function top to bottom beside docs/synchronization.md. Each barrier names who wrote, who reads and
 * the hazard it prevents (RAW read-after-write, WAR write-after-read, WAW, layout transition). Passes record
 * their own draws/dispatches (luts.c, sky_pass.c, bloom.c, tonemap.c); barriers live only here. */
#include "sky/frame.h"
#include "sky/view_params.h"

/* How each frame image was last used by the previous frame: the first barrier of this frame waits for it (WAR)
 * and discards the contents (old layout UNDEFINED). */
#define HDR_LAST_USE GPU_USAGE_FRAGMENT_SAMPLED            /* bloom downsample 0 and tone map read it */
#define BLOOM_LAST_USE GPU_USAGE_FRAGMENT_SAMPLED          /* upsample sources and the tone map read the mips */
#define LUT_LAST_USE GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED    /* the last frame's sky pass (and multiscatter) read them */

static uint32_t timed_begin(sky_renderer *r, VkCommandBuffer cmd, const char *pass)
{
    if (r->pass_trace) fprintf(r->pass_trace, "pass %s\n", pass);
    gpu_label_begin(r->ctx, cmd, pass);
    return gpu_timer_begin(r->active_timer, cmd, pass);
}

static void timed_end(sky_renderer *r, VkCommandBuffer cmd, uint32_t slot)
{
    gpu_timer_end(r->active_timer, cmd, slot);
    gpu_label_end(r->ctx, cmd);
}

static void record_luts(sky_renderer *r, VkCommandBuffer cmd)
{
    sky_luts *l = &r->luts;
    VkImageSubresourceRange one = gpu_color_range(0, 1);

    /* Transmittance LUT: the previous frames' sky passes sampled it (WAR); to GENERAL for imageStore. */
    gpu_barrier_batch b = gpu_barrier_batch_begin("before transmittance_lut");
    gpu_barrier_add_image(&b, "transmittance.to_storage", "transmittance_lut", l->transmittance.image, one,
                          LUT_LAST_USE, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
    gpu_barrier_flush(cmd, &b);
    uint32_t t = timed_begin(r, cmd, "transmittance_lut");
    luts_record_transmittance(l, cmd);
    timed_end(r, cmd, t);

    /* The transmittance compute shader wrote the LUT; the multiscatter compute shader (and later the sky's
     * fragment shader) samples it: RAW + GENERAL -> SHADER_READ_ONLY. The multiscatter LUT was sampled by the
     * previous frames (WAR) and becomes the storage target. */
    b = gpu_barrier_batch_begin("before multiscatter_lut");
    gpu_barrier_add_image(&b, "transmittance.write_to_sample", "transmittance_lut", l->transmittance.image, one,
                          GPU_USAGE_COMPUTE_STORAGE_WRITE, GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, false);
    if (r->variant.multiscatter) {
        gpu_barrier_add_image(&b, "multiscatter.to_storage", "multiscatter_lut", l->multiscatter.image, one,
                              LUT_LAST_USE, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
        gpu_barrier_flush(cmd, &b);
        t = timed_begin(r, cmd, "multiscatter_lut");
        luts_record_multiscatter(l, cmd);
        timed_end(r, cmd, t);
        /* The multiscatter compute shader wrote its LUT; the sky pass (and the ground-irradiance LUT) sample it:
         * RAW + layout. (The usage covers compute too, so every frame's first barrier has the same source.) */
        b = gpu_barrier_batch_begin("after multiscatter_lut");
        gpu_barrier_add_image(&b, "multiscatter.write_to_sample", "multiscatter_lut", l->multiscatter.image, one,
                              GPU_USAGE_COMPUTE_STORAGE_WRITE, GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, false);
    }
    /* Without multi-scattering: no LUT, no pass (readers bind the transmittance LUT, made readable above). */
    if (r->variant.ground) {
        /* The sky's irradiance on the ground (a lit ground only): previous frames sampled it (WAR). */
        gpu_barrier_add_image(&b, "ground_irradiance.to_storage", "ground_irradiance_lut", l->ground_irradiance.image,
                              one, LUT_LAST_USE, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
        gpu_barrier_flush(cmd, &b);
        t = timed_begin(r, cmd, "ground_irradiance_lut");
        luts_record_ground_irradiance(l, cmd);
        timed_end(r, cmd, t);
        /* It wrote the LUT; the sky pass and the sky-view LUT sample it: RAW + layout. */
        b = gpu_barrier_batch_begin("after ground_irradiance_lut");
        gpu_barrier_add_image(&b, "ground_irradiance.write_to_sample", "ground_irradiance_lut",
                              l->ground_irradiance.image, one, GPU_USAGE_COMPUTE_STORAGE_WRITE,
                              GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, false);
    }
    gpu_barrier_flush(cmd, &b);
}

static void record_bloom(sky_renderer *r, VkCommandBuffer cmd, const sky_view *v)
{
    bloom_chain *bl = &r->bloom;
    char name[64];
    /* Downsample chain: pass i renders mip i from mip i-1 (from the HDR image for i = 0). */
    for (uint32_t i = 0; i < bl->mip_count; ++i) {
        uint32_t t = timed_begin(r, cmd, "bloom_downsample");
        bloom_record_downsample(bl, cmd, i, (float)v->bloom_threshold);
        timed_end(r, cmd, t);
        /* Downsample i wrote mip i; downsample i+1 (or upsample into mip i-1, for the last) samples it: RAW +
         * layout. One barrier range per mip: the mip being rendered is never the one being sampled. */
        gpu_barrier_batch b = gpu_barrier_batch_begin("bloom downsample chain");
        snprintf(name, sizeof name, "bloom.mip%u.write_to_sample", i);
        gpu_barrier_add_image(&b, name, "bloom", bl->mips.image, gpu_color_range(i, 1),
                              GPU_USAGE_COLOR_ATTACHMENT_WRITE, GPU_USAGE_FRAGMENT_SAMPLED, false);
        gpu_barrier_flush(cmd, &b);
    }
    /* Upsample chain: pass into mip i adds a tent-filtered mip i+1 onto mip i's own downsampled contents. */
    for (int i = (int)bl->mip_count - 2; i >= 0; --i) {
        /* Mip i was last sampled by downsample i+1 (WAR) and holds its downsample result, which the load op
         * LOAD and the blend read: SHADER_READ_ONLY -> COLOR_ATTACHMENT with COLOR_ATTACHMENT_READ|WRITE. */
        gpu_barrier_batch b = gpu_barrier_batch_begin("bloom upsample chain");
        snprintf(name, sizeof name, "bloom.mip%d.to_blend", i);
        gpu_barrier_add_image(&b, name, "bloom", bl->mips.image, gpu_color_range((uint32_t)i, 1),
                              GPU_USAGE_FRAGMENT_SAMPLED, GPU_USAGE_COLOR_ATTACHMENT_BLEND, false);
        gpu_barrier_flush(cmd, &b);
        uint32_t t = timed_begin(r, cmd, "bloom_upsample");
        bloom_record_upsample(bl, cmd, (uint32_t)i);
        timed_end(r, cmd, t);
        /* Upsample wrote mip i; the next upsample (or the tone map, for mip 0) samples it: RAW + layout. */
        b = gpu_barrier_batch_begin("bloom upsample chain");
        snprintf(name, sizeof name, "bloom.mip%d.blend_to_sample", i);
        gpu_barrier_add_image(&b, name, "bloom", bl->mips.image, gpu_color_range((uint32_t)i, 1),
                              GPU_USAGE_COLOR_ATTACHMENT_BLEND, GPU_USAGE_FRAGMENT_SAMPLED, false);
        gpu_barrier_flush(cmd, &b);
    }
}

static bool format_is_srgb(VkFormat f)
{
    return f == VK_FORMAT_R8G8B8A8_SRGB || f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_A8B8G8R8_SRGB_PACK32;
}

static void copy_to_buffer(VkCommandBuffer cmd, VkImage image, VkExtent2D extent, VkBuffer buffer)
{
    VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                .imageExtent = {extent.width, extent.height, 1}};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &region);
}

void frame_record(sky_renderer *r, VkCommandBuffer cmd, const frame_desc *f)
{
    const sky_view *v = f->view;
    VkImageSubresourceRange one = gpu_color_range(0, 1);
    bool bloom = v->bloom && r->desc.bloom;
    gpu_timer *timer = f->timer ? f->timer : &r->timer;
    r->active_timer = timer;
    gpu_timer_reset(timer, cmd);

    /* 1. LUTs, only when the atmosphere changed: transmittance, then multi-scattering (reads transmittance). */
    if (f->force_luts || sky_renderer_luts_dirty(r)) {
        record_luts(r, cmd);
        r->lut_hash = sky_atmosphere_lut_hash(&r->atmosphere, r->variant.sun_visibility);
        r->luts_valid = true;
    }

    /* 2. Sky. The sky pass runs as a fragment pass (HDR as colour attachment) or a compute dispatch (HDR as
     * storage image); with the sky-view LUT it first renders that LUT for this frame's camera and sun. */
    sky_mode mode = sky_view_resolve_mode(v, r->atmosphere.radii.z);
    sky_pass_kind kind = sky_view_pass_kind(v, r->ctx->props.deviceType);
    gpu_usage sky_reads = kind == SKY_PASS_COMPUTE ? GPU_USAGE_COMPUTE_SAMPLED : GPU_USAGE_FRAGMENT_SAMPLED;
    gpu_usage hdr_write = kind == SKY_PASS_COMPUTE ? GPU_USAGE_COMPUTE_STORAGE_WRITE : GPU_USAGE_COLOR_ATTACHMENT_WRITE;
    gpu_barrier_batch b;
    uint32_t t;
    if (mode == SKY_MODE_SKYVIEW) {
        /* The previous frame's sky pass sampled the sky-view LUT (WAR; either stage, the pass kind may have
         * changed); this frame's values replace it: UNDEFINED -> GENERAL. */
        b = gpu_barrier_batch_begin("before skyview_lut");
        gpu_barrier_add_image(&b, "skyview.to_storage", "skyview_lut", r->luts.skyview.image, one,
                              GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
        gpu_barrier_flush(cmd, &b);
        SkyPush sv = sky_view_skyview_push(v);
        t = timed_begin(r, cmd, "skyview_lut");
        luts_record_skyview(&r->luts, cmd, &sv);
        timed_end(r, cmd, t);
    }

    /* The previous frame's bloom and tone map sampled the HDR image (WAR); its contents are not needed (every
     * pixel is rewritten): UNDEFINED -> COLOR_ATTACHMENT (fragment) or GENERAL (compute). With the sky-view
     * LUT: the LUT pass wrote it, the sky pass samples it (RAW + layout). */
    b = gpu_barrier_batch_begin("before sky");
    gpu_barrier_add_image(&b, "hdr.to_sky", "hdr", r->hdr.image, one, HDR_LAST_USE, hdr_write, true);
    if (mode == SKY_MODE_SKYVIEW)
        gpu_barrier_add_image(&b, "skyview.write_to_sample", "skyview_lut", r->luts.skyview.image, one,
                              GPU_USAGE_COMPUTE_STORAGE_WRITE, sky_reads, false);
    gpu_barrier_flush(cmd, &b);
    SkyPush push = sky_view_push(v, r->hdr.extent.width, r->hdr.extent.height);
    t = timed_begin(r, cmd, "sky");
    sky_pass_record(&r->sky, cmd, kind, mode, &r->hdr, &push);
    timed_end(r, cmd, t);

    /* The sky pass wrote the HDR image; bloom downsample 0 and the tone map sample it: RAW + layout.
     * The bloom mips were sampled by the previous frame (WAR) and are rendered anew: UNDEFINED -> attachment. */
    b = gpu_barrier_batch_begin("after sky");
    gpu_barrier_add_image(&b, "hdr.write_to_sample", "hdr", r->hdr.image, one, hdr_write,
                          GPU_USAGE_FRAGMENT_SAMPLED, false);
    if (bloom)
        gpu_barrier_add_image(&b, "bloom.to_attachment", "bloom", r->bloom.mips.image,
                              gpu_color_range(0, r->bloom.mip_count), BLOOM_LAST_USE,
                              GPU_USAGE_COLOR_ATTACHMENT_WRITE, true);
    /* Bloom switched off at run time (the window's B key) with the chain still allocated: the tone map's
     * descriptor still names mip 0 and must find it in SHADER_READ_ONLY, though it never samples it (strength
     * 0). A never-rendered chain is UNDEFINED: a layout-only transition, contents discarded (WAR on reads). */
    else if (r->desc.bloom)
        gpu_barrier_add_image(&b, "bloom.off_to_sample", "bloom", r->bloom.mips.image, gpu_color_range(0, 1),
                              BLOOM_LAST_USE, GPU_USAGE_FRAGMENT_SAMPLED, true);
    gpu_barrier_flush(cmd, &b);

    /* 3. Bloom: 5 downsamples, 4 additive upsamples. */
    if (bloom) record_bloom(r, cmd, v);

    /* 4. Tone map into the display image (and the linear composite for EXR output). The previous frame's
     * readback copy read them (WAR), or for a swapchain image the acquire semaphore's wait stage; they are
     * fully rewritten. */
    frame_target own = {r->display.image, r->display.view, r->display.extent,
                        r->desc.readback ? GPU_USAGE_TRANSFER_SRC : GPU_USAGE_COLOR_ATTACHMENT_WRITE,
                        r->desc.readback ? GPU_USAGE_TRANSFER_SRC : GPU_USAGE_COLOR_ATTACHMENT_WRITE, NULL};
    const frame_target *display = f->target ? f->target : &own;
    b = gpu_barrier_batch_begin("before tonemap");
    gpu_barrier_add_image(&b, "display.to_attachment", "display", display->image, one, display->before,
                          GPU_USAGE_COLOR_ATTACHMENT_WRITE, true);
    if (r->desc.readback)
        gpu_barrier_add_image(&b, "composite.to_attachment", "composite", r->composite.image, one,
                              GPU_USAGE_TRANSFER_SRC, GPU_USAGE_COLOR_ATTACHMENT_WRITE, true);
    gpu_barrier_flush(cmd, &b);
    TonemapPush tm = sky_view_tonemap_push(v, !f->target ? false : !format_is_srgb(r->desc.display_format));
    if (!bloom) tm.params.z = 0.0f;
    t = timed_begin(r, cmd, "tonemap");
    tonemap_record(&r->tonemap, cmd, display->extent, display->view,
                   r->desc.readback ? r->composite.view : VK_NULL_HANDLE, &tm);
    timed_end(r, cmd, t);

    /* 5. Readback (headless): the tone map wrote both images; the copies read them: RAW + layout. Then the
     * copies wrote the host buffers; the CPU reads them after the fence: RAW (a fence alone does not make
     * device writes visible to the host; the HOST_READ barrier does). */
    if (r->desc.readback && !f->target) {
        b = gpu_barrier_batch_begin("before readback");
        gpu_barrier_add_image(&b, "display.write_to_copy", "display", r->display.image, one,
                              GPU_USAGE_COLOR_ATTACHMENT_WRITE, GPU_USAGE_TRANSFER_SRC, false);
        gpu_barrier_add_image(&b, "composite.write_to_copy", "composite", r->composite.image, one,
                              GPU_USAGE_COLOR_ATTACHMENT_WRITE, GPU_USAGE_TRANSFER_SRC, false);
        gpu_barrier_flush(cmd, &b);
        t = timed_begin(r, cmd, "readback");
        copy_to_buffer(cmd, r->composite.image, r->composite.extent, r->readback_linear.buffer);
        copy_to_buffer(cmd, r->display.image, r->display.extent, r->readback_display.buffer);
        timed_end(r, cmd, t);
        b = gpu_barrier_batch_begin("after readback");
        gpu_barrier_add_buffer(&b, "readback.linear_to_host", "readback_linear", r->readback_linear.buffer,
                               GPU_USAGE_TRANSFER_DST, GPU_USAGE_HOST_READ);
        gpu_barrier_add_buffer(&b, "readback.display_to_host", "readback_display", r->readback_display.buffer,
                               GPU_USAGE_TRANSFER_DST, GPU_USAGE_HOST_READ);
        gpu_barrier_flush(cmd, &b);
    }

    /* 6. An external target (swapchain image): optionally captured (screenshot), then handed to its next user.
     * To present: COLOR_ATTACHMENT -> PRESENT_SRC with no destination stage; the submit's signal semaphore, at
     * ALL_COMMANDS (window.c), orders presentation after the tone map's writes and this layout transition (a
     * signal at COLOR_ATTACHMENT_OUTPUT would need that stage as this barrier's destination). */
    if (f->target) {
        gpu_usage last = GPU_USAGE_COLOR_ATTACHMENT_WRITE;
        if (f->target->capture) {
            b = gpu_barrier_batch_begin("before capture");
            gpu_barrier_add_image(&b, "display.write_to_capture", "display", display->image, one,
                                  GPU_USAGE_COLOR_ATTACHMENT_WRITE, GPU_USAGE_TRANSFER_SRC, false);
            gpu_barrier_flush(cmd, &b);
            copy_to_buffer(cmd, display->image, display->extent, f->target->capture->buffer);
            b = gpu_barrier_batch_begin("after capture");
            gpu_barrier_add_buffer(&b, "capture.to_host", "capture", f->target->capture->buffer,
                                   GPU_USAGE_TRANSFER_DST, GPU_USAGE_HOST_READ);
            gpu_barrier_flush(cmd, &b);
            last = GPU_USAGE_TRANSFER_SRC;
        }
        if (f->target->after != last) {
            b = gpu_barrier_batch_begin("end of frame");
            gpu_barrier_add_image(&b, "display.to_present", "display", display->image, one, last,
                                  f->target->after, false);
            gpu_barrier_flush(cmd, &b);
        }
    }
}
