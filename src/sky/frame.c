/* The frame spine: every pass of a frame in order, and every barrier between them.
 *
 * Read this function top to bottom beside docs/synchronization.md. Each barrier names who wrote, who reads and
 * the hazard it prevents (RAW read-after-write, WAR write-after-read, WAW, layout transition). Passes record
 * their own draws/dispatches (luts.c, sky_pass.c, bloom.c, tonemap.c); barriers live only in the frame functions,
 * one per kind of frame, each read top to bottom: frame_record (a view: headless, bands, sequences, the window,
 * readback, capture and a library host's colour image included) here; the LUT passes and the frames of LUTs alone
 * (frame_record_luts, frame_record_lut_readback, frame_record_luts_only, the compute queue's) in frame_luts.c; composite_frame_record (the composite's
 * frame, composite.c) and host_frame_record (the library's SCENE_LINEAR frame, host_frame.c). Nothing else in src/
 * records a barrier. */
#include "sky/frame.h"
#include "sky/frame_parts.h"
#include "sky/spectral_sum.h"
#include "sky/view_params.h"
#include "sky/tonemap_regions.h"
#include "gpu/async_queue.h"

/* How each frame image was last used by the previous frame: the first barrier of this frame waits for it (WAR)
 * and discards the contents (old layout UNDEFINED). */
#define HDR_LAST_USE GPU_USAGE_FRAGMENT_SAMPLED            /* bloom downsample 0 and tone map read it */
#define BLOOM_LAST_USE GPU_USAGE_FRAGMENT_SAMPLED          /* upsample sources and the tone map read the mips */
/* With the compute post chain: the single-pass downsampler and the compute tone map sample the HDR image; the
 * mips and tile counters were last touched by compute shaders, or (a swapchain target) mip 0 by the fragment
 * tone map. */
#define HDR_LAST_USE_COMPUTE GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED
#define CHAIN_LAST_USE_COMPUTE GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED

/* A pass: its debug label (gpu_label_begin also prints its `pass` trace line, the one pass trace) and timestamps. */
uint32_t frame_timed_begin(sky_renderer *r, VkCommandBuffer cmd, const char *pass)
{
    gpu_label_begin(r->ctx, cmd, pass);
    return gpu_timer_begin(r->active_timer, cmd, pass);
}

void frame_timed_end(sky_renderer *r, VkCommandBuffer cmd, uint32_t slot)
{
    gpu_timer_end(r->active_timer, cmd, slot);
    gpu_label_end(r->ctx, cmd);
}

/* One barrier on one mip of the bloom chain, named after its mip (e.g. "bloom.mip2.write_to_sample"). */
static void mip_barrier(gpu_barrier_batch *b, const bloom_chain *bl, const char *what, int mip, gpu_usage from,
                        gpu_usage to)
{
    char name[64];
    snprintf(name, sizeof name, "bloom.mip%d.%s", mip, what);
    gpu_barrier_add_image(b, name, "bloom", bl->mips.image, gpu_color_range((uint32_t)mip, 1), from, to, false);
}

/* The same hand-off between two compute passes that keep the chain in GENERAL: a global memory barrier (the
 * canonical compute -> compute pattern; no layout to change, so no image needs naming). */
static void mip_memory_barrier(gpu_barrier_batch *b, const char *what, int mip)
{
    char name[64], resource[32];
    snprintf(name, sizeof name, "bloom.mip%d.%s", mip, what);
    snprintf(resource, sizeof resource, "bloom_mip%d", mip);
    gpu_barrier_add_memory(b, name, resource, GPU_USAGE_COMPUTE_STORAGE_RW, GPU_USAGE_COMPUTE_STORAGE_RW);
}

