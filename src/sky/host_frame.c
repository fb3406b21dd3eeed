/* The SCENE_LINEAR pass (host_frame.h): the host's camera as push constants, the pass's pipeline and descriptor
 * sets, and its frame with every barrier on the host's images. */
#include "sky/host_frame.h"
#include "host_frame_comp.h"
#include "host_frame_f32_comp.h"
#include "sky/composite.h"
#include "sky/frame.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

/* --- The host's camera -> push constants ------------------------------------------------------------------ */

/* Column-major 4x4 (m[col * 4 + row]), as GLSL and the host's matrices. */
static void mat4_mul(const double a[16], const double b[16], double out[16])
{
    double r[16];
    for (int c = 0; c < 4; ++c)
        for (int i = 0; i < 4; ++i) {
            double s = 0.0;
            for (int k = 0; k < 4; ++k) s += a[k * 4 + i] * b[c * 4 + k];
            r[c * 4 + i] = s;
        }
    memcpy(out, r, sizeof r);
}

static void mat4_apply(const double m[16], const double v[4], double out[4])
{
    for (int i = 0; i < 4; ++i) out[i] = m[i] * v[0] + m[4 + i] * v[1] + m[8 + i] * v[2] + m[12 + i] * v[3];
}

/* Gauss-Jordan with partial pivoting, in double. False if singular. */
static bool mat4_invert(const double m[16], double out[16])
{
    double a[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) a[i][j] = m[j * 4 + i], a[i][j + 4] = i == j;
    for (int c = 0; c < 4; ++c) {
        int p = c;
        for (int i = c + 1; i < 4; ++i)
            if (fabs(a[i][c]) > fabs(a[p][c])) p = i;
        if (!(fabs(a[p][c]) > 1e-300)) return false;
        for (int j = 0; j < 8; ++j) {
            double t = a[c][j];
            a[c][j] = a[p][j], a[p][j] = t;
        }
        double inv = 1.0 / a[c][c];
        for (int j = 0; j < 8; ++j) a[c][j] *= inv;
        for (int i = 0; i < 4; ++i) {
            if (i == c) continue;
            double f = a[i][c];
            for (int j = 0; j < 8; ++j) a[i][j] -= f * a[c][j];
        }
    }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) out[j * 4 + i] = a[i][j + 4];
    return true;
}

