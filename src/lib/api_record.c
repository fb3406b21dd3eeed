/* Frames: the host's camera to the sky pass's rays, vksky_record over frame_record, the LUTs for the host's own
 * shaders (include/vksky.h). */
#include "lib/lib_internal.h"
#include "gpu/async_queue.h"
#include "sky/meter.h"

_Static_assert(VKSKY_AUTO_EXPOSURE_SLOTS == VKSKY_METER_SLOTS, "the API's exposure slots are the meter's");
_Static_assert(VKSKY_PROJECTION_TYPE_EQUIRECT == VKSKY_PROJECTION_EQUIRECT && VKSKY_PROJECTION_TYPE_CUBE ==
               VKSKY_PROJECTION_CUBEMAP && VKSKY_PROJECTION_TYPE_FISHEYE == VKSKY_PROJECTION_FISHEYE &&
               VKSKY_PROJECTION_TYPE_PERSPECTIVE == VKSKY_PROJECTION_PERSPECTIVE, "the API's projections are the shaders'");
#include <math.h>
#include <string.h>

static const double DEG = 3.14159265358979323846 / 180.0;

/* The host's world (+Y up, north -Z, east +X) to vksky's march frame (+Y up, azimuth 0 along +X, 90 along +Z):
 * a rotation, (x, y, z) -> (-z, y, x). */
static void host_to_march(const double h[3], double m[3]) { m[0] = -h[2], m[1] = h[1], m[2] = h[0]; }
static void march_to_host(const double m[3], double h[3]) { h[0] = m[2], h[1] = m[1], h[2] = -m[0]; }

void vksky_camera_look(vksky_camera *camera, double yaw_deg, double pitch_deg, double vertical_fov_deg, double aspect,
                       double near_m)
{
    if (!camera) return;
    /* The CLI camera's basis (sky/view_params.c), carried into the host's world. */
    sky_view v = sky_view_default();
    v.yaw_deg = yaw_deg, v.pitch_deg = pitch_deg;
    double fm[3], rm[3], um[3], f[3], r[3], u[3];
    sky_view_basis(&v, fm, rm, um);
    march_to_host(fm, f), march_to_host(rm, r), march_to_host(um, u);
    /* View: rows right, up, -forward (the eye looks down -Z), translated by the camera's position. */
    const double *p = camera->position_m;
    double *V = camera->view;
    memset(V, 0, sizeof camera->view);
    for (int c = 0; c < 3; ++c) V[c * 4 + 0] = r[c], V[c * 4 + 1] = u[c], V[c * 4 + 2] = -f[c];
    V[12] = -(r[0] * p[0] + r[1] * p[1] + r[2] * p[2]);
    V[13] = -(u[0] * p[0] + u[1] * p[1] + u[2] * p[2]);
    V[14] = f[0] * p[0] + f[1] * p[1] + f[2] * p[2];
    V[15] = 1.0;
    /* Projection: Vulkan clip space (y down), reversed depth with the far plane at infinity. */
    double t = 1.0 / tan(0.5 * vertical_fov_deg * DEG);
    double *P = camera->projection;
    memset(P, 0, sizeof camera->projection);
    P[0] = t / (aspect > 0.0 ? aspect : 1.0);
    P[5] = -t;
    P[11] = -1.0;    /* w = -z_eye */
    P[14] = near_m;  /* depth = near / -z_eye: 1 at the near plane, 0 at infinity */
}

