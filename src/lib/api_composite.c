/* Compositing a render through the API (include/vksky.h, "Compositing a render"; docs/library.md): the composite pass
 * of sky/composite.h over a host's renderer, its frame recorded into the host's command buffer, its inputs and layers
 * in host-visible buffers, one pair per slot so that a host can fill band k+1 while the GPU composites band k. */
#include "lib/lib_internal.h"
#include "sky/composite.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct vksky_composite {
    vksky_renderer *renderer;
    sky_composite c;
    uint32_t slot_count;
    gpu_buffer upload[VKSKY_COMPOSITE_SLOTS_MAX], readback[VKSKY_COMPOSITE_SLOTS_MAX];   /* [0]: the pass's own */
    CompositePush push;
    bool view_set;
};

static void view_in(const vksky_composite_view *a, composite_view *b)
{
    *b = (composite_view){.km_per_unit = a->km_per_unit, .up_axis = a->up_axis,
                          .ground_altitude_km = a->ground_altitude_km, .oriented = a->oriented,
                          .fov_y_deg = a->fov_y_deg, .sun_azimuth_deg = a->sun_azimuth_deg,
                          .sun_elevation_deg = a->sun_elevation_deg, .steps = a->steps, .max_steps = a->max_steps,
                          .steps_ramp_km = a->steps_ramp_km, .sample_offset = a->sample_offset,
                          .step_distribution = a->step_distribution};
    memcpy(b->camera, a->camera, sizeof b->camera);
    memcpy(b->forward, a->forward, sizeof b->forward);
    memcpy(b->right, a->right, sizeof b->right);
    memcpy(b->up, a->up, sizeof b->up);
}

void vksky_composite_view_orient(vksky_composite_view *v, double yaw_deg, double pitch_deg)
{
    if (!v) return;
    composite_view cv;
    view_in(v, &cv);
    composite_view_orient_yaw_pitch(&cv, yaw_deg, pitch_deg);
    memcpy(v->forward, cv.forward, sizeof v->forward);
    memcpy(v->right, cv.right, sizeof v->right);
    memcpy(v->up, cv.up, sizeof v->up);
    v->oriented = true;
}

void vksky_composite_world_to_local(int up_axis, const double world[3], double local[3])
{
    composite_world_to_local(up_axis, world, local);
}

double vksky_composite_view_altitude(const vksky_composite_view *view, const vksky_scene *scene)
{
    if (!view || !scene) return -1.0;
    composite_view v;
    view_in(view, &v);
    CompositePush push;
    return composite_push(&v, scene->o.atmosphere.bottom_radius, 1, 1, &push);
}

static vksky_result refuse(const vksky_context *c, const char *what)
{
    lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR, "vksky_composite_create: %s", what);
    return VKSKY_ERROR_INVALID_ARGUMENT;
}

