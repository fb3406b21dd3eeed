/* The renderer's resources and their lifetime (see sky/renderer.h). */
#include "sky/renderer.h"
#include <math.h>
#include "sky/shaders.h"
#include <stddef.h>
#include <string.h>
#include <time.h>

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

/* Everything whose size follows the output: HDR target, display/composite images, readback buffers, the bloom
 * chain and the tone map's descriptors. Their descriptor sets come from their own pool, reset on resize. */
static void create_sized(sky_renderer *r)
{
    const gpu_context *ctx = r->ctx;
    const sky_renderer_desc *desc = &r->desc;
    pass_shared sized = r->shared;
    sized.pool = r->size_pool;
    /* Colour attachment (fragment sky), storage (compute sky), sampled (bloom, tone map). */
    VkImageUsageFlags target_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                                     VK_IMAGE_USAGE_SAMPLED_BIT;
    /* Render scale buys time on large images; on small ones it saves nothing worth having and a few sky texels
     * cannot hold the view (a 7x3 frame at half size: 4x2 texels, the centre pixel between a sky and a ground
     * row). So where the scale would leave the shorter axis under MIN_SCALED_SKY texels, the sky is rendered at
     * the output's size. */
    enum { MIN_SCALED_SKY = 32 };
    double scale = desc->render_scale > 0.0 ? desc->render_scale : 1.0;
    double shorter = desc->width < desc->height ? desc->width : desc->height;
    if (shorter * scale < MIN_SCALED_SKY) scale = 1.0;
    uint32_t hw = (uint32_t)(desc->width * scale + 0.5), hh = (uint32_t)(desc->height * scale + 0.5);
    gpu_image_create(ctx, &r->hdr, "hdr", HDR_FORMAT, hw ? hw : 1, hh ? hh : 1, 1, target_usage);
    sky_pass_set_target(&r->sky, &r->shared, &r->hdr);
    /* The compute tone map writes the display image as a storage image: 8-bit UNORM (storage images cannot be
     * sRGB), the shader encodes sRGB, the bytes are the same. */
    bool compute_tonemap = r->post_kind == POST_PASS_COMPUTE && !desc->external_display;
    VkImageUsageFlags out_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                  (compute_tonemap ? VK_IMAGE_USAGE_STORAGE_BIT : 0);
    if (!desc->external_display)
        gpu_image_create(ctx, &r->display, "display", compute_tonemap ? VK_FORMAT_R8G8B8A8_UNORM : desc->display_format,
                         desc->width, desc->height, 1, out_usage);
    if (desc->readback) {
        /* Sampled too: a spectral group's composite is added into the GPU's sum (sky/spectral_sum.h). */
        gpu_image_create(ctx, &r->composite, "composite", HDR_FORMAT, desc->width, desc->height, 1,
                         out_usage | VK_IMAGE_USAGE_SAMPLED_BIT);
        r->display_last = r->composite_last = GPU_USAGE_TRANSFER_SRC;   /* as after a readback (first frame: discarded) */
        VkDeviceSize pixels = (VkDeviceSize)desc->width * desc->height;
        gpu_buffer_create(ctx, &r->readback_linear, "readback linear", pixels * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        gpu_buffer_create(ctx, &r->readback_display, "readback display", pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    }
    /* Before the tone maps: their sets name the meter's buffer (every frame's, read only when the view meters). */
    meter_create(&r->meter, &r->shared, r->size_pool, &r->hdr);
    if (desc->bloom)
        bloom_create(&r->bloom, &sized, &r->hdr, desc->bloom_mips ? desc->bloom_mips : 5, desc->bloom_quarter ? 1 : 0);
    tonemap_create(&r->tonemap, &sized, r->hdr.view, desc->bloom ? r->bloom.mips.mip_views[0] : r->hdr.view,
                   desc->display_format, desc->readback);
    meter_write_descriptor(ctx, r->tonemap.set, &r->meter);
    if (r->post_kind == POST_PASS_COMPUTE)
        post_compute_create(&r->post, &r->shared, &r->hdr, desc->bloom ? &r->bloom : NULL,
                            compute_tonemap ? r->display.view : VK_NULL_HANDLE,
                            compute_tonemap && desc->readback ? r->composite.view : VK_NULL_HANDLE,
                            desc->external_display && desc->host_storage_tonemap);
    if (r->post_kind == POST_PASS_COMPUTE && r->post.tonemap) meter_write_descriptor(ctx, r->post.tonemap_set, &r->meter);
    for (uint32_t i = 0; r->post_kind == POST_PASS_COMPUTE && r->post.host_tonemap && i < POST_HOST_SETS; ++i)
        meter_write_descriptor(ctx, r->post.host_sets[i], &r->meter);
    if (r->post_kind == POST_PASS_COMPUTE && desc->bloom && desc->bloom_downsample == BLOOM_DOWN_SINGLE_PASS &&
        !r->post.spd_pipeline)
        gpu_report(r->ctx, 1, "--bloom-downsample single-pass needs the device feature vulkanMemoryModelDeviceScope, "
                              "which this device lacks: the per-level downsample runs instead");
}

static void destroy_sized(sky_renderer *r)
{
    const gpu_context *ctx = r->ctx;
    if (r->post_kind == POST_PASS_COMPUTE) post_compute_destroy(&r->post, &r->shared);
    tonemap_destroy(&r->tonemap, &r->shared);
    meter_destroy(&r->meter, &r->shared);
    if (r->desc.bloom) bloom_destroy(&r->bloom, &r->shared);
    gpu_buffer_destroy(ctx, &r->readback_linear);
    gpu_buffer_destroy(ctx, &r->readback_display);
    gpu_image_destroy(ctx, &r->composite);
    gpu_image_destroy(ctx, &r->display);
    gpu_image_destroy(ctx, &r->hdr);
    VK_CHECK(vkResetDescriptorPool(ctx->device, r->size_pool, 0));
}

void sky_renderer_resize(sky_renderer *r, uint32_t width, uint32_t height)
{
    if (width == r->desc.width && height == r->desc.height) return;
    vkDeviceWaitIdle(r->ctx->device);
    destroy_sized(r);
    r->desc.width = width;
    r->desc.height = height;
    create_sized(r);
}

static void upload_atmosphere(sky_renderer *r);

/* The pipelines that carry the scene's variant (specialization constants): LUT passes and sky pass. */
static void build_variant(sky_renderer *r)
{
    r->variant_builds++;
    pass_shared *s = &r->shared;
    r->variant = sky_variant_of(&r->medium, &r->features);
    const sky_variant *v = &r->variant;
    const struct { uint32_t id; size_t offset, size; } map[VKSKY_SPEC_COUNT] = {
        {VKSKY_SPEC_RAYLEIGH, offsetof(sky_variant, rayleigh), sizeof v->rayleigh},
        {VKSKY_SPEC_MIE, offsetof(sky_variant, mie), sizeof v->mie},
        {VKSKY_SPEC_OZONE, offsetof(sky_variant, ozone), sizeof v->ozone},
        {VKSKY_SPEC_MULTISCATTER, offsetof(sky_variant, multiscatter), sizeof v->multiscatter},
        {VKSKY_SPEC_SUN_DISC, offsetof(sky_variant, sun_disc), sizeof v->sun_disc},
        {VKSKY_SPEC_GROUND, offsetof(sky_variant, ground), sizeof v->ground},
        {VKSKY_SPEC_MIE_PHASE, offsetof(sky_variant, mie_phase), sizeof v->mie_phase},
        {VKSKY_SPEC_RAYLEIGH_PROFILE, offsetof(sky_variant, profile[0]), sizeof v->profile[0]},
        {VKSKY_SPEC_MIE_PROFILE, offsetof(sky_variant, profile[1]), sizeof v->profile[1]},
        {VKSKY_SPEC_OZONE_PROFILE, offsetof(sky_variant, profile[2]), sizeof v->profile[2]},
        {VKSKY_SPEC_EXTRA_SPECIES, offsetof(sky_variant, extra_species), sizeof v->extra_species},
        {VKSKY_SPEC_EXTRA0_PROFILE, offsetof(sky_variant, extra_profile[0]), sizeof v->extra_profile[0]},
        {VKSKY_SPEC_EXTRA1_PROFILE, offsetof(sky_variant, extra_profile[1]), sizeof v->extra_profile[1]},
        {VKSKY_SPEC_SUN_VISIBILITY, offsetof(sky_variant, sun_visibility), sizeof v->sun_visibility}};
    for (int i = 0; i < VKSKY_SPEC_COUNT; ++i)
        r->spec_entries[i] = (VkSpecializationMapEntry){map[i].id, (uint32_t)map[i].offset, map[i].size};
    r->spec = (VkSpecializationInfo){.mapEntryCount = VKSKY_SPEC_COUNT, .pMapEntries = r->spec_entries, .dataSize = sizeof *v, .pData = v};
    s->spec = &r->spec;
    luts_create(&r->luts, s, &r->desc.lut, v->multiscatter, v->ground);
    sky_pass_create(&r->sky, s, &r->luts);
    r->luts_valid = false;
}

static void rebuild_variant_if_changed(sky_renderer *r)
{
    r->features.spectral4 = r->desc.spectral4;   /* the renderer's build, whatever the caller's features say */
    sky_variant want = sky_variant_of(&r->medium, &r->features);
    if (!memcmp(&want, &r->variant, sizeof want)) return;
    double start = now_ms();
    vkDeviceWaitIdle(r->ctx->device);
    sky_pass_destroy(&r->sky, &r->shared);
    luts_destroy(&r->luts, &r->shared);
    VK_CHECK(vkResetDescriptorPool(r->ctx->device, r->shared.pool, 0));
    build_variant(r);
    sky_pass_set_target(&r->sky, &r->shared, &r->hdr);
    r->pipelines_ms += now_ms() - start;
}

void sky_renderer_create(sky_renderer *r, gpu_context *ctx, const sky_renderer_desc *desc)
{
    memset(r, 0, sizeof *r);
    double start = now_ms();
    r->ctx = ctx;
    r->desc = *desc;
    if (r->desc.lut.transmittance_width == 0) r->desc.lut = sky_lut_quality_default();
    r->post_kind = post_pass_resolve(desc->post_pass, ctx);
    pass_shared *s = &r->shared;
    s->ctx = ctx;
    s->spectral4 = desc->spectral4;
    /* (+1 set of 1 uniform, 3 samplers' worth and 1 storage image: the second multiscatter pass of a lit ground) */
    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 9},
                                    {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 36},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 9},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4}};   /* the meter's, its and the tone map's sets */
    VkDescriptorPoolCreateInfo pinfo = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 32,
                                        .poolSizeCount = 4, .pPoolSizes = sizes};
    VK_CHECK(vkCreateDescriptorPool(ctx->device, &pinfo, gpu_allocator(ctx->device), &s->pool));
    s->linear_clamp = gpu_linear_clamp_sampler(ctx, "linear clamp");
    gpu_buffer_create(ctx, &s->atmosphere_ubo, "atmosphere uniforms", sizeof(AtmosphereParams),
                      VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    s->fullscreen_vs = gpu_shader_module(ctx, spirv_fullscreen_vert.code, spirv_fullscreen_vert.size, "fullscreen.vert");

    VkDescriptorPoolCreateInfo size_info = pinfo;
    VK_CHECK(vkCreateDescriptorPool(ctx->device, &size_info, gpu_allocator(ctx->device), &r->size_pool));
    model_atmosphere_earth(&r->medium);
    r->features = sky_features_default();
    r->sun_angular_radius = 0.5 * 0.53 * 3.14159265358979323846 / 180.0;
    if (desc->atmosphere) r->medium = *desc->atmosphere, r->sun_angular_radius = desc->sun_angular_radius_rad;
    if (desc->features) r->features = *desc->features;
    r->features.spectral4 = desc->spectral4;
    r->desc.atmosphere = NULL, r->desc.features = NULL;   /* the caller's, valid only during this call */
    build_variant(r);
    create_sized(r);
    gpu_timer_create(ctx, &r->timer);
    if (ctx->compute_queue) gpu_timer_create(ctx, &r->lut_timer);
    if (desc->atmosphere || desc->features) upload_atmosphere(r);
    r->pipelines_ms = now_ms() - start;
}