/* 4x4 inverse (column-major), by cofactors. Returns false for a singular matrix. */
static bool invert4(const double m[16], double out[16])
{
    double inv[16];
    inv[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] + m[9] * m[7] * m[14] + m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    inv[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] - m[8] * m[7] * m[14] - m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    inv[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] + m[8] * m[7] * m[13] + m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    inv[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] - m[8] * m[6] * m[13] - m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    inv[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] - m[9] * m[3] * m[14] - m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    inv[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] + m[8] * m[3] * m[14] + m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    inv[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] - m[8] * m[3] * m[13] - m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    inv[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] + m[8] * m[2] * m[13] + m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    inv[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] + m[5] * m[3] * m[14] + m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
    inv[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] - m[4] * m[3] * m[14] - m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    inv[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] + m[4] * m[3] * m[13] + m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    inv[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] - m[4] * m[2] * m[13] - m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    inv[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] - m[5] * m[3] * m[10] - m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
    inv[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] + m[4] * m[3] * m[10] + m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
    inv[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] - m[4] * m[3] * m[9] - m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
    inv[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] + m[4] * m[2] * m[9] + m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
    double det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
    if (!(fabs(det) > 0.0) || !isfinite(det)) return false;
    for (int i = 0; i < 16; ++i) out[i] = inv[i] / det;
    return true;
}

/* The world direction (march frame) through NDC (x, y): the inverse projection's point at mid depth, seen from
 * the eye, turned by the view's rotation (its transpose: a view is rigid). */
static bool ndc_ray(const double inv_proj[16], const double view[16], double x, double y, double out[3])
{
    double q[4];
    for (int r = 0; r < 4; ++r) q[r] = inv_proj[r] * x + inv_proj[4 + r] * y + inv_proj[8 + r] * 0.5 + inv_proj[12 + r];
    if (!(fabs(q[3]) > 0.0)) return false;
    double e[3] = {q[0] / q[3], q[1] / q[3], q[2] / q[3]}, w[3];
    for (int c = 0; c < 3; ++c) w[c] = view[c * 4 + 0] * e[0] + view[c * 4 + 1] * e[1] + view[c * 4 + 2] * e[2];
    host_to_march(w, out);
    return isfinite(out[0]) && isfinite(out[1]) && isfinite(out[2]);
}

/* The camera -> the view's rays and altitude (double, on the CPU: no planet-scale subtraction on the GPU). */
static bool camera_to_view(const vksky_camera *cam, double ground_radius_km, sky_view *v)
{
    double inv[16], c[3], px[3], py[3];
    if (!invert4(cam->projection, inv) || !ndc_ray(inv, cam->view, 0, 0, c) || !ndc_ray(inv, cam->view, 1, 0, px) ||
        !ndc_ray(inv, cam->view, 0, -1, py))
        return false;
    double n = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    if (!(n > 0.0)) return false;
    v->ray_given = true;
    for (int i = 0; i < 3; ++i)
        v->ray_forward[i] = c[i] / n, v->ray_right[i] = (px[i] - c[i]) / n, v->ray_up[i] = (py[i] - c[i]) / n;
    /* Altitude: |p| - R with p the camera from the planet's centre, as (|p|^2 - R^2) / (|p| + R). */
    double R = ground_radius_km * 1000.0, h0 = cam->origin_altitude_m + cam->position_m[1];
    double s2 = cam->position_m[0] * cam->position_m[0] + cam->position_m[2] * cam->position_m[2];
    double alt_m = (s2 + h0 * (2.0 * R + h0)) / (sqrt(s2 + (R + h0) * (R + h0)) + R);
    if (!isfinite(alt_m)) return false;
    v->altitude_km = alt_m > 0.0 ? alt_m / 1000.0 : 0.0;
    return true;
}

static gpu_usage_info image_use(vksky_image_use u)
{
    return (gpu_usage_info){.name = "host", .stage = u.stage, .access = u.access, .layout = u.layout};
}

