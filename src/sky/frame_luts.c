/* The LUTs' part of the frame spine: the LUT passes in order with the barriers between them, and the frames that
 * consist of LUTs alone (a LUT read back for tests, the library's LUT-only frame, the LUTs on an async compute
 * queue). frame.c's frame_record calls frame_record_luts_if_dirty as its first step. Read beside
 * docs/synchronization.md (§3, §10, §17); like frame.c, each barrier names writer, reader and hazard. */
#include "sky/frame.h"
#include "sky/frame_parts.h"
#include "sky/view_params.h"
#include "sky/lut_cache.h"
#include "gpu/async_queue.h"

/* The previous frames' last use of the LUTs: the sky pass (and the multiscatter LUT) sampled them. */
#define LUT_LAST_USE GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED

/* The LUTs recorded on a compute queue of another family than the graphics queue (--async-luts): no fragment stage
 * there, and the LUTs change owner at the end (docs/synchronization.md §10). */
static bool lut_compute_only(const sky_renderer *r)
{
    return r->lut_on_compute_queue && gpu_async_other_family(r->ctx);
}

/* A LUT pass wrote `base`'s LUT; the passes after it sample it: RAW + GENERAL -> SHADER_READ_ONLY (`at`). With the
 * LUTs on another family's compute queue, the in-queue readers are compute shaders only, and the last LUT (the one
 * whose barrier goes into `next`) is instead *released* to the graphics family: async_luts.c records the others'
 * releases and the acquires. `name`: the barrier's, when not `base`.write_to_sample (a second pass's). */
static void lut_written(sky_renderer *r, gpu_barrier_batch *at, gpu_barrier_batch *next, const char *base,
                        const char *resource, VkImage image, const char *written_name)
{
    char name[64];
    if (lut_compute_only(r) && at == next) {
        snprintf(name, sizeof name, "%s.release", base);
        gpu_usage_info to = *gpu_usage_get(GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED);
        to.stage = VK_PIPELINE_STAGE_2_NONE, to.access = VK_ACCESS_2_NONE;   /* ignored in a release */
        gpu_barrier_add_image_qfot(at, name, resource, image, gpu_color_range(0, 1),
                                   *gpu_usage_get(GPU_USAGE_COMPUTE_STORAGE_WRITE), to, r->ctx->compute_family,
                                   r->ctx->queue_family, true);
        return;
    }
    snprintf(name, sizeof name, "%s.write_to_sample", base);
    gpu_barrier_add_image(at, written_name ? written_name : name, resource, image, gpu_color_range(0, 1),
                          GPU_USAGE_COMPUTE_STORAGE_WRITE,
                          lut_compute_only(r) ? GPU_USAGE_COMPUTE_SAMPLED : GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, false);
}

static void record_multiscatter(sky_renderer *r, VkCommandBuffer cmd, bool sky_lit_ground)
{
    uint32_t t = frame_timed_begin(r, cmd, sky_lit_ground ? "multiscatter_lut_sky_ground" : "multiscatter_lut");
    luts_record_multiscatter(&r->luts, cmd, sky_lit_ground);
    frame_timed_end(r, cmd, t);
}

static void record_ground_irradiance(sky_renderer *r, VkCommandBuffer cmd, const char *pass)
{
    uint32_t t = frame_timed_begin(r, cmd, pass);
    luts_record_ground_irradiance(&r->luts, cmd);
    frame_timed_end(r, cmd, t);
}

/* A lit ground with multi-scattering (issue 31): the multiscatter LUT's ground lit by the sky as well as the sun.
 * The sky's light on the ground comes from the ground-irradiance LUT, which samples the multiscatter LUT: so the
 * first multiscatter pass (the ground lit by the sun alone, Hillaire's) feeds a first ground-irradiance pass, whose
 * LUT the second multiscatter pass reads in its ground term, and a second ground-irradiance pass follows from that
 * LUT for the sky pass (the pair the view samples agree). The passes rewrite the two images in place; `b` holds the
 * multiscatter LUT's RAW barrier after the first pass on entry, the second ground-irradiance pass's LUT barrier goes
 * into `next`. */