/* The fragment bloom chain. Its last barrier (mip 0 made readable) goes into `next`, the tone map's point. */
static void record_bloom(sky_renderer *r, VkCommandBuffer cmd, const sky_view *v, gpu_barrier_batch *next)
{
    bloom_chain *bl = &r->bloom;
    int n = (int)bl->mip_count;
    gpu_barrier_batch b = {0}, *at;
    /* Downsample chain: pass i renders mip i from mip i-1 (from the HDR image for i = 0). */
    for (int i = 0; i < n; ++i) {
        uint32_t t = frame_timed_begin(r, cmd, "bloom_downsample");
        bloom_record_downsample(bl, cmd, (uint32_t)i, (float)v->bloom_threshold);
        frame_timed_end(r, cmd, t);
        /* Downsample i wrote mip i; downsample i+1 (or upsample into mip i-1, for the last) samples it: RAW +
         * layout. One barrier range per mip: the mip being rendered is never the one being sampled. The last
         * one shares its call with the first upsample's barrier. */
        at = &b;
        if (i + 1 < n) b = gpu_barrier_batch_begin("bloom downsample chain");
        else if (n > 1) b = gpu_barrier_batch_begin("bloom downsample -> upsample");
        else at = next;
        mip_barrier(at, bl, "write_to_sample", i, GPU_USAGE_COLOR_ATTACHMENT_WRITE, GPU_USAGE_FRAGMENT_SAMPLED);
        if (i + 1 < n) gpu_barrier_flush(cmd, &b);
    }
    /* Upsample chain: pass into mip i adds a tent-filtered mip i+1 onto mip i's own downsampled contents. */
    for (int i = n - 2; i >= 0; --i) {
        /* Mip i was last sampled by downsample i+1 (WAR) and holds its downsample result, which the load op
         * LOAD and the blend read: SHADER_READ_ONLY -> COLOR_ATTACHMENT with COLOR_ATTACHMENT_READ|WRITE. Same
         * call as the barrier that made mip i+1 readable. */
        mip_barrier(&b, bl, "to_blend", i, GPU_USAGE_FRAGMENT_SAMPLED, GPU_USAGE_COLOR_ATTACHMENT_BLEND);
        gpu_barrier_flush(cmd, &b);
        uint32_t t = frame_timed_begin(r, cmd, "bloom_upsample");
        bloom_record_upsample(bl, cmd, (uint32_t)i);
        frame_timed_end(r, cmd, t);
        /* Upsample wrote mip i; the next upsample (or the tone map, for mip 0) samples it: RAW + layout. */
        at = next;
        if (i > 0) b = gpu_barrier_batch_begin("bloom upsample chain"), at = &b;
        mip_barrier(at, bl, "blend_to_sample", i, GPU_USAGE_COLOR_ATTACHMENT_BLEND, GPU_USAGE_FRAGMENT_SAMPLED);
    }
}

static bool format_is_srgb(VkFormat f)
{
    return f == VK_FORMAT_R8G8B8A8_SRGB || f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_A8B8G8R8_SRGB_PACK32;
}

void frame_copy_to_buffer(VkCommandBuffer cmd, VkImage image, VkExtent2D extent, VkBuffer buffer)
{
    VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                .imageExtent = {extent.width, extent.height, 1}};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &region);
}

/* Step 5 of a spectral group's frame (ABI 4; sky/spectral_sum.h, docs/synchronization.md §20): the tone map
 * (`writer`) wrote the composite; the sum samples it and adds it into its accumulation image; the last group resolves
 * the sum into the host's buffer. The display and composite stay as left (r->display_last, composite_last): the next
 * frame's first barriers on them start there. */
static void record_spectral_sum(sky_renderer *r, VkCommandBuffer cmd, const spectral_sum_step *step, gpu_usage writer)
{
    spectral_sum *s = step->sum;
    VkImageSubresourceRange one = gpu_color_range(0, 1);
    bool first = step->push.mode.x > 0.5f, last = step->push.mode.y > 0.5f;
    spectral_sum_bind(step, &r->composite);
    gpu_barrier_batch b = gpu_barrier_batch_begin("before spectral sum");
    /* The group frame's tone map wrote its composite; the sum samples it: RAW + layout. */
    gpu_barrier_add_image(&b, "spectral.composite_to_sum", "composite", r->composite.image, one, writer,
                          GPU_USAGE_COMPUTE_SAMPLED, false);
    if (first)   /* the previous frame's groups wrote the sum and its last group read it: WAW + WAR, contents dropped */
        gpu_barrier_add_image(&b, "spectral.sum_to_first", "spectral_sum", s->accum.image, one,
                              s->accum_written ? GPU_USAGE_COMPUTE_STORAGE_RW : GPU_USAGE_NONE,
                              GPU_USAGE_COMPUTE_STORAGE_RW, true);
    else         /* the group before added into the sum; this one reads and rewrites it: RAW + WAW */
        gpu_barrier_add_image(&b, "spectral.sum_to_add", "spectral_sum", s->accum.image, one,
                              GPU_USAGE_COMPUTE_STORAGE_RW, GPU_USAGE_COMPUTE_STORAGE_RW, false);
    gpu_barrier_flush(cmd, &b);
    s->accum_written = true;
    uint32_t t = frame_timed_begin(r, cmd, "spectral_sum");
    spectral_sum_dispatch(step, cmd);
    frame_timed_end(r, cmd, t);
    r->display_last = writer, r->composite_last = GPU_USAGE_COMPUTE_SAMPLED;
    if (!last) return;   /* nothing of the sum's is read before the next group's step */
    /* The resolve wrote the host's buffer; the CPU reads it after the fence: RAW (as readback.linear_to_host). */
    b = gpu_barrier_batch_begin("after spectral sum");
    gpu_barrier_add_buffer(&b, "spectral.resolved_to_host", "spectral_resolved", s->resolved.buffer,
                           GPU_USAGE_COMPUTE_STORAGE_WRITE, GPU_USAGE_HOST_READ);
    gpu_barrier_flush(cmd, &b);
}