static bool format_is_depth(VkFormat f)
{
    return f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_X8_D24_UNORM_PACK32 || f == VK_FORMAT_D32_SFLOAT ||
           f == VK_FORMAT_D16_UNORM_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

/* SCENE_LINEAR: the host's camera to the pass's push constants (sky/host_frame.c), its images with their uses. */
static vksky_result record_scene_linear(vksky_renderer *renderer, VkCommandBuffer cmd, const vksky_frame *frame)
{
    vksky_context *c = renderer->ctx;
    const vksky_image *img = &frame->color, *depth = frame->depth;
    if (!frame->camera || !img->image || !img->view || (depth && (!depth->image || !depth->view))) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record: SCENE_LINEAR needs frame.camera, frame.color's image and view, and frame.depth's "
                    "(or depth NULL)");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    if (img->extent.width != renderer->desc.width || img->extent.height != renderer->desc.height ||
        img->format != renderer->desc.target_format ||
        (depth && (depth->extent.width != img->extent.width || depth->extent.height != img->extent.height ||
                   !format_is_depth(depth->format)))) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record: frame.color %ux%u format %d (the renderer: %ux%u format %d), frame.depth %ux%u "
                    "format %d: expected the renderer's size and format, a depth format of the same size",
                    img->extent.width, img->extent.height, (int)img->format, renderer->desc.width,
                    renderer->desc.height, (int)renderer->desc.target_format, depth ? depth->extent.width : 0,
                    depth ? depth->extent.height : 0, depth ? (int)depth->format : 0);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    host_camera cam;
    memcpy(cam.position_m, frame->camera->position_m, sizeof cam.position_m);
    cam.origin_altitude_m = frame->camera->origin_altitude_m;
    memcpy(cam.view, frame->camera->view, sizeof cam.view);
    memcpy(cam.projection, frame->camera->projection, sizeof cam.projection);
    const model_atmosphere *a = &renderer->o.atmosphere;
    HostFramePush push;
    char err[200];
    if (host_frame_push(&cam, &renderer->o.view, a->bottom_radius, a->top_radius - a->bottom_radius,
                        img->extent.width, img->extent.height, depth != NULL, &push, err, sizeof err) != 0) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR, "vksky_record: %s", err);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    host_image color = {img->image, img->view, img->format, img->extent, image_use(img->before), image_use(img->after)};
    host_image z = {0};
    if (depth) z = (host_image){depth->image, depth->view, depth->format, depth->extent, image_use(depth->before),
                                image_use(depth->after)};
    host_frame_desc f = {.color = &color, .depth = depth ? &z : NULL, .push = &push, .force_luts = frame->force_luts};
    gpu_trap trap;   /* as record_trapped: an internal failure returns an error, the host resets the command buffer */
    if (setjmp(trap.jump)) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record: %s (the command buffer is incomplete: reset it)", trap.message);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    host_frame_record(&renderer->r, &renderer->hf, cmd, &f);
    gpu_trap_arm(NULL);
    return VKSKY_SUCCESS;
}

/* frame_record under the trap: an internal failure below (gpu_fail) returns an error instead of ending the host's
 * process; the command buffer is then half-recorded, and the host resets it. No allocation: a setjmp. */
