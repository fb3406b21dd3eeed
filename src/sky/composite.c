/* The composite pass (composite.h): pipeline, images, push constants, and its frame with every barrier.
 *
 * Inputs and outputs are each one image of stacked bands (2 in, VKSKY_AOV_COUNT out) rather than one image per
 * layer: one upload, one dispatch writing every layer, one copy back, and one barrier per hazard. */
#include "sky/composite.h"
#include "composite_comp.h"
#include "composite_volume_comp.h"
#include "sky/frame.h"
#include "sky/submit.h"
#include "sky/view_params.h"
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

static const double DEG = 3.14159265358979323846 / 180.0;

/* --- The world's conventions -> push constants ---------------------------------------------------------- */

/* One azimuth convention for every mode (docs/aerial_perspective.md "Conventions"): vksky's local frame is
 * (north, up, east), azimuth 0 north and 90 east. A Z-up world (Blender's) has north +Y and east +X, as Blender's
 * equirect lookup puts an environment map's azimuth 0 on +Y: (x, y, z) -> (y, z, x). A Y-up world (the same scene
 * turned by (x, y, z) -> (x, z, -y), as Z-up to Y-up exporters do) has north -Z and east +X: (x, y, z) -> (-z, y, x).
 * Both are rotations (det +1): handedness kept. */
void composite_world_to_local(int up_axis, const double w[3], double out[3])
{
    double x = w[0], y = w[1], z = w[2];
    if (up_axis == 2) {
        out[0] = y, out[1] = z, out[2] = x;
    } else {
        out[0] = -z, out[1] = y, out[2] = x;
    }
}

/* The inverse rotation: vksky local -> world. */
static void local_to_world(int up_axis, const double l[3], double out[3])
{
    double n = l[0], u = l[1], e = l[2];
    if (up_axis == 2) {
        out[0] = e, out[1] = n, out[2] = u;
    } else {
        out[0] = e, out[1] = u, out[2] = -n;
    }
}

static void dir_from_angles(double az_deg, double el_deg, double out[3])
{
    double az = az_deg * DEG, el = el_deg * DEG;
    out[0] = cos(el) * cos(az);
    out[1] = sin(el);
    out[2] = cos(el) * sin(az);
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross3(const double a[3], const double b[3], double out[3])
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    memcpy(out, c, sizeof c);
}

static void normalize3(double v[3])
{
    double n = sqrt(dot3(v, v));
    if (n > 0.0) v[0] /= n, v[1] /= n, v[2] /= n;
}

void composite_view_orient_yaw_pitch(composite_view *v, double yaw_deg, double pitch_deg)
{
    /* The sky pass's camera basis (renderer.c, sky_view_push), in the local frame, then into world axes. */
    double f[3], right[3], up[3];
    dir_from_angles(yaw_deg, pitch_deg, f);
    if (fabs(pitch_deg) >= 90.0 - 1e-9) {
        dir_from_angles(yaw_deg + 90.0, 0.0, right);
    } else {
        right[0] = -f[2], right[1] = 0.0, right[2] = f[0];
        normalize3(right);
    }
    cross3(right, f, up);
    local_to_world(v->up_axis, f, v->forward);
    local_to_world(v->up_axis, right, v->right);
    local_to_world(v->up_axis, up, v->up);
    v->oriented = true;
}

