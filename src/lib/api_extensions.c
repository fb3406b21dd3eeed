/* Extension chains (include/vksky.h, "Extension structs"): walking a `next` chain, the explicit quality
 * configuration, the per-pass GPU timings. */
#include "lib/lib_internal.h"
#include "app/quality/quality.h"
#include <string.h>

/* The chain of a renderer desc: each struct's type known and in its place, at most one of each; the quality config
 * (checked against the command line's ranges) in *quality. */
vksky_result lib_renderer_chain(const vksky_context *c, const void *next, const vksky_quality_config **quality,
                                bool *readback, const vksky_display_config **display)
{
    *quality = NULL, *readback = false, *display = NULL;
    for (int depth = 0; next; ++depth) {
        const vksky_chain *link = next;
        if (depth >= 16) {
            lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                        "vksky_renderer_create: the desc's next chain is over 16 structs long (a loop?)");
            return VKSKY_ERROR_INVALID_ARGUMENT;
        }
        bool twice = (link->type == VKSKY_STRUCTURE_TYPE_QUALITY_CONFIG && *quality) ||
                     (link->type == VKSKY_STRUCTURE_TYPE_READBACK_CONFIG && *readback) ||
                     (link->type == VKSKY_STRUCTURE_TYPE_DISPLAY_CONFIG && *display);
        if ((link->type != VKSKY_STRUCTURE_TYPE_QUALITY_CONFIG && link->type != VKSKY_STRUCTURE_TYPE_READBACK_CONFIG &&
             link->type != VKSKY_STRUCTURE_TYPE_DISPLAY_CONFIG) || twice) {
            lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                        "vksky_renderer_create: next chain: structure type %d %s (accepted here: "
                        "VKSKY_STRUCTURE_TYPE_QUALITY_CONFIG, _READBACK_CONFIG and _DISPLAY_CONFIG, each once)",
                        (int)link->type, twice ? "twice" : "is unknown to this library or not a renderer's");
            return VKSKY_ERROR_INVALID_ARGUMENT;
        }
        if (link->type == VKSKY_STRUCTURE_TYPE_QUALITY_CONFIG) *quality = next;
        else if (link->type == VKSKY_STRUCTURE_TYPE_DISPLAY_CONFIG) *display = next;
        else *readback = true;
        next = link->next;
    }
    const vksky_quality_config *q = *quality;
    if (!q) return VKSKY_SUCCESS;
    const char *bad = NULL;
    if ((unsigned)q->sky_mode > VKSKY_SKY_MODE_AUTO) bad = "sky_mode: MARCH, SKYVIEW or AUTO";
    else if ((unsigned)q->sky_pass > VKSKY_SKY_PASS_AUTO) bad = "sky_pass: FRAGMENT, COMPUTE or AUTO";
    else if (q->view_steps < 1 || q->view_steps > 4096) bad = "view_steps: 1..4096";
    else if (q->view_max_steps && (q->view_max_steps < q->view_steps || q->view_max_steps > 4096))
        bad = "view_max_steps: 0, or view_steps..4096";
    else if (!(q->step_distribution >= 1.0 && q->step_distribution <= 4.0)) bad = "step_distribution: 1..4";
    else if (!(q->sample_offset >= 0.0 && q->sample_offset <= 1.0)) bad = "sample_offset: 0..1";
    else if (q->skyview_width < 2 || q->skyview_width > 4096 || q->skyview_height < 2 || q->skyview_height > 4096)
        bad = "skyview_width, skyview_height: 2..4096";
    else if (q->skyview_steps < 1 || q->skyview_steps > 1024) bad = "skyview_steps: 1..1024";
    else if (q->transmittance_width < 2 || q->transmittance_width > 4096 || q->transmittance_height < 2 ||
             q->transmittance_height > 4096)
        bad = "transmittance_width, transmittance_height: 2..4096";
    else if (q->transmittance_steps < 1 || q->transmittance_steps > 4096) bad = "transmittance_steps: 1..4096";
    else if (q->multiscatter_size < 2 || q->multiscatter_size > 1024) bad = "multiscatter_size: 2..1024";
    else if (q->multiscatter_sqrt_dirs < 1 || q->multiscatter_sqrt_dirs > 64) bad = "multiscatter_sqrt_dirs: 1..64";
    else if (q->multiscatter_steps < 1 || q->multiscatter_steps > 4096) bad = "multiscatter_steps: 1..4096";
    else if (!(q->render_scale >= 0.1 && q->render_scale <= 1.0)) bad = "render_scale: 0.1..1";
    else if (q->bloom_mips < 1 || q->bloom_mips > 8) bad = "bloom_mips: 1..8";
    if (bad) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_renderer_create: vksky_quality_config: a value out of range; accepted %s", bad);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    return VKSKY_SUCCESS;
}