static vksky_result record_trapped(vksky_renderer *renderer, VkCommandBuffer cmd, const frame_desc *f, bool luts_only)
{
    gpu_trap trap;
    if (setjmp(trap.jump)) {
        lib_message(renderer->ctx->message, renderer->ctx->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record: %s (the command buffer is incomplete: reset it)", trap.message);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    if (luts_only) frame_record_luts_only(&renderer->r, cmd, f);
    else frame_record(&renderer->r, cmd, f);
    gpu_trap_arm(NULL);
    return VKSKY_SUCCESS;
}

static vksky_result record_frame(vksky_renderer *renderer, VkCommandBuffer cmd, const vksky_frame *frame);
vksky_result vksky_record_luts(vksky_renderer *renderer, VkCommandBuffer compute_cmd, bool force, bool *recorded)
{
    if (recorded) *recorded = false;
    if (!renderer || !compute_cmd) return VKSKY_ERROR_INVALID_ARGUMENT;
    vksky_context *c = renderer->ctx;
    if (!c->gpu.compute_queue) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record_luts: the context has no compute queue (vksky_context_desc.compute_queue)");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    if (!force && !sky_renderer_luts_dirty(&renderer->r)) return VKSKY_SUCCESS;
    const gpu_trace_sink *was = lib_trace_begin(c);   /* the LUT passes' lines go to this context's trace */
    gpu_trap trap;
    if (setjmp(trap.jump)) {
        lib_trace_end(was);
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record_luts: %s (the command buffer is incomplete: reset it)", trap.message);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    /* The LUT passes and their last barriers (the releases to the graphics family when the families differ), under
     * one label in the host's capture (vksky_context_set_debug_utils). */
    gpu_label_group_begin(&c->gpu, compute_cmd, "vksky.record_luts");
    frame_record_luts_compute(&renderer->r, compute_cmd);
    gpu_label_end(&c->gpu, compute_cmd);
    renderer->r.lut_acquire_pending = gpu_async_other_family(&c->gpu);
    gpu_trap_arm(NULL);
    lib_trace_end(was);
    if (recorded) *recorded = true;
    return VKSKY_SUCCESS;
}

vksky_result vksky_record(vksky_renderer *renderer, VkCommandBuffer cmd, const vksky_frame *frame)
{
    if (!renderer || !cmd || !frame) return VKSKY_ERROR_INVALID_ARGUMENT;
    const gpu_trace_sink *was = lib_trace_begin(renderer->ctx);   /* the lines go to this context's trace */
    /* The frame's passes (each labelled by the spine) under one label in the host's capture. */
    gpu_label_group_begin(&renderer->ctx->gpu, cmd, "vksky.record");
    vksky_result res = record_frame(renderer, cmd, frame);
    gpu_label_end(&renderer->ctx->gpu, cmd);
    lib_trace_end(was);
    return res;
}

/* A band of a whole image in a projection (vksky_frame_band): its ranges against the renderer, then the view's tile
 * offset and whole size, as the command line's banded renders set them (so the bands equal one whole frame). */
static vksky_result apply_band(const vksky_renderer *renderer, const vksky_frame_band *b, bool view_given, sky_view *v)
{
    const vksky_context *c = renderer->ctx;
    uint32_t w = renderer->desc.width, h = renderer->desc.height;
    const char *bad = NULL;
    if ((unsigned)b->projection > VKSKY_PROJECTION_TYPE_FISHEYE) bad = "projection: PERSPECTIVE, EQUIRECT, CUBE or FISHEYE";
    else if (b->whole_width != w) bad = "whole_width: the renderer's width (a band spans the whole image's columns)";
    else if (b->whole_height < 1 || b->whole_height > (1u << 20)) bad = "whole_height: 1..1048576";
    else if (b->first_row < -(int64_t)h || b->first_row > (int64_t)b->whole_height)
        bad = "first_row: -height..whole_height (the renderer's height)";
    else if ((uint64_t)b->meter_first_row + b->meter_rows > h) bad = "meter_first_row + meter_rows: within the frame's rows";
    else if (b->projection == VKSKY_PROJECTION_TYPE_PERSPECTIVE && !view_given)
        bad = "a perspective band: with a vksky_frame_view (the view the command line gives)";
    else if (renderer->o.render_scale != 1.0) bad = "a renderer of render_scale 1 (a band's rows are its own)";
    if (bad) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record: vksky_frame_band: projection %d, whole %ux%u, first_row %d, meter rows %u+%u on a "
                    "%ux%u renderer; accepted %s", (int)b->projection, b->whole_width, b->whole_height, b->first_row,
                    b->meter_first_row, b->meter_rows, w, h, bad);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    v->projection = (int)b->projection;
    v->tile_x = 0, v->tile_y = b->first_row;
    v->whole_width = (int)b->whole_width, v->whole_height = (int)b->whole_height;
    return VKSKY_SUCCESS;
}

static vksky_result record_frame(vksky_renderer *renderer, VkCommandBuffer cmd, const vksky_frame *frame)
{
    lib_frame_ext ext;
    vksky_result chain = lib_frame_chain(renderer->ctx, frame->next, &ext);
    if (chain != VKSKY_SUCCESS) return chain;
    const vksky_frame_view *given = ext.view;
    const vksky_auto_exposure *metered = ext.exposure;
    const vksky_frame_band *band = ext.band;
    const vksky_readback_target *readback_target = ext.target;
    chain = lib_window_check(renderer, &ext);   /* the window's values (a readback renderer: tone map, bloom) */
    if (chain != VKSKY_SUCCESS) return chain;
    vksky_context *c = renderer->ctx;
    sky_view v = renderer->o.view;
    if (renderer->desc.output == VKSKY_OUTPUT_LUTS_ONLY && !readback_target) {
        /* The camera gives the sky-view LUT its altitude; without one, the scene's camera altitude serves. */
        if (frame->camera && !camera_to_view(frame->camera, renderer->o.atmosphere.bottom_radius, &v)) {
            lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                        "vksky_record: the camera's matrices give no rays (a singular or non-perspective projection)");
            return VKSKY_ERROR_INVALID_ARGUMENT;
        }
        frame_desc f = {.view = &v, .force_luts = frame->force_luts};
        return record_trapped(renderer, cmd, &f, true);
    }
    if ((given || metered || band || readback_target) && renderer->desc.output != VKSKY_OUTPUT_DISPLAY) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record: vksky_frame_view, vksky_auto_exposure and vksky_frame_band are for output DISPLAY "
                    "only (the others take frame.camera and leave exposure to the host)");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    if (renderer->desc.output == VKSKY_OUTPUT_SCENE_LINEAR) return record_scene_linear(renderer, cmd, frame);
    if (!metered && !isfinite(frame->exposure)) return VKSKY_ERROR_INVALID_ARGUMENT;
    /* The frame's projection: a perspective of the whole image unless a band says otherwise. */
    v.projection = VKSKY_PROJECTION_TYPE_PERSPECTIVE;
    v.tile_x = v.tile_y = v.whole_width = v.whole_height = 0;
    if (band) {
        vksky_result res = apply_band(renderer, band, given != NULL, &v);
        if (res != VKSKY_SUCCESS) return res;
    }
    bool world_fixed = band && band->projection != VKSKY_PROJECTION_TYPE_PERSPECTIVE;   /* a map: no camera */
    if (given) {
        /* The view as given: the sky pass computes its rays from yaw, pitch and fov as the command line's do. */
        v.ray_given = false;
        v.yaw_deg = given->yaw_deg, v.pitch_deg = given->pitch_deg, v.fov_deg = given->fov_deg;
    } else if (world_fixed) {
        v.ray_given = false;   /* the projection gives every pixel its direction */
    } else if (!frame->camera || !camera_to_view(frame->camera, renderer->o.atmosphere.bottom_radius, &v)) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record: DISPLAY needs frame.camera (or a vksky_frame_view), and the camera's matrices must "
                    "give rays (not singular, a perspective projection)");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    v.exposure_ev = metered ? 0.0 : frame->exposure;
    /* Auto exposure: the spine's meter passes (sky/meter.h) between the sky and the tone map, the result in a slot. */
    v.auto_exposure = metered != NULL;
    v.auto_exposure_ease = metered ? metered->ease : 0.0;
    uint32_t slot = metered ? metered->slot : 0;
    if (readback_target && (!renderer->readback || readback_target->slot >= renderer->slot_count)) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record: vksky_readback_target: slot %u; the renderer has %u readback slot%s "
                    "(vksky_renderer_set_readback_slots)", readback_target->slot, renderer->slot_count,
                    renderer->slot_count == 1 ? "" : "s");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    spectral_sum_step refused;
    if (ext.spectral_sum && !renderer->readback) return lib_spectral_sum_step(renderer, ext.spectral_sum, &refused);
    if (renderer->readback) {
        /* The host's ring names the pair of readback buffers this frame's copies go to (slot 0 without one). */
        lib_readback_select(renderer, readback_target ? readback_target->slot : 0);
        /* vksky's own display and composite images, copied to its readback buffers: frame.color is not used. */
        if (ext.display) v.tonemap = (int)ext.display->tonemap, v.bloom = ext.display->bloom;   /* checked above */
        frame_desc own = {.view = &v, .force_luts = frame->force_luts, .meter_slot = slot,
                          .follows_frame = readback_target && readback_target->follows_frame,
                          .meter_first_row = band ? band->meter_first_row : 0, .meter_rows = band ? band->meter_rows : 0};
        /* ABI 4: a spectral group's frame adds its composite into the GPU's sum instead (api_spectral_sum.c). */
        spectral_sum_step sum_step;
        if (ext.spectral_sum) {
            vksky_result res = lib_spectral_sum_step(renderer, ext.spectral_sum, &sum_step);
            if (res != VKSKY_SUCCESS) return res;
            own.sum = &sum_step;
        }
        return record_trapped(renderer, cmd, &own, false);
    }
    const vksky_image *img = &frame->color;
    if (!img->image || !img->view) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record: DISPLAY needs frame.color's image and view");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    if (img->extent.width != renderer->desc.width || img->extent.height != renderer->desc.height ||
        img->format != renderer->desc.target_format) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record: frame.color is %ux%u format %d; the renderer is %ux%u format %d (resize it)",
                    img->extent.width, img->extent.height, (int)img->format, renderer->desc.width,
                    renderer->desc.height, (int)renderer->desc.target_format);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    frame_target target = {.image = img->image, .view = img->view, .extent = img->extent, .host_uses = true,
                           .host_before = image_use(img->before), .host_after = image_use(img->after)};
    frame_desc f = {.view = &v, .force_luts = frame->force_luts, .target = &target, .meter_slot = slot,
                    .meter_first_row = band ? band->meter_first_row : 0, .meter_rows = band ? band->meter_rows : 0};
    /* ABI 3, the window's values (api_window.c): tone map, bloom, place, timer slot, capture, swapchain uses. */
    vksky_result res = lib_window_apply(renderer, &ext, &v, &f, &target);
    if (res != VKSKY_SUCCESS) return res;
    /* vksky_display_config: the compute tone map writes the host's storage image (not a capture's or a swapchain's). */
    target.storage = renderer->host_compute && target.host_uses && !target.capture;
    return record_trapped(renderer, cmd, &f, false);
}

