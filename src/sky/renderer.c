#include "sky/renderer.h"
#include "sky/shaders.h"
#include "io/image_io.h"
#include <math.h>
#include <stddef.h>
#include <string.h>
#include <time.h>

static const double DEG = 3.14159265358979323846 / 180.0;

sky_view sky_view_default(void)
{
    return (sky_view){
        .altitude_km = 0.001, .yaw_deg = 0.0, .pitch_deg = 10.0, .fov_deg = 75.0,
        .sun_azimuth_deg = 0.0, .sun_elevation_deg = 20.0, .steps = 32, .max_steps = 0, .steps_ramp_km = 100.0,
        .sample_offset = 0.5, .step_distribution = 2.0, .mode = SKY_CHOICE_MARCH, .pass_kind = SKY_PASS_AUTO, .skyview_steps = 30,
        .exposure_ev = 0.0, .tonemap = VKSKY_TONEMAP_ACES, .bloom = true,
        .bloom_strength = 0.04, .bloom_threshold = 1.0};
}

static void dir_from_angles(double az_deg, double el_deg, double out[3])
{
    double az = az_deg * DEG, el = el_deg * DEG;
    out[0] = cos(el) * cos(az);
    out[1] = sin(el);
    out[2] = cos(el) * sin(az);
}

SkyPush sky_view_push(const sky_view *v, uint32_t width, uint32_t height)
{
    /* The ray matrix: camera basis scaled by tan(fov/2) and the aspect ratio, built in double. */
    double f[3], right[3], up[3];
    dir_from_angles(v->yaw_deg, v->pitch_deg, f);
    if (fabs(v->pitch_deg) >= 90.0 - 1e-9) {
        dir_from_angles(v->yaw_deg + 90.0, 0.0, right);
    } else {
        /* right = normalize(cross(f, +Y)) */
        double rx = -f[2], rz = f[0], n = sqrt(rx * rx + rz * rz);
        right[0] = rx / n, right[1] = 0.0, right[2] = rz / n;
    }
    /* up = cross(right, f) */
    up[0] = right[1] * f[2] - right[2] * f[1];
    up[1] = right[2] * f[0] - right[0] * f[2];
    up[2] = right[0] * f[1] - right[1] * f[0];
    double ty = tan(0.5 * v->fov_deg * DEG), tx = ty * (double)width / (double)height;
    double sun[3];
    dir_from_angles(v->sun_azimuth_deg, v->sun_elevation_deg, sun);
    int max_steps = v->max_steps > v->steps ? v->max_steps : v->steps;
    return (SkyPush){
        .forward = {(float)f[0], (float)f[1], (float)f[2], (float)v->altitude_km},
        .right = {(float)(right[0] * tx), (float)(right[1] * tx), (float)(right[2] * tx), 1.0f / (float)width},
        .up = {(float)(up[0] * ty), (float)(up[1] * ty), (float)(up[2] * ty), 1.0f / (float)height},
        .sun_dir = {(float)sun[0], (float)sun[1], (float)sun[2], (float)v->step_distribution},
        .march = {(float)v->steps, (float)max_steps, (float)v->sample_offset, (float)v->steps_ramp_km},
    };
}

SkyPush sky_view_skyview_push(const sky_view *v)
{
    SkyPush p = sky_view_push(v, 1, 1);
    p.march = (vksky_vec4){(float)v->skyview_steps, (float)v->skyview_steps, (float)v->sample_offset,
                           (float)v->steps_ramp_km};
    return p;
}

sky_pass_kind sky_renderer_pass_kind(const sky_renderer *r, const sky_view *v)
{
    if (v->pass_kind != SKY_PASS_AUTO) return v->pass_kind;
    return r->ctx->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? SKY_PASS_FRAGMENT : SKY_PASS_COMPUTE;
}

sky_mode sky_view_resolve_mode(const sky_view *v, const sky_renderer *r)
{
    if (v->mode == SKY_CHOICE_MARCH) return SKY_MODE_MARCH;
    if (v->mode == SKY_CHOICE_FILL) return SKY_MODE_FILL;
    bool inside = v->altitude_km < r->atmosphere.radii.z;
    if (v->mode == SKY_CHOICE_SKYVIEW) return inside ? SKY_MODE_SKYVIEW : SKY_MODE_MARCH;
    return inside ? SKY_MODE_SKYVIEW : SKY_MODE_MARCH;
}

