/* Submission and readback over a renderer (see sky/submit.h). */
#include "sky/submit.h"
#include "sky/lut_cache.h"
#include <string.h>
#include <time.h>

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

double sky_renderer_render(sky_renderer *r, const frame_desc *f)
{
    if (r->ctx->compute_queue) return sky_renderer_render_async(r, f);
    VkCommandBuffer cmd = gpu_begin_commands(r->ctx);
    frame_record(r, cmd, f);
    double t0 = now_ms();
    gpu_submit_and_wait(r->ctx, cmd);
    double wall = now_ms() - t0;
    if (r->desc.readback) {
        gpu_buffer_invalidate(r->ctx, &r->readback_linear);
        gpu_buffer_invalidate(r->ctx, &r->readback_display);
    }
    if (r->lut_cache == SKY_LUT_CACHE_MISS) sky_renderer_store_luts(r);
    return wall;
}

void sky_renderer_store_luts(sky_renderer *r)
{
    /* Only LUTs that hold the current medium (the key is made from it). */
    if (r->lut_cache != SKY_LUT_CACHE_MISS || !r->luts_valid || sky_renderer_luts_dirty(r)) return;
    const gpu_context *ctx = r->ctx;
    size_t size = sky_lut_cache_size(r);
    gpu_buffer buf;
    gpu_buffer_create(ctx, &buf, "lut cache readback", size, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    VkCommandBuffer cmd = gpu_begin_commands(ctx);
    frame_record_lut_cache_readback(r, cmd, buf.buffer);
    gpu_submit_and_wait(ctx, cmd);
    gpu_buffer_invalidate(ctx, &buf);
    sky_lut_cache_put(r, buf.mapped, size);
    gpu_buffer_destroy(ctx, &buf);
}

VkExtent2D sky_renderer_lut_extent(const sky_renderer *r, int which)
{
    return which == 0 ? r->luts.transmittance.extent : r->luts.multiscatter.extent;
}

VkFormat sky_renderer_read_lut(sky_renderer *r, int which, void *texels_out)
{
    const gpu_context *ctx = r->ctx;
    const gpu_image *img = which == 0 ? &r->luts.transmittance : &r->luts.multiscatter;
    if (!img->image) return VK_FORMAT_UNDEFINED;   /* no multi-scattering LUT in this variant */
    const char *name = which == 0 ? "transmittance_lut" : "multiscatter_lut";
    size_t count = (size_t)img->extent.width * img->extent.height * 4;
    bool f32 = img->format == VK_FORMAT_R32G32B32A32_SFLOAT;
    gpu_buffer buf;
    gpu_buffer_create(ctx, &buf, "lut readback", count * (f32 ? sizeof(float) : sizeof(uint16_t)),
                      VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    VkCommandBuffer cmd = gpu_begin_commands(ctx);
    frame_record_lut_readback(r, cmd, img, name, buf.buffer);
    gpu_submit_and_wait(ctx, cmd);
    gpu_buffer_invalidate(ctx, &buf);
    /* As stored: the half -> float conversion is the caller's (io/ has it; sky/ may not include io/). */
    memcpy(texels_out, buf.mapped, count * (f32 ? sizeof(float) : sizeof(uint16_t)));
    gpu_buffer_destroy(ctx, &buf);
    return img->format;
}