vksky_result vksky_renderer_get_exposure(const vksky_renderer *renderer, uint32_t slot, vksky_exposure *out)
{
    if (!renderer || !out || slot >= VKSKY_AUTO_EXPOSURE_SLOTS || renderer->desc.output != VKSKY_OUTPUT_DISPLAY)
        return VKSKY_ERROR_INVALID_ARGUMENT;
    meter_result m = meter_read(&renderer->ctx->gpu, &renderer->r.meter, slot);
    *out = (vksky_exposure){.ev100 = m.ev100, .log_average = m.log_average, .pixel_count = m.count};
    return VKSKY_SUCCESS;
}

vksky_result vksky_get_luts(const vksky_renderer *renderer, vksky_luts *out)
{
    if (!renderer || !out) return VKSKY_ERROR_INVALID_ARGUMENT;
    const sky_renderer *r = &renderer->r;
    double sun_m[3], el = renderer->o.view.sun_elevation_deg * DEG, az = renderer->o.view.sun_azimuth_deg * DEG;
    sun_m[0] = cos(el) * cos(az), sun_m[1] = sin(el), sun_m[2] = cos(el) * sin(az);
    *out = (vksky_luts){
        .transmittance = r->luts.transmittance.view, .multiscatter = r->luts.multiscatter_view,
        .skyview = r->luts.skyview.view, .sampler = r->shared.linear_clamp,
        .bottom_radius_km = (float)r->medium.bottom_radius, .top_radius_km = (float)r->medium.top_radius,
        .sun_direction = {(float)sun_m[0], (float)sun_m[1], (float)sun_m[2]},
        .sun_illuminance = {r->atmosphere.sun.x, r->atmosphere.sun.y, r->atmosphere.sun.z},
        .ready_stage = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
        .ready_access = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
    return VKSKY_SUCCESS;
}