void sky_renderer_destroy(sky_renderer *r)
{
    if (!r->ctx) return;
    const gpu_context *ctx = r->ctx;
    pass_shared *s = &r->shared;
    vkDeviceWaitIdle(ctx->device);
    gpu_timer_destroy(ctx, &r->timer);
    gpu_timer_destroy(ctx, &r->lut_timer);
    if (r->size_pool) destroy_sized(r);   /* absent when creation failed before it (the library's trap) */
    vkDestroyDescriptorPool(ctx->device, r->size_pool, gpu_allocator(ctx->device));
    sky_pass_destroy(&r->sky, s);
    luts_destroy(&r->luts, s);
    gpu_buffer_destroy(ctx, &r->lut_staging);
    vkDestroyShaderModule(ctx->device, s->fullscreen_vs, gpu_allocator(ctx->device));
    gpu_buffer_destroy(ctx, &s->atmosphere_ubo);
    vkDestroySampler(ctx->device, s->linear_clamp, gpu_allocator(ctx->device));
    vkDestroyDescriptorPool(ctx->device, s->pool, gpu_allocator(ctx->device));
    memset(r, 0, sizeof *r);
}

static void upload_atmosphere(sky_renderer *r)
{
    rebuild_variant_if_changed(r);
    sky_atmosphere_pack(&r->medium, r->sun_angular_radius, r->desc.lut, &r->features, &r->atmosphere);
    /* Host write before the submit that reads it: vkQueueSubmit makes it visible (no barrier needed); the
     * caller guarantees no frame in flight still reads the old values. */
    memcpy(r->shared.atmosphere_ubo.mapped, &r->atmosphere, sizeof r->atmosphere);
    if (!r->shared.atmosphere_ubo.coherent) {
        VkMappedMemoryRange range = {.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE,
                                     .memory = r->shared.atmosphere_ubo.memory, .size = VK_WHOLE_SIZE};
        VK_CHECK(vkFlushMappedMemoryRanges(r->ctx->device, 1, &range));
    }
}

/* The medium and the features together: the variant is a function of both, so setting them one at a time would
 * build the pipelines for a mix of the old and the new scene first. */
void sky_renderer_set_scene(sky_renderer *r, const model_atmosphere *a, double sun_angular_radius_rad,
                            const sky_features *f)
{
    r->medium = *a;
    r->sun_angular_radius = sun_angular_radius_rad;
    r->features = *f;
    upload_atmosphere(r);
}

void sky_renderer_set_atmosphere(sky_renderer *r, const model_atmosphere *a, double sun_angular_radius_rad)
{
    sky_renderer_set_scene(r, a, sun_angular_radius_rad, &r->features);
}

void sky_renderer_set_features(sky_renderer *r, const sky_features *f)
{
    sky_renderer_set_scene(r, &r->medium, r->sun_angular_radius, f);
}

bool sky_renderer_luts_dirty(const sky_renderer *r)
{
    return !r->luts_valid || r->lut_hash != sky_atmosphere_lut_hash(&r->atmosphere, r->variant.sun_visibility);
}