vksky_result vksky_composite_create(vksky_renderer *renderer, const vksky_composite_desc *desc, vksky_composite **out)
{
    if (out) *out = NULL;
    if (!renderer || !desc || !out) return VKSKY_ERROR_INVALID_ARGUMENT;
    vksky_context *ctx = renderer->ctx;
    if (desc->abi_version != VKSKY_ABI_VERSION) {
        lib_message(ctx->message, ctx->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_composite_create: abi_version %u; this library is ABI %u", desc->abi_version,
                    VKSKY_ABI_VERSION);
        return VKSKY_ERROR_ABI_MISMATCH;
    }
    if (desc->next) return refuse(ctx, "next: NULL (no extension struct is known here)");
    /* A group of three wavelengths a pass renders them in the layers' R, G, B (the host sums the groups); four a
     * pass is the four-wide build, whose fourth wavelength the RGB layers cannot hold. */
    if (renderer->per_pass == 4)
        return refuse(ctx, "a renderer of an RGB scene or of a spectral group of three a pass (not four)");
    if (desc->slots > VKSKY_COMPOSITE_SLOTS_MAX) return refuse(ctx, "slots: 0..2 (0: one)");
    if (desc->volume && (desc->volume_size[0] < 1 || desc->volume_size[1] < 1 || desc->volume_size[2] < 1 ||
                         desc->volume_size[0] > 512 || desc->volume_size[1] > 512 || desc->volume_size[2] > 512 ||
                         !(desc->volume_range_km > 0.0) || !(desc->volume_distribution >= 1.0)))
        return refuse(ctx, "volume: sizes 1..512 each, range_km > 0, distribution >= 1");
    vksky_composite *c = calloc(1, sizeof *c);
    if (!c) return VKSKY_ERROR_OUT_OF_MEMORY;
    c->renderer = renderer;
    c->slot_count = desc->slots ? desc->slots : 1;
    ap_volume_desc vol = {desc->volume_size[0], desc->volume_size[1], desc->volume_size[2],
                          (float)desc->volume_range_km, (float)desc->volume_distribution};
    char err[300];
    const gpu_trace_sink *was = lib_trace_begin(ctx);
    gpu_trap trap;
    if (setjmp(trap.jump)) {
        lib_trace_end(was);
        lib_message(ctx->message, ctx->message_user, VKSKY_SEVERITY_ERROR, "%s", trap.message);
        for (uint32_t s = 1; s < c->slot_count; ++s) {
            if (c->upload[s].buffer) gpu_buffer_destroy(&ctx->gpu, &c->upload[s]);
            if (c->readback[s].buffer) gpu_buffer_destroy(&ctx->gpu, &c->readback[s]);
        }
        sky_composite_destroy(&c->c, &renderer->r);
        free(c);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    int rc = sky_composite_create(&c->c, &renderer->r, desc->width, desc->rows, desc->volume ? &vol : NULL, err,
                                  sizeof err);
    if (rc == 0) {
        c->upload[0] = c->c.upload, c->readback[0] = c->c.readback;
        VkDeviceSize pixels = (VkDeviceSize)desc->width * desc->rows;
        for (uint32_t s = 1; s < c->slot_count; ++s) {   /* as the pass's own pair (sky_composite_create) */
            gpu_buffer_create(&ctx->gpu, &c->upload[s], "composite upload", pixels * 2 * 16,
                              VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
            gpu_buffer_create(&ctx->gpu, &c->readback[s], "aovs readback", pixels * VKSKY_AOV_COUNT * 16,
                              VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        }
    }
    gpu_trap_arm(NULL);
    lib_trace_end(was);
    if (rc != 0) {
        lib_message(ctx->message, ctx->message_user, VKSKY_SEVERITY_ERROR, "%s", err);
        free(c);
        return VKSKY_ERROR_UNSUPPORTED;
    }
    *out = c;
    return VKSKY_SUCCESS;
}

void vksky_composite_destroy(vksky_composite *c)
{
    if (!c) return;
    const gpu_context *g = &c->renderer->ctx->gpu;
    for (uint32_t s = 1; s < c->slot_count; ++s) {
        gpu_buffer_destroy(g, &c->upload[s]);
        gpu_buffer_destroy(g, &c->readback[s]);
    }
    c->c.upload = c->upload[0], c->c.readback = c->readback[0];   /* the pass destroys its own pair */
    sky_composite_destroy(&c->c, &c->renderer->r);
    free(c);
}

vksky_result vksky_composite_set_view(vksky_composite *c, const vksky_composite_view *view, uint32_t whole_height,
                                      uint32_t flags, double *altitude_km)
{
    if (!c || !view || whole_height == 0) return VKSKY_ERROR_INVALID_ARGUMENT;
    composite_view v;
    view_in(view, &v);
    CompositePush push;
    double altitude = composite_push(&v, c->renderer->o.atmosphere.bottom_radius, c->c.width, whole_height, &push);
    if (altitude_km) *altitude_km = altitude;
    if (!(altitude >= 0.0)) {
        const vksky_context *ctx = c->renderer->ctx;
        lib_message(ctx->message, ctx->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_composite_set_view: the camera is inside the planet (%.4g km below the ground)", -altitude);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    if (flags & VKSKY_COMPOSITE_FAST) composite_push_fast(&v, &push);
    /* The sky pass's own altitude, exactly (the --aovs frame: its camera at the world origin). */
    if (flags & VKSKY_COMPOSITE_VIEW_ALTITUDE) push.forward.w = (float)view->altitude_km;
    c->push = push;
    c->view_set = true;
    return VKSKY_SUCCESS;
}

float *vksky_composite_inputs(vksky_composite *c, uint32_t slot)
{
    return c && slot < c->slot_count ? c->upload[slot].mapped : NULL;
}

/* Each sky tile (shared.h) none of whose pixels shows sky (alpha >= 1: the shader's own test), marked in its first
 * pixel's position w, so that the shader need not read the tile's alphas to skip its sky rays. */
static void mark_sky_tiles(float *in, uint32_t width, uint32_t rows)
{
    const uint32_t tile = VKSKY_COMPOSITE_TILE;
    size_t all = (size_t)width * rows * 4;
    for (uint32_t ty = 0; ty < rows; ty += tile)
        for (uint32_t tx = 0; tx < width; tx += tile) {
            bool sky = false;
            for (uint32_t y = ty; y < ty + tile && y < rows && !sky; ++y)
                for (uint32_t x = tx; x < tx + tile && x < width && !sky; ++x)
                    sky = !(in[((size_t)y * width + x) * 4 + 3] >= 1.0f);
            in[all + ((size_t)ty * width + tx) * 4 + 3] = sky ? 1.0f : (float)VKSKY_COMPOSITE_TILE_NO_SKY;
        }
}

vksky_result vksky_composite_record(vksky_composite *c, VkCommandBuffer cmd, const vksky_composite_frame *frame)
{
    if (!c || !cmd || !frame) return VKSKY_ERROR_INVALID_ARGUMENT;
    vksky_context *ctx = c->renderer->ctx;
    const char *bad = !c->view_set                     ? "no view yet (vksky_composite_set_view)"
                      : frame->next                    ? "next: NULL"
                      : frame->slot >= c->slot_count   ? "slot: below the composite's slots"
                      : frame->first_row < 0           ? "first_row: >= 0"
                                                       : NULL;
    if (bad) {
        lib_message(ctx->message, ctx->message_user, VKSKY_SEVERITY_ERROR, "vksky_composite_record: %s", bad);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    mark_sky_tiles(c->upload[frame->slot].mapped, c->c.width, c->c.height);
    c->c.upload = c->upload[frame->slot], c->c.readback = c->readback[frame->slot];
    CompositePush push = c->push;
    push.right.w = (float)frame->first_row;   /* the band's first row (shared.h) */
    const gpu_trace_sink *was = lib_trace_begin(ctx);
    gpu_label_group_begin(&ctx->gpu, cmd, "vksky.composite");
    composite_frame_record(&c->renderer->r, &c->c, cmd, &push, frame->force_luts, frame->follows_frame);
    gpu_label_end(&ctx->gpu, cmd);
    lib_trace_end(was);
    return VKSKY_SUCCESS;
}

const float *vksky_composite_layer(vksky_composite *c, uint32_t slot, uint32_t layer)
{
    if (!c || slot >= c->slot_count || layer >= VKSKY_COMPOSITE_LAYERS) return NULL;
    gpu_buffer_invalidate(&c->renderer->ctx->gpu, &c->readback[slot]);
    return (const float *)c->readback[slot].mapped + (size_t)layer * 4 * c->c.width * c->c.height;
}