/* Step 5, readback (or a spectral group's sum on the GPU, f->sum): the tone map (`writer`) wrote the display and
 * composite images; the copies read them: RAW +
 * layout. Then the copies wrote the host buffers; the CPU reads them after the fence: RAW (a fence alone does
 * not make device writes visible to the host; the HOST_READ barrier does). */
static void record_readback(sky_renderer *r, VkCommandBuffer cmd, const frame_desc *f, gpu_usage writer,
                            const char *display_name, const char *composite_name)
{
    if (f->sum) {   /* a spectral group: its composite added into the GPU's sum instead (sky/spectral_sum.h) */
        record_spectral_sum(r, cmd, f->sum, writer);
        return;
    }
    VkImageSubresourceRange one = gpu_color_range(0, 1);
    gpu_barrier_batch b = gpu_barrier_batch_begin("before readback");
    gpu_barrier_add_image(&b, display_name, "display", r->display.image, one, writer, GPU_USAGE_TRANSFER_SRC, false);
    gpu_barrier_add_image(&b, composite_name, "composite", r->composite.image, one, writer, GPU_USAGE_TRANSFER_SRC,
                          false);
    if (f->follows_frame) {
        /* The previous frame's copies wrote the readback buffers; this frame's copies rewrite them: WAW. Between
         * real frames the fence wait and the host's read order them; frames recorded back to back into one command
         * buffer (VKSKY_FRAMES) need this barrier instead. */
        gpu_barrier_add_buffer(&b, "frames.readback_linear", "readback_linear", r->readback_linear.buffer,
                               GPU_USAGE_TRANSFER_DST, GPU_USAGE_TRANSFER_DST);
        gpu_barrier_add_buffer(&b, "frames.readback_display", "readback_display", r->readback_display.buffer,
                               GPU_USAGE_TRANSFER_DST, GPU_USAGE_TRANSFER_DST);
    }
    gpu_barrier_flush(cmd, &b);
    r->display_last = r->composite_last = GPU_USAGE_TRANSFER_SRC;
    uint32_t t = frame_timed_begin(r, cmd, "readback");
    frame_copy_to_buffer(cmd, r->composite.image, r->composite.extent, r->readback_linear.buffer);
    frame_copy_to_buffer(cmd, r->display.image, r->display.extent, r->readback_display.buffer);
    frame_timed_end(r, cmd, t);
    b = gpu_barrier_batch_begin("after readback");
    gpu_barrier_add_buffer(&b, "readback.linear_to_host", "readback_linear", r->readback_linear.buffer,
                           GPU_USAGE_TRANSFER_DST, GPU_USAGE_HOST_READ);
    gpu_barrier_add_buffer(&b, "readback.display_to_host", "readback_display", r->readback_display.buffer,
                           GPU_USAGE_TRANSFER_DST, GPU_USAGE_HOST_READ);
    gpu_barrier_flush(cmd, &b);
}

/* Step 2b, auto exposure's meter (sky/meter.h, meter.comp; issue 32): the log-average luminance of the HDR image in two
 * dispatches, its result read by this frame's tone map: a reduction feeding a later pass of the same frame. Its last
 * barriers go into `next`, the batch of the point after the sky pass (bloom's, or the tone map's). */
static void record_meter(sky_renderer *r, VkCommandBuffer cmd, const frame_desc *f, gpu_usage hdr_write,
                         gpu_barrier_batch *next)
{
    double scale = f->view->ev100 ? f->view->light_scale : 1.0;
    bool every_pixel = r->variant.ground;   /* a lit ground is part of the scene; the black void below it is not */
    VkBuffer buf = r->meter.buffer.buffer;
    /* The sky pass wrote the HDR image; the meter, then bloom and the tone map (compute or fragment), sample it: RAW +
     * layout (it replaces hdr.write_to_sample / hdr.write_to_compute_sample). The previous frame's average read the
     * partials and its tone map a result; this frame rewrites them (one buffer for the frames in flight): WAR. */
    gpu_barrier_batch b = gpu_barrier_batch_begin("before meter");
    gpu_barrier_add_image(&b, "meter.hdr_to_read", "hdr", r->hdr.image, gpu_color_range(0, 1), hdr_write,
                          GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, false);
    gpu_barrier_add_buffer(&b, "meter.to_write", "meter", buf, GPU_USAGE_SHADER_STORAGE_READ,
                           GPU_USAGE_COMPUTE_STORAGE_WRITE);
    gpu_barrier_flush(cmd, &b);
    uint32_t t = frame_timed_begin(r, cmd, "meter");
    meter_record_tiles(&r->meter, cmd, scale, every_pixel, f->meter_first_row, f->meter_rows,
                       f->view->projection == VKSKY_PROJECTION_FISHEYE, f->view->tile_y);
    frame_timed_end(r, cmd, t);
    /* The tiles wrote their partial sums; the average reads them: RAW. The average also writes the buffer (result[slot]
     * and `adapted`, bytes the tiles never write, so no WAW by the specification's definition of a data race); its
     * destination access says so, because a validator that tracks a descriptor's whole range, not the bytes a
     * shader touches, counts a WAW otherwise (docs/synchronization.md §14, "What a newer layer sees"). */
    b = gpu_barrier_batch_begin("before meter_average");
    gpu_barrier_add_buffer(&b, "meter.partials_to_average", "meter", buf, GPU_USAGE_COMPUTE_STORAGE_WRITE,
                           GPU_USAGE_COMPUTE_STORAGE_READ_WRITE);
    gpu_barrier_flush(cmd, &b);
    t = frame_timed_begin(r, cmd, "meter_average");
    meter_record_average(&r->meter, cmd, scale, every_pixel, f->meter_slot % VKSKY_METER_SLOTS,
                         f->view->auto_exposure_ease);
    frame_timed_end(r, cmd, t);
    /* The average wrote result[slot]; the tone map (compute or fragment) reads it: RAW. The host reads it after the
     * frame's fence (the title's EV100, the run's line): RAW (a fence alone makes nothing visible to the host). */
    gpu_barrier_add_buffer(next, "meter.result_to_tonemap", "meter", buf, GPU_USAGE_COMPUTE_STORAGE_WRITE,
                           GPU_USAGE_SHADER_STORAGE_READ);
    gpu_barrier_add_buffer(next, "meter.result_to_host", "meter", buf, GPU_USAGE_COMPUTE_STORAGE_WRITE,
                           GPU_USAGE_HOST_READ);
}