vksky_result lib_frame_chain(const vksky_context *c, const void *next, lib_frame_ext *ext)
{
    /* The frame's types in the order of lib_frame_ext's fields; seen[k]: the struct of KNOWN[k], once. */
    static const vksky_structure_type KNOWN[] = {
        VKSKY_STRUCTURE_TYPE_FRAME_VIEW, VKSKY_STRUCTURE_TYPE_AUTO_EXPOSURE, VKSKY_STRUCTURE_TYPE_FRAME_BAND,
        VKSKY_STRUCTURE_TYPE_READBACK_TARGET, VKSKY_STRUCTURE_TYPE_FRAME_DISPLAY, VKSKY_STRUCTURE_TYPE_FRAME_PLACE,
        VKSKY_STRUCTURE_TYPE_FRAME_TIMER, VKSKY_STRUCTURE_TYPE_FRAME_CAPTURE, VKSKY_STRUCTURE_TYPE_FRAME_SWAPCHAIN,
        VKSKY_STRUCTURE_TYPE_FRAME_SPECTRAL_SUM};
    enum { N = sizeof KNOWN / sizeof KNOWN[0] };
    const void *seen[N] = {0};
    for (int depth = 0; next; ++depth) {
        const vksky_chain *link = next;
        int k = 0;
        while (k < N && KNOWN[k] != link->type) ++k;
        bool twice = k < N && seen[k];
        if (depth >= 16 || k == N || twice) {
            lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                        "vksky_record: frame.next: structure type %d %s (accepted here: VKSKY_STRUCTURE_TYPE_FRAME_VIEW, "
                        "VKSKY_STRUCTURE_TYPE_AUTO_EXPOSURE, VKSKY_STRUCTURE_TYPE_FRAME_BAND, "
                        "VKSKY_STRUCTURE_TYPE_READBACK_TARGET, VKSKY_STRUCTURE_TYPE_FRAME_DISPLAY, "
                        "VKSKY_STRUCTURE_TYPE_FRAME_PLACE, VKSKY_STRUCTURE_TYPE_FRAME_TIMER, "
                        "VKSKY_STRUCTURE_TYPE_FRAME_CAPTURE, VKSKY_STRUCTURE_TYPE_FRAME_SWAPCHAIN, "
                        "VKSKY_STRUCTURE_TYPE_FRAME_SPECTRAL_SUM, each once)",
                        (int)link->type,
                        depth >= 16 ? "past 16 links (a loop?)" : twice ? "twice" : "is unknown to this library or not a frame's");
            return VKSKY_ERROR_INVALID_ARGUMENT;
        }
        seen[k] = next;
        next = link->next;
    }
    *ext = (lib_frame_ext){.view = seen[0], .exposure = seen[1], .band = seen[2], .target = seen[3],
                           .display = seen[4], .place = seen[5], .timer = seen[6], .capture = seen[7],
                           .swapchain = seen[8], .spectral_sum = seen[9]};
    const vksky_auto_exposure *e = ext->exposure;
    if (e && (e->slot >= VKSKY_AUTO_EXPOSURE_SLOTS || !(e->ease >= 0.0 && e->ease <= 1e6))) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record: vksky_auto_exposure: slot %u, ease %g; accepted slot 0..%u, ease 0..1 (or more: none)",
                    e->slot, e->ease, VKSKY_AUTO_EXPOSURE_SLOTS - 1);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    const vksky_frame_view *v = ext->view;
    if (v && !(v->yaw_deg >= -360.0 && v->yaw_deg <= 360.0 && v->pitch_deg >= -90.0 && v->pitch_deg <= 90.0 &&
               v->fov_deg >= 1.0 && v->fov_deg <= 170.0)) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record: vksky_frame_view: yaw %g, pitch %g, fov %g; accepted yaw -360..360, pitch -90..90, "
                    "fov 1..170", v->yaw_deg, v->pitch_deg, v->fov_deg);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    return VKSKY_SUCCESS;
}

static const sky_mode_choice MODES[] = {SKY_CHOICE_MARCH, SKY_CHOICE_SKYVIEW, SKY_CHOICE_AUTO};
static const sky_pass_kind PASSES[] = {SKY_PASS_FRAGMENT, SKY_PASS_COMPUTE, SKY_PASS_AUTO};