TonemapPush sky_view_tonemap_push(const sky_view *v, bool encode_srgb_in_shader)
{
    return (TonemapPush){.params = {(float)exp2(v->exposure_ev), (float)v->tonemap,
                                    v->bloom ? (float)v->bloom_strength : 0.0f, encode_srgb_in_shader ? 1.0f : 0.0f}};
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
    double scale = desc->render_scale > 0.0 ? desc->render_scale : 1.0;
    uint32_t hw = (uint32_t)(desc->width * scale + 0.5), hh = (uint32_t)(desc->height * scale + 0.5);
    gpu_image_create(ctx, &r->hdr, "hdr", HDR_FORMAT, hw ? hw : 1, hh ? hh : 1, 1, target_usage);
    sky_pass_set_target(&r->sky, &r->shared, &r->hdr);
    if (!desc->external_display)
        gpu_image_create(ctx, &r->display, "display", desc->display_format, desc->width, desc->height, 1,
                         VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    if (desc->readback) {
        gpu_image_create(ctx, &r->composite, "composite", HDR_FORMAT, desc->width, desc->height, 1,
                         VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        VkDeviceSize pixels = (VkDeviceSize)desc->width * desc->height;
        gpu_buffer_create(ctx, &r->readback_linear, "readback linear", pixels * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        gpu_buffer_create(ctx, &r->readback_display, "readback display", pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    }
    if (desc->bloom) bloom_create(&r->bloom, &sized, &r->hdr, desc->bloom_mips ? desc->bloom_mips : 5);
    tonemap_create(&r->tonemap, &sized, r->hdr.view, desc->bloom ? r->bloom.mips.mip_views[0] : r->hdr.view,
                   desc->display_format, desc->readback);
}

static void destroy_sized(sky_renderer *r)
{
    const gpu_context *ctx = r->ctx;
    tonemap_destroy(&r->tonemap, &r->shared);
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

/* The pipelines that carry the scene's variant (specialization constants): LUT passes and sky pass. */
static void build_variant(sky_renderer *r)
{
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
    sky_variant want = sky_variant_of(&r->medium, &r->features);
    if (!memcmp(&want, &r->variant, sizeof want)) return;
    vkDeviceWaitIdle(r->ctx->device);
    sky_pass_destroy(&r->sky, &r->shared);
    luts_destroy(&r->luts, &r->shared);
    VK_CHECK(vkResetDescriptorPool(r->ctx->device, r->shared.pool, 0));
    build_variant(r);
    sky_pass_set_target(&r->sky, &r->shared, &r->hdr);
}

void sky_renderer_create(sky_renderer *r, gpu_context *ctx, const sky_renderer_desc *desc)
{
    memset(r, 0, sizeof *r);
    r->ctx = ctx;
    r->desc = *desc;
    if (r->desc.lut.transmittance_width == 0) r->desc.lut = sky_lut_quality_default();
    pass_shared *s = &r->shared;
    s->ctx = ctx;
    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 8},
                                    {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 32},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 8}};
    VkDescriptorPoolCreateInfo pinfo = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 32,
                                        .poolSizeCount = 3, .pPoolSizes = sizes};
    VK_CHECK(vkCreateDescriptorPool(ctx->device, &pinfo, NULL, &s->pool));
    s->linear_clamp = gpu_linear_clamp_sampler(ctx, "linear clamp");
    gpu_buffer_create(ctx, &s->atmosphere_ubo, "atmosphere uniforms", sizeof(AtmosphereParams),
                      VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    s->fullscreen_vs = gpu_shader_module(ctx, spirv_fullscreen_vert.code, spirv_fullscreen_vert.size, "fullscreen.vert");

    VkDescriptorPoolCreateInfo size_info = pinfo;
    VK_CHECK(vkCreateDescriptorPool(ctx->device, &size_info, NULL, &r->size_pool));
    model_atmosphere_earth(&r->medium);
    r->features = sky_features_default();
    r->sun_angular_radius = 0.5 * 0.53 * 3.14159265358979323846 / 180.0;
    build_variant(r);
    create_sized(r);
    gpu_timer_create(ctx, &r->timer);
}

void sky_renderer_destroy(sky_renderer *r)
{
    if (!r->ctx) return;
    const gpu_context *ctx = r->ctx;
    pass_shared *s = &r->shared;
    vkDeviceWaitIdle(ctx->device);
    gpu_timer_destroy(ctx, &r->timer);
    destroy_sized(r);
    vkDestroyDescriptorPool(ctx->device, r->size_pool, NULL);
    sky_pass_destroy(&r->sky, s);
    luts_destroy(&r->luts, s);
    vkDestroyShaderModule(ctx->device, s->fullscreen_vs, NULL);
    gpu_buffer_destroy(ctx, &s->atmosphere_ubo);
    vkDestroySampler(ctx->device, s->linear_clamp, NULL);
    vkDestroyDescriptorPool(ctx->device, s->pool, NULL);
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

void sky_renderer_set_atmosphere(sky_renderer *r, const model_atmosphere *a, double sun_angular_radius_rad)
{
    r->medium = *a;
    r->sun_angular_radius = sun_angular_radius_rad;
    upload_atmosphere(r);
}

void sky_renderer_set_features(sky_renderer *r, const sky_features *f)
{
    r->features = *f;
    upload_atmosphere(r);
}

bool sky_renderer_luts_dirty(const sky_renderer *r)
{
    return !r->luts_valid || r->lut_hash != sky_atmosphere_lut_hash(&r->atmosphere, r->variant.sun_visibility);
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

double sky_renderer_render(sky_renderer *r, const frame_desc *f)
{
    VkCommandBuffer cmd = gpu_begin_commands(r->ctx);
    frame_record(r, cmd, f);
    double t0 = now_ms();
    gpu_submit_and_wait(r->ctx, cmd);
    double wall = now_ms() - t0;
    if (r->desc.readback) {
        gpu_buffer_invalidate(r->ctx, &r->readback_linear);
        gpu_buffer_invalidate(r->ctx, &r->readback_display);
    }
    return wall;
}

VkExtent2D sky_renderer_lut_extent(const sky_renderer *r, int which)
{
    return which == 0 ? r->luts.transmittance.extent : r->luts.multiscatter.extent;
}

void sky_renderer_read_lut(sky_renderer *r, int which, float *rgba_out)
{
    const gpu_context *ctx = r->ctx;
    const gpu_image *img = which == 0 ? &r->luts.transmittance : &r->luts.multiscatter;
    if (!img->image) return;   /* no multi-scattering LUT in this variant */
    const char *name = which == 0 ? "transmittance_lut" : "multiscatter_lut";
    size_t count = (size_t)img->extent.width * img->extent.height * 4;
    bool f32 = img->format == VK_FORMAT_R32G32B32A32_SFLOAT;
    gpu_buffer buf;
    gpu_buffer_create(ctx, &buf, "lut readback", count * (f32 ? sizeof(float) : sizeof(uint16_t)),
                      VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    VkCommandBuffer cmd = gpu_begin_commands(ctx);
    /* The LUT passes wrote the LUT and made it readable by shaders; the copy reads it: to TRANSFER_SRC. */
    gpu_barrier_batch b = gpu_barrier_batch_begin("lut readback");
    gpu_barrier_add_image(&b, "lut_readback.to_copy", name, img->image, gpu_color_range(0, 1),
                          GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, GPU_USAGE_TRANSFER_SRC, false);
    gpu_barrier_flush(cmd, &b);
    VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                .imageExtent = {img->extent.width, img->extent.height, 1}};
    vkCmdCopyImageToBuffer(cmd, img->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buf.buffer, 1, &region);
    /* Back to the sampled layout for later frames (WAR against the copy); the buffer to the host (RAW). */
    b = gpu_barrier_batch_begin("lut readback");
    gpu_barrier_add_image(&b, "lut_readback.to_sample", name, img->image, gpu_color_range(0, 1),
                          GPU_USAGE_TRANSFER_SRC, GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, false);
    gpu_barrier_add_buffer(&b, "lut_readback.to_host", "lut readback", buf.buffer, GPU_USAGE_TRANSFER_DST,
                           GPU_USAGE_HOST_READ);
    gpu_barrier_flush(cmd, &b);
    gpu_submit_and_wait(ctx, cmd);
    gpu_buffer_invalidate(ctx, &buf);
    if (f32) {
        memcpy(rgba_out, buf.mapped, count * sizeof(float));
    } else {
        const uint16_t *h = buf.mapped;
        for (size_t i = 0; i < count; ++i) rgba_out[i] = io_half_to_float(h[i]);
    }
    gpu_buffer_destroy(ctx, &buf);
}