static double len3(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

int host_frame_push(const host_camera *camera, const sky_view *view, double ground_radius_km,
                    double atmosphere_top_km, uint32_t width, uint32_t height, bool has_depth, HostFramePush *out,
                    char *err, size_t err_size)
{
    /* The march frame at the camera, its altitude, the sun and the march settings: the composite pass's conventions
     * (a Y-up world in metres, the planet's centre below the world origin). */
    composite_view cv = {.km_per_unit = 0.001, .up_axis = 1, .ground_altitude_km = camera->origin_altitude_m * 0.001,
                         .sun_azimuth_deg = view->sun_azimuth_deg, .sun_elevation_deg = view->sun_elevation_deg,
                         .steps = view->steps, .max_steps = view->max_steps, .steps_ramp_km = view->steps_ramp_km,
                         .sample_offset = view->sample_offset, .step_distribution = view->step_distribution};
    memcpy(cv.camera, camera->position_m, sizeof cv.camera);
    CompositePush cp;
    double altitude = composite_push(&cv, ground_radius_km, width, height, &cp);
    if (!(altitude >= 0.0)) {
        snprintf(err, err_size, "the camera is below the ground (altitude %.6g km)", altitude);
        return -1;
    }
    /* inverse(projection x view) without the view's translation: clip -> a world offset from the camera. */
    double rot[16], pr[16], inv[16];
    memcpy(rot, camera->view, sizeof rot);
    rot[12] = rot[13] = rot[14] = 0.0;
    mat4_mul(camera->projection, rot, pr);
    if (!mat4_invert(pr, inv)) {
        snprintf(err, err_size, "projection x view is singular");
        return -1;
    }
    const double *c0 = inv, *c1 = inv + 4, *c2 = inv + 8, *c3 = inv + 12;
    /* A perspective: the depth reaches the point through w alone (no xyz term), w does not depend on x, y. */
    double scale = fmax(len3(c0), fmax(len3(c1), len3(c3)));
    if (!(len3(c2) <= 1e-6 * scale) || !(fabs(c0[3]) + fabs(c1[3]) <= 1e-6 * (fabs(c2[3]) + fabs(c3[3])))) {
        snprintf(err, err_size, "the projection is not a perspective (accepted: a perspective projection, "
                                "standard or reversed depth, finite or infinite far plane)");
        return -1;
    }
    /* The point 1 m and 2 m in front of the camera along c3's ray: which side is in front (clip w > 0), and
     * whether depth falls with distance (reversed). */
    double n3 = len3(c3), front = 0.0, d[2] = {0, 0};
    for (int k = 0; k < 2 && front == 0.0; ++k) {
        double sgn = k == 0 ? 1.0 : -1.0, q[4] = {sgn * c3[0] / n3, sgn * c3[1] / n3, sgn * c3[2] / n3, 1.0}, clip[4];
        mat4_apply(pr, q, clip);
        if (clip[3] > 0.0) front = sgn;
    }
    if (front == 0.0) {
        snprintf(err, err_size, "the projection puts nothing in front of the camera");
        return -1;
    }
    for (int k = 0; k < 2; ++k) {
        double t = k + 1.0, q[4] = {front * t * c3[0] / n3, front * t * c3[1] / n3, front * t * c3[2] / n3, 1.0};
        double clip[4];
        mat4_apply(pr, q, clip);
        d[k] = clip[2] / clip[3];
    }
    bool reversed = d[1] < d[0];
    double w1 = c2[3] * d[0] + c3[3];
    double sigma = (w1 > 0.0 ? 1.0 : -1.0);
    /* World offset (m) -> march-frame km: the composite's rows (km per metre included). */
    double cols[3][3], rows[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) rows[i][j] = (&cp.world_to_march[i].x)[j];
    const double *src[3] = {c3, c0, c1};
    for (int v = 0; v < 3; ++v)
        for (int i = 0; i < 3; ++i) cols[v][i] = rows[i][0] * src[v][0] + rows[i][1] * src[v][1] + rows[i][2] * src[v][2];
    double s = sigma / len3(cols[0]);
    SkyPush *sky = &out->sky;
    /* ndc.y in the sky's convention is up: Vulkan's clip y is down, so up = -c1. */
    sky->forward = (vksky_vec4){(float)(s * cols[0][0]), (float)(s * cols[0][1]), (float)(s * cols[0][2]), (float)altitude};
    sky->right = (vksky_vec4){(float)(s * cols[1][0]), (float)(s * cols[1][1]), (float)(s * cols[1][2]), 1.0f / (float)width};
    sky->up = (vksky_vec4){(float)(-s * cols[2][0]), (float)(-s * cols[2][1]), (float)(-s * cols[2][2]), 1.0f / (float)height};
    sky->sun_dir = cp.sun_dir;
    sky->march = cp.march;
    sky->projection = (vksky_vec4){0.0f, 0.0f, 0.0f, 0.0f};   /* VKSKY_PROJECTION_PERSPECTIVE, no tile */
    sky->horizon = (vksky_vec4){(float)sky_view_horizon_sine(altitude, ground_radius_km), 1.0f,
                                (float)sky_view_march_blend(altitude, atmosphere_top_km),
                                (float)sky_view_horizon_march_blend(altitude, atmosphere_top_km)};
    out->depth = (vksky_vec4){(float)(s * c2[3]), (float)(s * c3[3]), reversed ? 0.0f : 1.0f,
                              !has_depth ? 2.0f : reversed ? 1.0f : 0.0f};
    return 0;
}

/* --- The pass ---------------------------------------------------------------------------------------------- */

bool host_frame_format_supported(VkFormat format)
{
    return format == VK_FORMAT_R16G16B16A16_SFLOAT || format == VK_FORMAT_R32G32B32A32_SFLOAT;
}

int host_frame_create(host_frame *h, sky_renderer *r, VkFormat color_format, char *err, size_t err_size)
{
    const gpu_context *ctx = r->ctx;
    const pass_shared *s = &r->shared;
    memset(h, 0, sizeof *h);
    if (!host_frame_format_supported(color_format)) {
        snprintf(err, err_size, "the colour image's format %d cannot be the pass's storage image (accepted: "
                                "R16G16B16A16_SFLOAT, R32G32B32A32_SFLOAT)", (int)color_format);
        return -1;
    }
    h->format = color_format;
    VkSamplerCreateInfo sinfo = {.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO, .magFilter = VK_FILTER_NEAREST,
                                 .minFilter = VK_FILTER_NEAREST, .mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                 .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                 .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                 .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE};
    VK_CHECK(vkCreateSampler(ctx->device, &sinfo, gpu_allocator(ctx->device), &h->nearest));
    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, HOST_FRAME_SETS},
                                    {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4 * HOST_FRAME_SETS},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, HOST_FRAME_SETS}};
    VkDescriptorPoolCreateInfo pinfo = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                        .maxSets = HOST_FRAME_SETS, .poolSizeCount = 3, .pPoolSizes = sizes};
    VK_CHECK(vkCreateDescriptorPool(ctx->device, &pinfo, gpu_allocator(ctx->device), &h->pool));
    const VkDescriptorType UBO = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, SAMPLED = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    /* The atmosphere passes' slots (shaders/glsl/bindings.h): the LUTs, the host's depth, its colour as the output. */
    const gpu_slot slots[] = {{VKSKY_BINDING_ATMOSPHERE, UBO},
                              {VKSKY_BINDING_TRANSMITTANCE_LUT, SAMPLED},
                              {VKSKY_BINDING_MULTISCATTER_LUT, SAMPLED},
                              {VKSKY_BINDING_GROUND_IRRADIANCE_LUT, SAMPLED},
                              {VKSKY_BINDING_HOST_DEPTH, SAMPLED},
                              {VKSKY_BINDING_OUTPUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    h->set_layout = gpu_set_layout(ctx, slots, 6, VK_SHADER_STAGE_COMPUTE_BIT, "host_frame");
    h->layout = gpu_pipeline_layout(ctx, h->set_layout, sizeof(HostFramePush), VK_SHADER_STAGE_COMPUTE_BIT, "host_frame");
    for (int i = 0; i < HOST_FRAME_SETS; ++i) {
        h->sets[i] = gpu_alloc_set(ctx, h->pool, h->set_layout, "host_frame");
        gpu_write_uniform(ctx, h->sets[i], VKSKY_BINDING_ATMOSPHERE, s->atmosphere_ubo.buffer, sizeof(AtmosphereParams));
        gpu_write_sampled(ctx, h->sets[i], VKSKY_BINDING_TRANSMITTANCE_LUT, r->luts.transmittance.view, s->linear_clamp);
        gpu_write_sampled(ctx, h->sets[i], VKSKY_BINDING_MULTISCATTER_LUT, r->luts.multiscatter_view, s->linear_clamp);
        gpu_write_sampled(ctx, h->sets[i], VKSKY_BINDING_GROUND_IRRADIANCE_LUT, r->luts.ground_irradiance_view, s->linear_clamp);
    }
    bool f32 = color_format == VK_FORMAT_R32G32B32A32_SFLOAT;
    VkShaderModule m = f32 ? gpu_shader_module(ctx, spv_host_frame_f32_comp, sizeof spv_host_frame_f32_comp, "host_frame.comp")
                           : gpu_shader_module(ctx, spv_host_frame_comp, sizeof spv_host_frame_comp, "host_frame.comp");
    h->pipeline = gpu_compute_pipeline_spec(ctx, h->layout, m, s->spec, "host_frame");
    vkDestroyShaderModule(ctx->device, m, gpu_allocator(ctx->device));
    return 0;
}

void host_frame_destroy(host_frame *h, const sky_renderer *r)
{
    VkDevice d = r->ctx->device;
    if (!h->pipeline) return;
    vkDestroyPipeline(d, h->pipeline, gpu_allocator(d));
    vkDestroyPipelineLayout(d, h->layout, gpu_allocator(d));
    vkDestroyDescriptorSetLayout(d, h->set_layout, gpu_allocator(d));
    vkDestroyDescriptorPool(d, h->pool, gpu_allocator(d));
    vkDestroySampler(d, h->nearest, gpu_allocator(d));
    memset(h, 0, sizeof *h);
}

/* The set naming this (colour, depth) pair: a set already written for it, else the least recently used one
 * rewritten (no allocation per frame). */
static VkDescriptorSet pair_set(host_frame *h, const sky_renderer *r, VkImageView color, VkImageView depth)
{
    int pick = 0;
    ++h->use_clock;
    for (int i = 0; i < HOST_FRAME_SETS; ++i) {
        if (h->set_color[i] == color && h->set_depth[i] == depth && h->set_used[i]) {
            h->set_used[i] = h->use_clock;
            return h->sets[i];
        }
        if (h->set_used[i] < h->set_used[pick]) pick = i;
    }
    gpu_write_sampled(r->ctx, h->sets[pick], VKSKY_BINDING_HOST_DEPTH, depth, h->nearest);
    gpu_write_storage(r->ctx, h->sets[pick], VKSKY_BINDING_OUTPUT, color);
    h->set_color[pick] = color, h->set_depth[pick] = depth, h->set_used[pick] = h->use_clock;
    return h->sets[pick];
}

static bool format_has_stencil(VkFormat f)
{
    return f == VK_FORMAT_D16_UNORM_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

/* vksky's own uses of the host's images while the pass runs. */
static const gpu_usage_info COLOR_IN_PASS = {"host_frame_rw", VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                             VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                             VK_IMAGE_LAYOUT_GENERAL};
static const gpu_usage_info DEPTH_IN_PASS = {"host_frame_depth", VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                             VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};

void host_frame_record(sky_renderer *r, host_frame *h, VkCommandBuffer cmd, const host_frame_desc *f)
{
    const host_image *color = f->color, *depth = f->depth;
    VkImageSubresourceRange one = gpu_color_range(0, 1);
    VkImageSubresourceRange depth_range = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
    if (depth && format_has_stencil(depth->format)) depth_range.aspectMask |= VK_IMAGE_ASPECT_STENCIL_BIT;
    r->active_timer = &r->timer;
    gpu_timer_reset(&r->timer, cmd);

    /* 1. The LUTs, when the atmosphere changed (frame.c); their last barrier joins the pass's point. */
    gpu_barrier_batch b = gpu_barrier_batch_begin("before host_frame");
    frame_record_luts(r, cmd, f->force_luts, &b);

    /* 2. The host's images, from the host's last use to the pass's. Colour: the host's geometry pass wrote it (RAW),
     * or read it (WAR); the pass reads and writes it in GENERAL. Depth: the host's depth test wrote it (RAW); the
     * pass samples it: to SHADER_READ_ONLY. */
    gpu_barrier_add_image_info(&b, "host.color.to_storage", "host_color", color->image, one, color->before,
                               COLOR_IN_PASS, false);
    if (depth)
        gpu_barrier_add_image_info(&b, "host.depth.to_sample", "host_depth", depth->image, depth_range,
                                   depth->before, DEPTH_IN_PASS, false);
    gpu_barrier_flush(cmd, &b);

    /* 3. The pass: sky behind the geometry, aerial perspective on it. Without a depth image the transmittance LUT
     * stands in for it (never read: the push says "no depth"). */
    VkDescriptorSet set = pair_set(h, r, color->view, depth ? depth->view : r->luts.transmittance.view);
    gpu_label_begin(r->ctx, cmd, "host_frame");
    uint32_t t = gpu_timer_begin(&r->timer, cmd, "host_frame");
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, h->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, h->layout, 0, 1, &set, 0, NULL);
    vkCmdPushConstants(cmd, h->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof *f->push, f->push);
    vkCmdDispatch(cmd, (color->extent.width + 7) / 8, (color->extent.height + 7) / 8, 1);
    gpu_timer_end(&r->timer, cmd, t);
    gpu_label_end(r->ctx, cmd);

    /* 4. Back to the host: the pass wrote the colour image; the host's next use reads (RAW) or overwrites it (WAW),
     * in its layout. The pass sampled the depth; the host's next use (next frame's clear, its depth test) writes it
     * (WAR) in its layout. */
    b = gpu_barrier_batch_begin("after host_frame");
    gpu_barrier_add_image_info(&b, "host.color.to_after", "host_color", color->image, one, COLOR_IN_PASS,
                               color->after, false);
    if (depth)
        gpu_barrier_add_image_info(&b, "host.depth.to_after", "host_depth", depth->image, depth_range,
                                   DEPTH_IN_PASS, depth->after, false);
    gpu_barrier_flush(cmd, &b);
}