static void record_sky_lit_ground(sky_renderer *r, VkCommandBuffer cmd, gpu_barrier_batch *b, gpu_barrier_batch *next,
                                  gpu_usage last_use)
{
    sky_luts *l = &r->luts;
    VkImageSubresourceRange one = gpu_color_range(0, 1);
    /* The first ground-irradiance pass: previous frames sampled its LUT (WAR + layout; as the only pass, below). */
    gpu_barrier_add_image(b, "ground_irradiance.to_storage", "ground_irradiance_lut", l->ground_irradiance.image, one,
                          last_use, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
    gpu_barrier_flush(cmd, b);
    record_ground_irradiance(r, cmd, "ground_irradiance_lut_first");

    /* It wrote its LUT; the second multiscatter pass samples it: RAW + GENERAL -> SHADER_READ_ONLY. And that pass
     * rewrites the multiscatter LUT the first ground-irradiance pass sampled: WAR + SHADER_READ_ONLY -> GENERAL (old
     * contents discarded: every texel is written again). */
    *b = gpu_barrier_batch_begin("before multiscatter_lut_sky_ground");
    gpu_barrier_add_image(b, "ground_irradiance.first_to_sample", "ground_irradiance_lut", l->ground_irradiance.image,
                          one, GPU_USAGE_COMPUTE_STORAGE_WRITE, GPU_USAGE_COMPUTE_SAMPLED, false);
    gpu_barrier_add_image(b, "multiscatter.to_storage_again", "multiscatter_lut", l->multiscatter.image, one,
                          GPU_USAGE_COMPUTE_SAMPLED, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
    gpu_barrier_flush(cmd, b);
    record_multiscatter(r, cmd, true);

    /* The second multiscatter pass wrote the LUT; the second ground-irradiance pass and the sky pass sample it: RAW
     * + layout. And that pass rewrites the ground-irradiance LUT the second multiscatter pass sampled: WAR +
     * SHADER_READ_ONLY -> GENERAL (discarded). */
    *b = gpu_barrier_batch_begin("before ground_irradiance_lut");
    lut_written(r, b, next, "multiscatter", "multiscatter_lut", l->multiscatter.image, "multiscatter.again_to_sample");
    gpu_barrier_add_image(b, "ground_irradiance.to_storage_again", "ground_irradiance_lut", l->ground_irradiance.image,
                          one, GPU_USAGE_COMPUTE_SAMPLED, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
    gpu_barrier_flush(cmd, b);
    record_ground_irradiance(r, cmd, "ground_irradiance_lut");
    /* It wrote the LUT; the sky pass and the sky-view LUT sample it: RAW + layout. */
    lut_written(r, next, next, "ground_irradiance", "ground_irradiance_lut", l->ground_irradiance.image, NULL);
}

/* The LUT passes. Their last barrier (the last LUT made readable) goes into `next`, the batch of the point that
 * follows them: back-to-back barriers share one vkCmdPipelineBarrier2 (one call per point, §2 of the guide). */
static void record_luts(sky_renderer *r, VkCommandBuffer cmd, gpu_barrier_batch *next)
{
    sky_luts *l = &r->luts;
    VkImageSubresourceRange one = gpu_color_range(0, 1);
    bool ms = r->variant.multiscatter, ground = r->variant.ground;
    /* On a compute-only queue (--async-luts, another family) no stage but compute exists: the previous frames'
     * fragment reads are ordered by the graphics_done wait of the submission instead (async_luts.c). */
    gpu_usage last_use = lut_compute_only(r) ? GPU_USAGE_COMPUTE_SAMPLED : LUT_LAST_USE;

    /* Transmittance LUT: the previous frames' sky passes sampled it (WAR); to GENERAL for imageStore. */
    gpu_barrier_batch b = gpu_barrier_batch_begin("before transmittance_lut");
    gpu_barrier_add_image(&b, "transmittance.to_storage", "transmittance_lut", l->transmittance.image, one,
                          last_use, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
    gpu_barrier_flush(cmd, &b);
    uint32_t t = frame_timed_begin(r, cmd, "transmittance_lut");
    luts_record_transmittance(l, cmd);
    frame_timed_end(r, cmd, t);

    /* The transmittance compute shader wrote the LUT; the multiscatter compute shader (and later the sky's
     * fragment shader) samples it: RAW + GENERAL -> SHADER_READ_ONLY. Without multi-scattering (readers bind the
     * transmittance LUT) and a lit ground, this is the LUTs' last barrier. */
    gpu_barrier_batch *at = next;
    if (ms || ground) b = gpu_barrier_batch_begin(ms ? "before multiscatter_lut" : "before ground_irradiance_lut"), at = &b;
    lut_written(r, at, next, "transmittance", "transmittance_lut", l->transmittance.image, NULL);
    if (ms) {
        /* The multiscatter LUT was sampled by the previous frames (WAR) and becomes the storage target. */
        gpu_barrier_add_image(&b, "multiscatter.to_storage", "multiscatter_lut", l->multiscatter.image, one,
                              last_use, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
        gpu_barrier_flush(cmd, &b);
        record_multiscatter(r, cmd, false);
        /* The multiscatter compute shader wrote its LUT; the sky pass (and the ground-irradiance LUT) sample it:
         * RAW + layout. (The usage covers compute too, so every frame's first barrier has the same source.) */
        at = next;
        if (ground) b = gpu_barrier_batch_begin("before ground_irradiance_lut"), at = &b;
        lut_written(r, at, next, "multiscatter", "multiscatter_lut", l->multiscatter.image, NULL);
        /* A lit ground: the ground-irradiance LUT, a second multiscatter pass and the LUT again (above). */
        if (ground) record_sky_lit_ground(r, cmd, &b, next, last_use);
        return;
    }
    if (ground) {
        /* The sky's irradiance on the ground (a lit ground only): previous frames sampled it (WAR). */
        gpu_barrier_add_image(&b, "ground_irradiance.to_storage", "ground_irradiance_lut", l->ground_irradiance.image,
                              one, last_use, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
        gpu_barrier_flush(cmd, &b);
        record_ground_irradiance(r, cmd, "ground_irradiance_lut");
        /* It wrote the LUT; the sky pass and the sky-view LUT sample it: RAW + layout. */
        lut_written(r, next, next, "ground_irradiance", "ground_irradiance_lut", l->ground_irradiance.image, NULL);
    }
}

/* The LUTs, when dirty (or forced); their last barrier goes into `next`. */
void frame_record_luts_if_dirty(sky_renderer *r, VkCommandBuffer cmd, bool force, gpu_barrier_batch *next)
{
    /* LUTs the compute queue of another family released (--async-luts): acquired at this point. */
    if (r->lut_acquire_pending && !r->lut_on_compute_queue) frame_add_lut_transfers(r, next, false);
    if (force || sky_renderer_luts_dirty(r)) {
        /* A warm start: the medium's LUTs from the cache on disk (benchmarks that force them compute them; the compute
         * queue of --async-luts computes them, its release barriers being the LUT passes' own). */
        if (!force && !r->lut_on_compute_queue && sky_lut_cache_fetch(r)) frame_record_lut_cache_upload(r, cmd, next);
        else record_luts(r, cmd, next);
        r->lut_hash = sky_atmosphere_lut_hash(&r->atmosphere, r->variant.sun_visibility);
        r->luts_valid = true;
    }
}

void frame_record_luts(sky_renderer *r, VkCommandBuffer cmd, bool force, gpu_barrier_batch *next)
{
    gpu_barrier_batch b = gpu_barrier_batch_begin("after the LUTs");
    frame_record_luts_if_dirty(r, cmd, force, next ? next : &b);
    gpu_barrier_flush(cmd, &b);
}

void frame_record_luts_compute(sky_renderer *r, VkCommandBuffer cmd)
{
    r->lut_on_compute_queue = true;
    r->active_timer = &r->lut_timer;
    gpu_timer_reset(&r->lut_timer, cmd);
    gpu_barrier_batch end = gpu_barrier_batch_begin("end of the LUTs (compute queue)");
    frame_record_luts_if_dirty(r, cmd, true, &end);
    if (gpu_async_other_family(r->ctx)) frame_add_lut_transfers(r, &end, true);
    gpu_barrier_flush(cmd, &end);
    r->lut_on_compute_queue = false;
}

/* The LUT readback's frame (tests). The LUT passes wrote the LUT and made it readable by shaders; the copy reads it:
 * RAW + layout to TRANSFER_SRC. Then the image goes back to the sampled layout for later frames (WAR against the
 * copy) and the copy's writes to the host buffer are made visible to the host after the fence (RAW). */
void frame_record_lut_readback(sky_renderer *r, VkCommandBuffer cmd, const gpu_image *img, const char *name,
                               VkBuffer buffer)
{
    VkImageSubresourceRange one = gpu_color_range(0, 1);
    gpu_barrier_batch b = gpu_barrier_batch_begin("before lut readback");
    gpu_barrier_add_image(&b, "lut_readback.to_copy", name, img->image, one, GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED,
                          GPU_USAGE_TRANSFER_SRC, false);
    gpu_barrier_flush(cmd, &b);
    gpu_label_begin(r->ctx, cmd, "lut_readback");
    frame_copy_to_buffer(cmd, img->image, img->extent, buffer);
    gpu_label_end(r->ctx, cmd);
    b = gpu_barrier_batch_begin("after lut readback");
    gpu_barrier_add_image(&b, "lut_readback.to_sample", name, img->image, one, GPU_USAGE_TRANSFER_SRC,
                          GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, false);
    gpu_barrier_add_buffer(&b, "lut_readback.to_host", "lut_readback", buffer, GPU_USAGE_TRANSFER_DST,
                           GPU_USAGE_HOST_READ);
    gpu_barrier_flush(cmd, &b);
}

/* The library's LUT-only frame (vksky_record, VKSKY_OUTPUT_LUTS_ONLY): the LUTs when their inputs changed, then the
 * sky-view LUT for this view's camera altitude and sun, left readable by compute and fragment shaders for the
 * host's own passes. */
void frame_record_luts_only(sky_renderer *r, VkCommandBuffer cmd, const frame_desc *f)
{
    VkImageSubresourceRange one = gpu_color_range(0, 1);
    r->active_timer = f->timer ? f->timer : &r->timer;
    gpu_timer_reset(r->active_timer, cmd);
    gpu_barrier_batch b = gpu_barrier_batch_begin("before skyview_lut");
    frame_record_luts_if_dirty(r, cmd, f->force_luts, &b);
    /* The host's passes of the previous frame sampled the sky-view LUT (WAR); rewritten whole: UNDEFINED -> GENERAL. */
    gpu_barrier_add_image(&b, "skyview.to_storage", "skyview_lut", r->luts.skyview.image, one,
                          GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
    gpu_barrier_flush(cmd, &b);
    SkyPush sv = sky_view_skyview_push(f->view);
    uint32_t t = frame_timed_begin(r, cmd, "skyview_lut");
    luts_record_skyview(&r->luts, cmd, &sv);
    frame_timed_end(r, cmd, t);
    /* The LUT pass wrote it; the host's compute or fragment shaders sample it: RAW + layout. */
    b = gpu_barrier_batch_begin("after skyview_lut");
    gpu_barrier_add_image(&b, "skyview.write_to_host", "skyview_lut", r->luts.skyview.image, one,
                          GPU_USAGE_COMPUTE_STORAGE_WRITE, GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, false);
    gpu_barrier_flush(cmd, &b);
}

/* The LUTs of this variant in the order their passes write them; the last one's barrier closes the LUT passes. */
static int lut_list(const sky_renderer *r, const gpu_image *img[3], const char *base[3])
{
    int n = 0;
    img[n] = &r->luts.transmittance, base[n++] = "transmittance";
    if (r->variant.multiscatter) img[n] = &r->luts.multiscatter, base[n++] = "multiscatter";
    if (r->variant.ground) img[n] = &r->luts.ground_irradiance, base[n++] = "ground_irradiance";
    return n;
}

/* The ownership transfer's halves (another queue family only). The last LUT leaves its pass in GENERAL and is
 * released with its own GENERAL -> SHADER_READ_ONLY transition (lut_written, above); the others were already made
 * SHADER_READ_ONLY for the compute shaders after them and keep it. Release: source the compute shader stage, no
 * destination (ignored: the acquire is the other queue's). Acquire: the same layouts, families and range; no source
 * (the semaphore wait orders it after the release), the destination the sky's samplers. */
void frame_add_lut_transfers(sky_renderer *r, gpu_barrier_batch *b, bool release)
{
    const gpu_image *img[3];
    const char *base[3];
    int n = lut_list(r, img, base);
    gpu_usage_info none = {"none", VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    gpu_usage_info sampled = *gpu_usage_get(GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED);
    for (int i = 0; i < n; ++i) {
        char name[64], resource[64];
        bool last = i == n - 1;
        snprintf(resource, sizeof resource, "%s_lut", base[i]);
        if (release) {
            if (last) continue;   /* lut_written released it */
            gpu_usage_info from = *gpu_usage_get(GPU_USAGE_COMPUTE_SAMPLED);
            snprintf(name, sizeof name, "%s.release", base[i]);
            gpu_barrier_add_image_qfot(b, name, resource, img[i]->image, gpu_color_range(0, 1), from, none,
                                       r->ctx->compute_family, r->ctx->queue_family, true);
        } else {
            gpu_usage_info from = none;
            if (last) from.layout = VK_IMAGE_LAYOUT_GENERAL;
            snprintf(name, sizeof name, "%s.acquire", base[i]);
            gpu_barrier_add_image_qfot(b, name, resource, img[i]->image, gpu_color_range(0, 1), from, sampled,
                                       r->ctx->compute_family, r->ctx->queue_family, false);
        }
    }
    if (!release) r->lut_acquire_pending = false;
}

/* --- The LUT cache (sky/lut_cache.h, issue 27): the medium's LUTs uploaded from a file instead of computed, and
 * read back once after they were computed so that the file can be written. --- */

/* One barrier per cached LUT image, all of one name and one usage change (the cache's copies move them together). */
static void lut_cache_barriers(gpu_barrier_batch *b, const char *name, const gpu_image *const imgs[3],
                               const char *const names[3], int n, gpu_usage from, gpu_usage to, bool discard)
{
    for (int i = 0; i < n; ++i)
        gpu_barrier_add_image(b, name, names[i], imgs[i]->image, gpu_color_range(0, 1), from, to, discard);
}

/* In place of the LUT passes: the previous frames' shaders sampled the LUTs (WAR); the copies from r->lut_staging
 * overwrite them whole: UNDEFINED -> TRANSFER_DST. Then the copies wrote them; the sky pass (and the sky-view LUT)
 * sample them: RAW + layout, into `next` like the LUT passes' last barrier. The staging buffer's host writes need
 * no barrier: a submission makes the host writes made before it visible to the device. */
void frame_record_lut_cache_upload(sky_renderer *r, VkCommandBuffer cmd, gpu_barrier_batch *next)
{
    const gpu_image *imgs[3];
    const char *names[3];
    int n = sky_lut_cache_images(r, imgs, names);
    gpu_barrier_batch b = gpu_barrier_batch_begin("before lut_cache_upload");
    lut_cache_barriers(&b, "lut_cache.to_transfer_dst", imgs, names, n, LUT_LAST_USE, GPU_USAGE_TRANSFER_DST, true);
    gpu_barrier_flush(cmd, &b);
    uint32_t t = frame_timed_begin(r, cmd, "lut_cache_upload");
    VkDeviceSize offset = 0;
    for (int i = 0; i < n; ++i) {
        VkBufferImageCopy region = sky_lut_cache_region(imgs[i], &offset);
        vkCmdCopyBufferToImage(cmd, r->lut_staging.buffer, imgs[i]->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                               &region);
    }
    frame_timed_end(r, cmd, t);
    lut_cache_barriers(next, "lut_cache.upload_to_sample", imgs, names, n, GPU_USAGE_TRANSFER_DST, LUT_LAST_USE, false);
}

/* A frame of its own after the frame that computed the LUTs (a miss): they were made readable by shaders; the copies
 * read them: layout to TRANSFER_SRC. Then back to sampled for later frames (WAR against the copies), and the copies'
 * writes made visible to the host after the fence (RAW), as the tests' LUT readback does. */
void frame_record_lut_cache_readback(sky_renderer *r, VkCommandBuffer cmd, VkBuffer buffer)
{
    const gpu_image *imgs[3];
    const char *names[3];
    int n = sky_lut_cache_images(r, imgs, names);
    gpu_barrier_batch b = gpu_barrier_batch_begin("before lut_cache_readback");
    lut_cache_barriers(&b, "lut_cache.to_transfer_src", imgs, names, n, LUT_LAST_USE, GPU_USAGE_TRANSFER_SRC, false);
    gpu_barrier_flush(cmd, &b);
    gpu_label_begin(r->ctx, cmd, "lut_cache_readback");
    VkDeviceSize offset = 0;
    for (int i = 0; i < n; ++i) {
        VkBufferImageCopy region = sky_lut_cache_region(imgs[i], &offset);
        vkCmdCopyImageToBuffer(cmd, imgs[i]->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &region);
    }
    gpu_label_end(r->ctx, cmd);
    b = gpu_barrier_batch_begin("after lut_cache_readback");
    lut_cache_barriers(&b, "lut_cache.readback_to_sample", imgs, names, n, GPU_USAGE_TRANSFER_SRC, LUT_LAST_USE,
                       false);
    gpu_barrier_add_buffer(&b, "lut_cache.readback_to_host", "lut_cache_readback", buffer, GPU_USAGE_TRANSFER_DST,
                           GPU_USAGE_HOST_READ);
    gpu_barrier_flush(cmd, &b);
}