double composite_push(const composite_view *v, double bottom_radius_km, uint32_t width, uint32_t height,
                      CompositePush *out)
{
    /* The camera in the local frame, km, and its offset from the planet's centre (straight below the world
     * origin, at depth Rb + ground altitude). Altitude in double without forming |r| - Rb from two large
     * numbers: h = (|r|^2 - Rb^2) / (|r| + Rb) with |r|^2 - Rb^2 = x^2 + z^2 + y' (2 Rb + y'), y' = y + g. */
    double cw[3] = {v->camera[0] * v->km_per_unit, v->camera[1] * v->km_per_unit, v->camera[2] * v->km_per_unit};
    double c[3];
    composite_world_to_local(v->up_axis, cw, c);
    double Rb = bottom_radius_km, yp = c[1] + v->ground_altitude_km;
    double rvec[3] = {c[0], Rb + yp, c[2]};
    double rlen = sqrt(dot3(rvec, rvec));
    double altitude = (c[0] * c[0] + c[2] * c[2] + yp * (2.0 * Rb + yp)) / (rlen + Rb);
    if (!(altitude >= 0.0) || !isfinite(altitude)) return altitude < 0.0 ? altitude : -1.0;

    /* The march frame at the camera: up = the local vertical n; e_x = local +X made perpendicular to n (the
     * camera is never far from the world origin compared with the planet's radius, so they are never parallel),
     * e_z = e_x x n keeps the local frame's handedness. */
    double n[3] = {rvec[0] / rlen, rvec[1] / rlen, rvec[2] / rlen};
    double ex[3] = {1.0 - n[0] * n[0], -n[0] * n[1], -n[0] * n[2]};
    normalize3(ex);
    double ez[3];
    cross3(ex, n, ez);
    const double *rows[3] = {ex, n, ez};

    /* World offset (world units) -> march-frame km: rows[i] . (local(w) * unit). */
    for (int i = 0; i < 3; ++i) {
        double unit_axes[3];
        for (int j = 0; j < 3; ++j) {   /* column j: the image of world axis j */
            double e[3] = {j == 0, j == 1, j == 2}, l[3];
            composite_world_to_local(v->up_axis, e, l);
            unit_axes[j] = dot3(rows[i], l) * v->km_per_unit;
        }
        out->world_to_march[i] = (vksky_vec4){(float)unit_axes[0], (float)unit_axes[1], (float)unit_axes[2],
                                              (float)v->camera[i]};
    }
    /* A direction given in world axes -> march frame. */
#define TO_MARCH(world, dst)                                                                                  \
    do {                                                                                                      \
        double l_[3];                                                                                         \
        composite_world_to_local(v->up_axis, (world), l_);                                                    \
        for (int i_ = 0; i_ < 3; ++i_) (dst)[i_] = dot3(rows[i_], l_);                                        \
    } while (0)
    double sun_local[3], sun_world[3], sun[3];
    dir_from_angles(v->sun_azimuth_deg, v->sun_elevation_deg, sun_local);
    local_to_world(v->up_axis, sun_local, sun_world);
    TO_MARCH(sun_world, sun);
    double f[3] = {0, 0, 0}, rt[3] = {0, 0, 0}, up[3] = {0, 0, 0};
    double ty = tan(0.5 * v->fov_y_deg * DEG), tx = ty * (double)width / (double)height;
    if (v->oriented) {
        TO_MARCH(v->forward, f);
        TO_MARCH(v->right, rt);
        TO_MARCH(v->up, up);
    }
#undef TO_MARCH
    int max_steps = v->max_steps > v->steps ? v->max_steps : v->steps;
    out->forward = (vksky_vec4){(float)f[0], (float)f[1], (float)f[2], (float)altitude};
    out->right = (vksky_vec4){(float)(rt[0] * tx), (float)(rt[1] * tx), (float)(rt[2] * tx), 0.0f};   /* band row 0 */
    out->up = (vksky_vec4){(float)(up[0] * ty), (float)(up[1] * ty), (float)(up[2] * ty), 1.0f / (float)height};
    out->sun_dir = (vksky_vec4){(float)sun[0], (float)sun[1], (float)sun[2], (float)v->step_distribution};
    out->march = (vksky_vec4){(float)v->steps, (float)max_steps, (float)v->sample_offset, (float)v->steps_ramp_km};
    return altitude;
}

void composite_push_fast(const composite_view *v, CompositePush *push)
{
    /* With a fixed count (min = max) the march ignores march.w: its sign is free to carry the flag. */
    if (v->max_steps == 0) push->march.w = -(float)COMPOSITE_POINT_RAMP_KM;
}

/* --- The pass ------------------------------------------------------------------------------------------- */