/* Steps 3-5 with the compute post chain: the bloom chain in one dispatch (plus the upsamples), the tone map as
 * a dispatch fused with the last upsample. Everything the chain touches stays in GENERAL. Returns false when
 * the target needs the fragment tone map (a swapchain image), which the caller then records: its last barrier
 * (mip 0 made readable by fragment shaders) is then in `next`, the tone map's point. */
static bool record_post_compute(sky_renderer *r, VkCommandBuffer cmd, const frame_desc *f, gpu_usage hdr_write,
                                bool bloom, gpu_barrier_batch *next)
{
    const sky_view *v = f->view;
    bloom_chain *bl = &r->bloom;
    post_compute *pc = &r->post;
    VkImageSubresourceRange one = gpu_color_range(0, 1);
    /* A library host's storage-capable image (frame_target.storage): the compute tone map writes it directly. */
    const frame_target *host = f->target && f->target->storage && f->target->host_uses && !f->target->capture &&
                               pc->host_tonemap ? f->target : NULL;
    bool compute_tonemap = (pc->tonemap && !f->target) || host;
    bool spd = bloom && r->desc.bloom_downsample == BLOOM_DOWN_SINGLE_PASS && pc->spd_pipeline;   /* post.c */
    uint32_t t;

    /* The sky pass wrote the HDR image; the single pass (bloom level 0) and the tone map sample it, both compute
     * shaders: RAW + layout. The mips were read by the previous frame's chain and tone map (WAR) and are
     * rewritten: UNDEFINED -> GENERAL. The tile counters were read and written by the previous frame's single
     * pass's atomics (WAR, WAW); the clear rewrites them: UNDEFINED -> GENERAL. */
    /* Without bloom no pass follows before the tone map: these barriers join the tone map's point. */
    gpu_barrier_batch b = gpu_barrier_batch_begin(bloom ? "after sky (compute post)" : "before tonemap (compute)");
    gpu_barrier_batch *first = bloom || compute_tonemap ? &b : next;
    if (v->auto_exposure)   /* 2b: meter.hdr_to_read makes it readable; the meter's last barriers join this point */
        record_meter(r, cmd, f, hdr_write, first);
    else
        gpu_barrier_add_image(first, "hdr.write_to_compute_sample", "hdr", r->hdr.image, one, hdr_write,
                              compute_tonemap ? GPU_USAGE_COMPUTE_SAMPLED : GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, false);
    if (bloom) {
        gpu_barrier_add_image(&b, "bloom.to_storage", "bloom", bl->mips.image, gpu_color_range(0, bl->mip_count),
                              CHAIN_LAST_USE_COMPUTE, GPU_USAGE_COMPUTE_STORAGE_RW, true);
        if (spd)
            gpu_barrier_add_image(&b, "spd_counters.to_clear", "spd_counters", pc->counters.image, one,
                                  GPU_USAGE_COMPUTE_STORAGE_RW, GPU_USAGE_CLEAR_DST, true);
    } else if (r->desc.bloom && compute_tonemap) {
        /* Bloom switched off at run time: the tone map's descriptors still name mips 0 and 1 in GENERAL, never
         * sampled (strength 0): a layout-only transition (WAR on the previous frame's reads). */
        gpu_barrier_add_image(first, "bloom.off_to_storage", "bloom", bl->mips.image, gpu_color_range(0, bl->mip_count),
                              CHAIN_LAST_USE_COMPUTE, GPU_USAGE_COMPUTE_STORAGE_RW, true);
    } else if (r->desc.bloom) {
        /* The same for the fragment tone map (a swapchain target): its descriptor names mip 0 in SHADER_READ_ONLY.
         * One transition, UNDEFINED -> SHADER_READ_ONLY, whose own source stages hold the previous frame's reads
         * (WAR): not GENERAL first and SHADER_READ_ONLY second, where the second transition would be ordered after
         * those reads only through the first, which the specification does not promise (docs/synchronization.md
         * §14, "What a newer layer sees"). */
        gpu_barrier_add_image(next, "bloom.off_to_sample", "bloom", bl->mips.image, one, CHAIN_LAST_USE_COMPUTE,
                              GPU_USAGE_FRAGMENT_SAMPLED, true);
    }
    if (bloom) gpu_barrier_flush(cmd, &b);

    if (bloom && !spd) {
        /* One dispatch per level (the fragment chain's structure, compute shaders): level k wrote mip k; level
         * k+1 samples it: RAW. Every mip stays in GENERAL: a global memory barrier. */
        for (uint32_t k = 0; k < bl->mip_count; ++k) {
            t = frame_timed_begin(r, cmd, "bloom_downsample");
            post_record_downsample_level(pc, bl, cmd, k, r->hdr.extent, (float)v->bloom_threshold);
            frame_timed_end(r, cmd, t);
            if (k + 1 < bl->mip_count) {
                b = gpu_barrier_batch_begin("bloom downsample chain (compute)");
                mip_memory_barrier(&b, "down_to_read", (int)k);
                gpu_barrier_flush(cmd, &b);
            }
        }
        /* The last level wrote its mip (RAW for the first upsample); and the upsamples rewrite mips the later
         * levels sampled (WAR): one global barrier for the chain. */
        b = gpu_barrier_batch_begin("bloom downsample chain (compute)");
        gpu_barrier_add_memory(&b, "bloom.down_to_upsample", "bloom", GPU_USAGE_COMPUTE_STORAGE_RW,
                               GPU_USAGE_COMPUTE_STORAGE_RW);
        gpu_barrier_flush(cmd, &b);
    } else if (spd) {
        /* The clear, a transfer command, in a label of its own: it is not part of the dispatch's timing. */
        gpu_label_begin(r->ctx, cmd, "spd_counters_clear");
        post_record_clear_counters(pc, cmd);
        gpu_label_end(r->ctx, cmd);
        /* The clear wrote the counters; the single pass's atomics read and write them: RAW + WAW. */
        b = gpu_barrier_batch_begin("before bloom_spd");
        gpu_barrier_add_image(&b, "spd_counters.clear_to_atomic", "spd_counters", pc->counters.image, one,
                              GPU_USAGE_CLEAR_DST, GPU_USAGE_COMPUTE_STORAGE_RW, false);
        gpu_barrier_flush(cmd, &b);
        /* One dispatch, every level: inside it workgroups hand tiles on through the counters (bloom_spd.comp;
         * docs/synchronization.md, "Inside the single-pass downsampler"), no barrier of the API's. */
        t = frame_timed_begin(r, cmd, "bloom_spd");
        post_record_downsample(pc, cmd, (float)v->bloom_threshold);
        frame_timed_end(r, cmd, t);
        /* The single pass wrote every level; the upsamples (and the tone map) read them: a global barrier. */
        b = gpu_barrier_batch_begin("after bloom_spd");
        gpu_barrier_add_memory(&b, "bloom.spd_to_upsample", "bloom", GPU_USAGE_COMPUTE_STORAGE_RW,
                               GPU_USAGE_COMPUTE_STORAGE_RW);
        gpu_barrier_flush(cmd, &b);
    }
    /* The point before the tone map: the last upsample's barrier and the tone map's own share one call. */
    if (bloom && compute_tonemap) b = gpu_barrier_batch_begin("before tonemap (compute)");
    if (bloom) {
        /* Upsamples down to mip 1 (mip 0's is fused into the compute tone map; a swapchain target's fragment
         * tone map needs it done: down to mip 0). */
        int last = compute_tonemap ? 1 : 0;
        for (int i = (int)bl->mip_count - 2; i >= last; --i) {
            t = frame_timed_begin(r, cmd, "bloom_upsample");
            post_record_upsample(pc, bl, cmd, (uint32_t)i);
            frame_timed_end(r, cmd, t);
            /* Upsample wrote mip i; the next upsample (or the compute tone map) reads it: RAW, a global barrier.
             * (Mip 0, written only for the fragment tone map: bloom.mip0.storage_to_fragment is its barrier.) */
            if (i == 0) continue;
            if (i == last) {
                mip_memory_barrier(&b, "up_to_read", i);
                continue;
            }
            gpu_barrier_batch c = gpu_barrier_batch_begin("bloom upsample chain (compute)");
            mip_memory_barrier(&c, "up_to_read", i);
            gpu_barrier_flush(cmd, &c);
        }
    }

    TonemapPush tm = sky_view_tonemap_push(v, compute_tonemap ? true : !format_is_srgb(r->desc.display_format));
    if (!bloom) tm.params.z = 0.0f;
    tm.meter.y = (float)(f->meter_slot % VKSKY_METER_SLOTS);
    if (host) {
        /* The host's image, from its own last use (whatever it was); the tone map rewrites every pixel (WAR or WAW
         * on that use, the layout to GENERAL). */
        gpu_barrier_add_image_info(&b, "host.color.to_compute_tonemap", "host color", host->image, one, host->host_before,
                                   *gpu_usage_get(GPU_USAGE_COMPUTE_STORAGE_WRITE), true);
        gpu_barrier_flush(cmd, &b);
        t = frame_timed_begin(r, cmd, "tonemap");
        post_record_tonemap_set(pc, bl, cmd, host->extent, &tm, post_host_set(pc, r->ctx, host->view));
        frame_timed_end(r, cmd, t);
        /* The tone map's writes made available to the host's next use, in its layout (RAW or WAW, and the layout it
         * asked for). */
        b = gpu_barrier_batch_begin("end of frame");
        gpu_barrier_add_image_info(&b, "host.color.compute_to_after", "host color", host->image, one,
                                   *gpu_usage_get(GPU_USAGE_COMPUTE_STORAGE_WRITE), host->host_after, false);
        gpu_barrier_flush(cmd, &b);
        return true;
    }
    if (compute_tonemap) {
        /* The display and composite images were read by the previous frame's readback copies (WAR); the
         * compute tone map rewrites every pixel: UNDEFINED -> GENERAL. */
        gpu_barrier_add_image(&b, "display.to_storage", "display", r->display.image, one,
                              r->desc.readback ? r->display_last : GPU_USAGE_TRANSFER_SRC,
                              GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
        if (r->desc.readback)
            gpu_barrier_add_image(&b, "composite.to_storage", "composite", r->composite.image, one,
                                  r->composite_last, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
        gpu_barrier_flush(cmd, &b);
        t = frame_timed_begin(r, cmd, "tonemap");
        post_record_tonemap(pc, bl, cmd, r->display.extent, &tm);
        frame_timed_end(r, cmd, t);
        if (r->desc.readback) {
            record_readback(r, cmd, f, GPU_USAGE_COMPUTE_STORAGE_WRITE, "display.storage_to_copy",
                            "composite.storage_to_copy");
        }
        return true;
    }
    /* A target the compute tone map cannot write (a swapchain image): the fragment tone map follows (frame_record
     * step 4); it samples mip 0, which the compute upsample wrote: RAW + GENERAL -> SHADER_READ_ONLY. */
    if (bloom)
        gpu_barrier_add_image(next, "bloom.mip0.storage_to_fragment", "bloom", bl->mips.image, one,
                              GPU_USAGE_COMPUTE_STORAGE_RW, GPU_USAGE_FRAGMENT_SAMPLED, false);
    return false;
}

void frame_record(sky_renderer *r, VkCommandBuffer cmd, const frame_desc *f)
{
    const sky_view *v = f->view;
    VkImageSubresourceRange one = gpu_color_range(0, 1);
    bool bloom = v->bloom && r->desc.bloom;
    gpu_timer *timer = f->timer ? f->timer : &r->timer;
    r->active_timer = timer;
    gpu_timer_reset(timer, cmd);

    sky_mode mode = sky_view_resolve_mode(v, r->atmosphere.radii.z);
    sky_pass_kind kind = sky_view_pass_kind(v, r->ctx->props.deviceType);
    gpu_usage sky_reads = kind == SKY_PASS_COMPUTE ? GPU_USAGE_COMPUTE_SAMPLED : GPU_USAGE_FRAGMENT_SAMPLED;
    gpu_usage hdr_write = kind == SKY_PASS_COMPUTE ? GPU_USAGE_COMPUTE_STORAGE_WRITE : GPU_USAGE_COLOR_ATTACHMENT_WRITE;
    uint32_t t;

    /* 1. LUTs, only when the atmosphere changed: transmittance, then multi-scattering (reads transmittance). The
     * barrier that makes the last LUT readable joins the next point's call (the sky-view LUT's, or the sky's). */
    gpu_barrier_batch b = gpu_barrier_batch_begin(mode == SKY_MODE_SKYVIEW ? "before skyview_lut" : "before sky");
    frame_record_luts_if_dirty(r, cmd, f->force_luts, &b);

    /* 2. Sky. The sky pass runs as a fragment pass (HDR as colour attachment) or a compute dispatch (HDR as
     * storage image); with the sky-view LUT it first renders that LUT for this frame's camera and sun. */
    if (mode == SKY_MODE_SKYVIEW) {
        /* The previous frame's sky pass sampled the sky-view LUT (WAR; either stage, the pass kind may have
         * changed); this frame's values replace it: UNDEFINED -> GENERAL. */
        gpu_barrier_add_image(&b, "skyview.to_storage", "skyview_lut", r->luts.skyview.image, one,
                              GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
        gpu_barrier_flush(cmd, &b);
        SkyPush sv = sky_view_skyview_push(v);
        t = frame_timed_begin(r, cmd, "skyview_lut");
        luts_record_skyview(&r->luts, cmd, &sv);
        frame_timed_end(r, cmd, t);
        b = gpu_barrier_batch_begin("before sky");
    }

    /* The previous frame's bloom and tone map sampled the HDR image (WAR); its contents are not needed (every
     * pixel is rewritten): UNDEFINED -> COLOR_ATTACHMENT (fragment) or GENERAL (compute). With the sky-view
     * LUT: the LUT pass wrote it, the sky pass samples it (RAW + layout). */
    /* (A metered frame's meter sampled it too, in a compute shader: hdr_metered.) */
    gpu_barrier_add_image(&b, "hdr.to_sky", "hdr", r->hdr.image, one,
                          r->post_kind == POST_PASS_COMPUTE || r->hdr_metered ? HDR_LAST_USE_COMPUTE : HDR_LAST_USE,
                          hdr_write, true);
    if (mode == SKY_MODE_SKYVIEW)
        gpu_barrier_add_image(&b, "skyview.write_to_sample", "skyview_lut", r->luts.skyview.image, one,
                              GPU_USAGE_COMPUTE_STORAGE_WRITE, sky_reads, false);
    gpu_barrier_flush(cmd, &b);
    SkyPush push = sky_view_push(v, r->hdr.extent.width, r->hdr.extent.height,
                                 (double)r->desc.width / (double)r->desc.height);
    /* The horizon from the camera's altitude in double; at render scale 1 the sky pass resolves each pixel's
     * coverage of sky and ground, below it the tone map's upsample does (shaders/glsl/horizon.glsl). */
    sky_view_set_horizon(&push, v, r->medium.bottom_radius, r->medium.top_radius - r->medium.bottom_radius,
                         r->hdr.extent.width == r->desc.width && r->hdr.extent.height == r->desc.height);
    t = frame_timed_begin(r, cmd, "sky");
    sky_pass_record(&r->sky, cmd, kind, mode, &r->hdr, &push);
    frame_timed_end(r, cmd, t);
    /* 2b. Auto exposure: the meter reads the HDR image, the tone map its result (record_meter, at step 3's start). */
    r->hdr_metered = v->auto_exposure;

    /* 3. Post: the compute chain (bloom in one dispatch + upsamples, tone map fused with the last upsample:
     * record_post_compute, which for its own display image also does steps 4 and 5), or the fragment chain. */
    gpu_barrier_batch before_tonemap = gpu_barrier_batch_begin("before tonemap");
    if (r->post_kind == POST_PASS_COMPUTE) {
        if (record_post_compute(r, cmd, f, hdr_write, bloom, &before_tonemap)) return;
    } else {
        /* The sky pass wrote the HDR image; bloom downsample 0 and the tone map sample it: RAW + layout.
         * The bloom mips were sampled by the previous frame (WAR) and are rendered anew: UNDEFINED -> attachment. */
        b = gpu_barrier_batch_begin("after sky");
        /* Without bloom no pass follows before the tone map: these join its point. */
        gpu_barrier_batch *after_sky = bloom ? &b : &before_tonemap;
        if (v->auto_exposure)   /* 2b: meter.hdr_to_read makes it readable; the meter's last barriers join this point */
            record_meter(r, cmd, f, hdr_write, after_sky);
        else
            gpu_barrier_add_image(after_sky, "hdr.write_to_sample", "hdr", r->hdr.image, one, hdr_write,
                                  GPU_USAGE_FRAGMENT_SAMPLED, false);
        if (bloom)
            gpu_barrier_add_image(&b, "bloom.to_attachment", "bloom", r->bloom.mips.image,
                                  gpu_color_range(0, r->bloom.mip_count), BLOOM_LAST_USE,
                                  GPU_USAGE_COLOR_ATTACHMENT_WRITE, true);
        /* Bloom switched off at run time (the window's B key) with the chain still allocated: the tone map's
         * descriptor still names mip 0 and must find it in SHADER_READ_ONLY, though it never samples it (strength
         * 0). A never-rendered chain is UNDEFINED: a layout-only transition, contents discarded (WAR on reads). */
        else if (r->desc.bloom)
            gpu_barrier_add_image(after_sky, "bloom.off_to_sample", "bloom", r->bloom.mips.image, gpu_color_range(0, 1),
                                  BLOOM_LAST_USE, GPU_USAGE_FRAGMENT_SAMPLED, true);
        if (bloom) gpu_barrier_flush(cmd, &b);

        /* Bloom: 5 downsamples, 4 additive upsamples; the last barrier joins the tone map's point. */
        if (bloom) record_bloom(r, cmd, v, &before_tonemap);
    }

    /* 4. Tone map into the display image (and the linear composite for EXR output). The previous frame's
     * readback copy read them (WAR), or for a swapchain image the acquire semaphore's wait stage; they are
     * fully rewritten. */
    frame_target own = {r->display.image, r->display.view, r->display.extent,
                        r->desc.readback ? r->display_last : GPU_USAGE_COLOR_ATTACHMENT_WRITE,
                        r->desc.readback ? GPU_USAGE_TRANSFER_SRC : GPU_USAGE_COLOR_ATTACHMENT_WRITE, .capture = NULL};
    const frame_target *display = f->target ? f->target : &own;
    b = before_tonemap;
    if (display->host_uses)   /* the host's image: from its own last use (whatever it was) */
        gpu_barrier_add_image_info(&b, "host.color.to_attachment", "host color", display->image, one,
                                   display->host_before, *gpu_usage_get(GPU_USAGE_COLOR_ATTACHMENT_WRITE), true);
    else
        gpu_barrier_add_image(&b, "display.to_attachment", "display", display->image, one, display->before,
                              GPU_USAGE_COLOR_ATTACHMENT_WRITE, true);
    if (r->desc.readback)
        gpu_barrier_add_image(&b, "composite.to_attachment", "composite", r->composite.image, one,
                              r->composite_last, GPU_USAGE_COLOR_ATTACHMENT_WRITE, true);
    gpu_barrier_flush(cmd, &b);
    TonemapPush tm = sky_view_tonemap_push(v, !f->target ? false : !format_is_srgb(r->desc.display_format));
    if (!bloom) tm.params.z = 0.0f;
    tm.meter.y = (float)(f->meter_slot % VKSKY_METER_SLOTS);
    /* Issue 26: the horizon path only in the tiles it may reach (sky/tonemap_regions.h). */
    tonemap_regions regions;
    tonemap_regions_plan(&regions, &push, r->hdr.extent, display->extent);
    t = frame_timed_begin(r, cmd, "tonemap");
    tonemap_record(&r->tonemap, cmd, display->extent, display->view,
                   r->desc.readback ? r->composite.view : VK_NULL_HANDLE, &tm, &regions,
                   r->hdr.extent.width == display->extent.width && r->hdr.extent.height == display->extent.height);
    frame_timed_end(r, cmd, t);

    /* 5. Readback (headless): record_readback. */
    if (r->desc.readback && !f->target) {
        record_readback(r, cmd, f, GPU_USAGE_COLOR_ATTACHMENT_WRITE, "display.write_to_copy",
                        "composite.write_to_copy");
    }

    /* 6. An external target (swapchain image): optionally captured (screenshot), then handed to its next user.
     * To present: COLOR_ATTACHMENT -> PRESENT_SRC with no destination stage; the submit's signal semaphore, at
     * ALL_COMMANDS (window.c), orders presentation after the tone map's writes and this layout transition (a
     * signal at COLOR_ATTACHMENT_OUTPUT would need that stage as this barrier's destination). */
    if (f->target) {
        gpu_usage last = GPU_USAGE_COLOR_ATTACHMENT_WRITE;
        b = gpu_barrier_batch_begin("end of frame");
        if (f->target->capture) {
            gpu_barrier_batch c = gpu_barrier_batch_begin("before capture");
            gpu_barrier_add_image(&c, "display.write_to_capture", "display", display->image, one,
                                  GPU_USAGE_COLOR_ATTACHMENT_WRITE, GPU_USAGE_TRANSFER_SRC, false);
            gpu_barrier_flush(cmd, &c);
            gpu_label_begin(r->ctx, cmd, "capture");
            frame_copy_to_buffer(cmd, display->image, display->extent, f->target->capture->buffer);
            gpu_label_end(r->ctx, cmd);
            /* The copy wrote the buffer; the host reads it after the fence (RAW). Same call as the present's. */
            gpu_barrier_add_buffer(&b, "capture.to_host", "capture", f->target->capture->buffer,
                                   GPU_USAGE_TRANSFER_DST, GPU_USAGE_HOST_READ);
            last = GPU_USAGE_TRANSFER_SRC;
        }
        /* The host's image: the tone map's writes made available to the host's next use, in its layout (RAW or
         * WAW, and the layout it asked for). */
        if (f->target->host_uses)
            gpu_barrier_add_image_info(&b, "host.color.to_after", "host color", display->image, one,
                                       *gpu_usage_get(last), f->target->host_after, false);
        else if (f->target->after != last)
            gpu_barrier_add_image(&b, "display.to_present", "display", display->image, one, last, f->target->after,
                                  false);
        gpu_barrier_flush(cmd, &b);
    }
}