void lib_quality_from_config(const vksky_quality_config *q, quality_config *out)
{
    *out = (quality_config){
        .name = "host", .mode = MODES[q->sky_mode], .pass_kind = PASSES[q->sky_pass], .steps = (int)q->view_steps,
        .max_steps = (int)q->view_max_steps, .step_distribution = q->step_distribution,
        .sample_offset = q->sample_offset, .skyview_width = (int)q->skyview_width,
        .skyview_height = (int)q->skyview_height, .skyview_steps = (int)q->skyview_steps,
        .transmittance_width = (int)q->transmittance_width, .transmittance_height = (int)q->transmittance_height,
        .transmittance_steps = (int)q->transmittance_steps, .multiscatter_size = (int)q->multiscatter_size,
        .multiscatter_sqrt_dirs = (int)q->multiscatter_sqrt_dirs, .multiscatter_steps = (int)q->multiscatter_steps,
        .lut_f32 = q->lut_f32, .render_scale = q->render_scale, .bloom_mips = (int)q->bloom_mips,
        .bloom_quarter = q->bloom_quarter};
}

vksky_result vksky_quality_config_preset(const char *preset, vksky_quality_config *out)
{
    const quality_config *q = preset ? quality_preset(preset) : NULL;
    if (!q || !out) return VKSKY_ERROR_INVALID_ARGUMENT;
    vksky_sky_mode mode = VKSKY_SKY_MODE_MARCH;
    vksky_sky_pass pass = VKSKY_SKY_PASS_AUTO;
    for (int i = 0; i < 3; ++i) {
        if (MODES[i] == q->mode) mode = (vksky_sky_mode)i;
        if (PASSES[i] == q->pass_kind) pass = (vksky_sky_pass)i;
    }
    *out = (vksky_quality_config){
        .type = VKSKY_STRUCTURE_TYPE_QUALITY_CONFIG, .sky_mode = mode, .sky_pass = pass,
        .view_steps = (uint32_t)q->steps, .view_max_steps = (uint32_t)q->max_steps,
        .step_distribution = q->step_distribution, .sample_offset = q->sample_offset,
        .skyview_width = (uint32_t)q->skyview_width, .skyview_height = (uint32_t)q->skyview_height,
        .skyview_steps = (uint32_t)q->skyview_steps, .transmittance_width = (uint32_t)q->transmittance_width,
        .transmittance_height = (uint32_t)q->transmittance_height,
        .transmittance_steps = (uint32_t)q->transmittance_steps, .multiscatter_size = (uint32_t)q->multiscatter_size,
        .multiscatter_sqrt_dirs = (uint32_t)q->multiscatter_sqrt_dirs,
        .multiscatter_steps = (uint32_t)q->multiscatter_steps, .lut_f32 = q->lut_f32,
        .render_scale = q->render_scale, .bloom_mips = (uint32_t)q->bloom_mips, .bloom_quarter = q->bloom_quarter};
    return VKSKY_SUCCESS;
}

/* A timer's last recorded results as the API's entries (the frame's timer, or the compute queue's LUT timer). */
vksky_result lib_timings_read(vksky_renderer *renderer, gpu_timer *t, vksky_pass_timing *out, uint32_t capacity,
                              uint32_t *count)
{
    *count = 0;
    if (!t->enabled) return VKSKY_ERROR_UNSUPPORTED;
    double ms[GPU_TIMER_MAX];
    gpu_trap trap;
    if (setjmp(trap.jump)) {
        lib_message(renderer->ctx->message, renderer->ctx->message_user, VKSKY_SEVERITY_ERROR, "%s", trap.message);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    uint32_t n = gpu_timer_read(&renderer->ctx->gpu, t, ms);
    gpu_trap_arm(NULL);
    for (uint32_t i = 0; i < n && i < capacity; ++i) out[i] = (vksky_pass_timing){t->names[i], ms[i]};
    *count = n;
    return VKSKY_SUCCESS;
}

vksky_result vksky_renderer_get_timings(vksky_renderer *renderer, vksky_pass_timing *out, uint32_t capacity,
                                        uint32_t *count)
{
    if (!renderer || !count || (capacity && !out)) return VKSKY_ERROR_INVALID_ARGUMENT;
    return lib_timings_read(renderer, &renderer->r.timer, out, capacity, count);
}

vksky_result vksky_renderer_get_lut_timings(vksky_renderer *renderer, vksky_pass_timing *out, uint32_t capacity,
                                            uint32_t *count)
{
    if (!renderer || !count || (capacity && !out)) return VKSKY_ERROR_INVALID_ARGUMENT;
    *count = 0;
    if (!renderer->ctx->gpu.compute_queue) {
        lib_message(renderer->ctx->message, renderer->ctx->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_renderer_get_lut_timings: the context has no compute queue (vksky_get_timings has the LUT "
                    "passes of a frame that built them)");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    return lib_timings_read(renderer, &renderer->r.lut_timer, out, capacity, count);
}