int sky_composite_create(sky_composite *c, sky_renderer *r, uint32_t width, uint32_t height,
                         const ap_volume_desc *volume, char *err, size_t err_size)
{
    const gpu_context *ctx = r->ctx;
    memset(c, 0, sizeof *c);
    uint32_t limit = ctx->props.limits.maxImageDimension2D;
    if (width == 0 || height == 0 || width > limit || (uint64_t)height * VKSKY_AOV_COUNT > limit) {
        snprintf(err, err_size, "%ux%u is too large for this device's images (%u layers of %u rows at most)",
                 width, height, VKSKY_AOV_COUNT, limit / VKSKY_AOV_COUNT);
        return -1;
    }
    if (volume && ap_volume_create(&c->volume, r, volume, err, err_size) != 0) return -1;
    c->has_volume = volume != NULL;
    c->width = width, c->height = height;
    gpu_image_create(ctx, &c->input, "composite_in", VK_FORMAT_R32G32B32A32_SFLOAT, width, 2 * height, 1,
                     VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
    gpu_image_create(ctx, &c->output, "aovs", VK_FORMAT_R32G32B32A32_SFLOAT, width, VKSKY_AOV_COUNT * height, 1,
                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    VkDeviceSize pixels = (VkDeviceSize)width * height;
    gpu_buffer_create(ctx, &c->upload, "composite upload", pixels * 2 * 16, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    gpu_buffer_create(ctx, &c->readback, "aovs readback", pixels * VKSKY_AOV_COUNT * 16,
                      VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    /* texelFetch only; nearest, so no filtering support of the float32 format is asked for. */
    VkSamplerCreateInfo sinfo = {.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO, .magFilter = VK_FILTER_NEAREST,
                                 .minFilter = VK_FILTER_NEAREST, .mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                 .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                 .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                 .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE};
    VK_CHECK(vkCreateSampler(ctx->device, &sinfo, gpu_allocator(ctx->device), &c->nearest));
    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                    {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 5},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
    VkDescriptorPoolCreateInfo pinfo = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1,
                                        .poolSizeCount = 3, .pPoolSizes = sizes};
    VK_CHECK(vkCreateDescriptorPool(ctx->device, &pinfo, gpu_allocator(ctx->device), &c->pool));
    const VkDescriptorType UBO = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, SAMPLED = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    /* The volume (the last slot) only in the volume variant (composite.comp with AERIAL_VOLUME). */
    const gpu_slot slots[] = {{VKSKY_BINDING_ATMOSPHERE, UBO}, {VKSKY_BINDING_TRANSMITTANCE_LUT, SAMPLED},
                              {VKSKY_BINDING_MULTISCATTER_LUT, SAMPLED}, {VKSKY_BINDING_GROUND_IRRADIANCE_LUT, SAMPLED},
                              {VKSKY_BINDING_COMPOSITE_IN, SAMPLED}, {VKSKY_BINDING_OUTPUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                              {VKSKY_BINDING_AP_VOLUME, SAMPLED}};
    c->set_layout = gpu_set_layout(ctx, slots, c->has_volume ? 7 : 6, VK_SHADER_STAGE_COMPUTE_BIT, "composite");
    c->layout = gpu_pipeline_layout(ctx, c->set_layout, sizeof(CompositePush), VK_SHADER_STAGE_COMPUTE_BIT, "composite");
    c->set = gpu_alloc_set(ctx, c->pool, c->set_layout, "composite");
    const pass_shared *s = &r->shared;
    gpu_write_uniform(ctx, c->set, VKSKY_BINDING_ATMOSPHERE, s->atmosphere_ubo.buffer, sizeof(AtmosphereParams));
    gpu_write_sampled(ctx, c->set, VKSKY_BINDING_TRANSMITTANCE_LUT, r->luts.transmittance.view, s->linear_clamp);
    gpu_write_sampled(ctx, c->set, VKSKY_BINDING_MULTISCATTER_LUT, r->luts.multiscatter_view, s->linear_clamp);
    gpu_write_sampled(ctx, c->set, VKSKY_BINDING_GROUND_IRRADIANCE_LUT, r->luts.ground_irradiance_view,
                      s->linear_clamp);
    gpu_write_sampled(ctx, c->set, VKSKY_BINDING_COMPOSITE_IN, c->input.view, c->nearest);
    gpu_write_storage(ctx, c->set, VKSKY_BINDING_OUTPUT, c->output.view);
    VkShaderModule m;
    if (c->has_volume) {
        gpu_write_sampled(ctx, c->set, VKSKY_BINDING_AP_VOLUME, c->volume.image.view, s->linear_clamp);
        ap_volume_spec spec;
        ap_volume_spec_make(s->spec, volume, &spec);
        m = gpu_shader_module(ctx, spv_composite_volume_comp, sizeof spv_composite_volume_comp, "composite.comp");
        c->pipeline = gpu_compute_pipeline_spec(ctx, c->layout, m, &spec.info, "composite (volume)");
    } else {
        m = gpu_shader_module(ctx, spv_composite_comp, sizeof spv_composite_comp, "composite.comp");
        c->pipeline = gpu_compute_pipeline_spec(ctx, c->layout, m, s->spec, "composite");
    }
    vkDestroyShaderModule(ctx->device, m, gpu_allocator(ctx->device));
    return 0;
}

void sky_composite_destroy(sky_composite *c, const sky_renderer *r)
{
    const gpu_context *ctx = r->ctx;
    if (!c->pipeline) return;
    vkDeviceWaitIdle(ctx->device);
    vkDestroyPipeline(ctx->device, c->pipeline, gpu_allocator(ctx->device));
    vkDestroyPipelineLayout(ctx->device, c->layout, gpu_allocator(ctx->device));
    vkDestroyDescriptorSetLayout(ctx->device, c->set_layout, gpu_allocator(ctx->device));
    vkDestroyDescriptorPool(ctx->device, c->pool, gpu_allocator(ctx->device));
    vkDestroySampler(ctx->device, c->nearest, gpu_allocator(ctx->device));
    gpu_buffer_destroy(ctx, &c->upload);
    gpu_buffer_destroy(ctx, &c->readback);
    gpu_image_destroy(ctx, &c->input);
    gpu_image_destroy(ctx, &c->output);
    if (c->has_volume) ap_volume_destroy(&c->volume, r);
    memset(c, 0, sizeof *c);
}

float *sky_composite_inputs(sky_composite *c) { return c->upload.mapped; }

const float *sky_composite_layer(const sky_composite *c, int k)
{
    return (const float *)c->readback.mapped + (size_t)k * 4 * c->width * c->height;
}

/* --- The composite frame -------------------------------------------------------------------------------- */

/* A pass: trace line, debug label, GPU timestamps (as frame.c's passes). */
static uint32_t pass_begin(sky_renderer *r, VkCommandBuffer cmd, const char *pass)
{
    gpu_label_begin(r->ctx, cmd, pass);
    return gpu_timer_begin(&r->timer, cmd, pass);
}

static void pass_end(sky_renderer *r, VkCommandBuffer cmd, uint32_t slot)
{
    gpu_timer_end(&r->timer, cmd, slot);
    gpu_label_end(r->ctx, cmd);
}

void composite_frame_record(sky_renderer *r, sky_composite *c, VkCommandBuffer cmd, const CompositePush *push,
                            bool force_luts, bool follows_frame)
{
    VkImageSubresourceRange one = gpu_color_range(0, 1);
    r->active_timer = &r->timer;
    gpu_timer_reset(&r->timer, cmd);

    /* 1. LUTs, only when the atmosphere changed (frame.c): afterwards readable by compute shaders. Their last
     * barrier shares the next point's call. */
    gpu_barrier_batch b = gpu_barrier_batch_begin(c->has_volume ? "before ap_volume" : "before composite upload");
    frame_record_luts(r, cmd, force_luts, &b);

    /* 1b. --aerial-perspective volume: the froxel volume, marched once per froxel (reads the LUTs). The previous
     * frame's composite pass sampled it (WAR); every texel is rewritten: UNDEFINED -> GENERAL. */
    uint32_t t;
    if (c->has_volume) {
        gpu_barrier_add_image(&b, "ap_volume.to_storage", "ap_volume", c->volume.image.image, one,
                              GPU_USAGE_COMPUTE_SAMPLED, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
        gpu_barrier_flush(cmd, &b);
        t = pass_begin(r, cmd, "ap_volume");
        ap_volume_dispatch(&c->volume, cmd, push);
        pass_end(r, cmd, t);
    }

    /* 2. Upload. The previous frame's composite pass sampled the input image (WAR); it is fully rewritten:
     * UNDEFINED -> TRANSFER_DST. (The host wrote the upload buffer before the submit: the submit makes that
     * visible, no barrier.) */
    if (c->has_volume) b = gpu_barrier_batch_begin("before composite upload");
    gpu_barrier_add_image(&b, "composite_in.to_upload", "composite_in", c->input.image, one,
                          GPU_USAGE_COMPUTE_SAMPLED, GPU_USAGE_TRANSFER_DST, true);
    gpu_barrier_flush(cmd, &b);
    t = pass_begin(r, cmd, "composite_upload");
    VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                .imageExtent = {c->width, 2 * c->height, 1}};
    vkCmdCopyBufferToImage(cmd, c->upload.buffer, c->input.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    pass_end(r, cmd, t);

    /* 3. The copy wrote the inputs; the composite shader samples them: RAW + layout. The previous frame's
     * readback copy read the layer image (WAR); every texel is rewritten: UNDEFINED -> GENERAL. The volume pass
     * wrote the volume; the composite shader samples it: RAW + layout. */
    b = gpu_barrier_batch_begin("before composite");
    if (c->has_volume)
        gpu_barrier_add_image(&b, "ap_volume.write_to_sample", "ap_volume", c->volume.image.image, one,
                              GPU_USAGE_COMPUTE_STORAGE_WRITE, GPU_USAGE_COMPUTE_SAMPLED, false);
    gpu_barrier_add_image(&b, "composite_in.upload_to_read", "composite_in", c->input.image, one,
                          GPU_USAGE_TRANSFER_DST, GPU_USAGE_COMPUTE_SAMPLED, false);
    gpu_barrier_add_image(&b, "aovs.to_storage", "aovs", c->output.image, one, GPU_USAGE_TRANSFER_SRC,
                          GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
    gpu_barrier_flush(cmd, &b);
    t = pass_begin(r, cmd, "composite");
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, c->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, c->layout, 0, 1, &c->set, 0, NULL);
    vkCmdPushConstants(cmd, c->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof *push, push);
    vkCmdDispatch(cmd, (c->width + 7) / 8, (c->height + 7) / 8, 1);
    pass_end(r, cmd, t);

    /* 4. The composite shader wrote every layer; the readback copy reads them: RAW + GENERAL -> TRANSFER_SRC. */
    b = gpu_barrier_batch_begin("after composite");
    gpu_barrier_add_image(&b, "aovs.write_to_copy", "aovs", c->output.image, one, GPU_USAGE_COMPUTE_STORAGE_WRITE,
                          GPU_USAGE_TRANSFER_SRC, false);
    /* The previous frame's copy wrote the readback buffer; this frame's copy rewrites it: WAW. Between real frames
     * the fence and the host's read order them; frames recorded back to back into one command buffer
     * (VKSKY_FRAMES) need this barrier instead. */
    if (follows_frame)
        gpu_barrier_add_buffer(&b, "frames.aovs_readback", "aovs_readback", c->readback.buffer, GPU_USAGE_TRANSFER_DST,
                               GPU_USAGE_TRANSFER_DST);
    gpu_barrier_flush(cmd, &b);
    t = pass_begin(r, cmd, "composite_readback");
    region.imageExtent = (VkExtent3D){c->width, VKSKY_AOV_COUNT * c->height, 1};
    vkCmdCopyImageToBuffer(cmd, c->output.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, c->readback.buffer, 1, &region);
    pass_end(r, cmd, t);

    /* 5. The copy wrote the readback buffer; the CPU reads it after the fence: RAW (the fence alone does not
     * make device writes visible to the host). */
    b = gpu_barrier_batch_begin("after composite readback");
    gpu_barrier_add_buffer(&b, "aovs.to_host", "aovs_readback", c->readback.buffer, GPU_USAGE_TRANSFER_DST,
                           GPU_USAGE_HOST_READ);
    gpu_barrier_flush(cmd, &b);
}

double sky_composite_render(sky_renderer *r, sky_composite *c, const CompositePush *push, int frames)
{
    VkCommandBuffer cmd = gpu_begin_commands(r->ctx);
    for (int i = 0; i < (frames > 1 ? frames : 1) && i < 16; ++i)
        composite_frame_record(r, c, cmd, push, i > 0, i > 0);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    gpu_submit_and_wait(r->ctx, cmd);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    gpu_buffer_invalidate(r->ctx, &c->readback);
    return (double)(t1.tv_sec - t0.tv_sec) * 1e3 + (double)(t1.tv_nsec - t0.tv_nsec) * 1e-6;
}
