/* ABI 3: what an interactive window gives each frame (include/vksky.h, "an interactive window's frames"): the tone
 * map and bloom its keys switch, where its fly camera is, a timer per frame in flight, the screenshot's copy and a
 * swapchain image's uses. Each is a value of the frame: no pipeline is rebuilt, nothing is allocated per frame (a
 * slot's timer and the capture buffer are made at their first frame). */
#include "lib/lib_internal.h"
#include <math.h>

_Static_assert(VKSKY_TONEMAP_OPERATOR_CLAMP == VKSKY_TONEMAP_CLAMP && VKSKY_TONEMAP_OPERATOR_REINHARD ==
               VKSKY_TONEMAP_REINHARD && VKSKY_TONEMAP_OPERATOR_ACES == VKSKY_TONEMAP_ACES,
               "the API's tone map operators are the shaders'");

static vksky_result refuse(const vksky_renderer *r, const char *what)
{
    lib_message(r->ctx->message, r->ctx->message_user, VKSKY_SEVERITY_ERROR, "vksky_record: %s", what);
    return VKSKY_ERROR_INVALID_ARGUMENT;
}

/* The window's values checked: any of them wants a DISPLAY frame into the host's image (the readback renderer's
 * frames are the command line's, which set none of them). */
vksky_result lib_window_check(const vksky_renderer *r, const lib_frame_ext *e)
{
    bool any = e->display || e->place || e->timer || e->capture || e->swapchain;
    if (!any) return VKSKY_SUCCESS;
    if (r->desc.output != VKSKY_OUTPUT_DISPLAY)
        return refuse(r, "vksky_frame_display, _place, _timer, _capture and _swapchain are for output DISPLAY");
    /* A readback renderer takes this frame's tone map and bloom switch (the command line's spectral groups render a
     * bloom-free frame for the host's meter: app/runs/spectral_host.c), not the window's other values. */
    if (r->readback && (e->place || e->timer || e->capture || e->swapchain))
        return refuse(r, "vksky_frame_place, _timer, _capture and _swapchain are for output DISPLAY into the host's "
                         "image (no vksky_readback_config)");
    if (e->display && (unsigned)e->display->tonemap > VKSKY_TONEMAP_OPERATOR_ACES)
        return refuse(r, "vksky_frame_display: tonemap; accepted CLAMP, REINHARD or ACES");
    if (e->display && e->display->bloom && !r->desc.bloom)
        return refuse(r, "vksky_frame_display: bloom on; accepted only on a renderer made with desc.bloom (its chain)");
    const vksky_frame_place *p = e->place;
    if (p && !e->view) return refuse(r, "vksky_frame_place: accepted only beside a vksky_frame_view");
    if (p && !(p->altitude_km >= 0.0 && p->altitude_km <= 1e6 && p->sun_azimuth_deg >= -720.0 &&
               p->sun_azimuth_deg <= 720.0 && p->sun_elevation_deg >= -90.0 && p->sun_elevation_deg <= 90.0))
        return refuse(r, "vksky_frame_place: accepted altitude_km 0..1e6, sun_azimuth_deg -720..720, "
                         "sun_elevation_deg -90..90");
    if (e->timer && e->timer->slot >= VKSKY_TIMER_SLOTS)
        return refuse(r, "vksky_frame_timer: slot; accepted 0..VKSKY_TIMER_SLOTS-1");
    return VKSKY_SUCCESS;
}

vksky_result lib_window_apply(vksky_renderer *r, const lib_frame_ext *e, sky_view *v, frame_desc *f,
                              frame_target *target)
{
    vksky_result res = lib_window_check(r, e);
    if (res != VKSKY_SUCCESS || !(e->display || e->place || e->timer || e->capture || e->swapchain)) return res;
    if (e->display) v->tonemap = (int)e->display->tonemap, v->bloom = e->display->bloom;
    /* The fly camera's place as the window's own view holds it: the same doubles, so the same rays. */
    if (e->place)
        v->altitude_km = e->place->altitude_km, v->sun_azimuth_deg = e->place->sun_azimuth_deg,
        v->sun_elevation_deg = e->place->sun_elevation_deg;
    if (e->swapchain) {
        /* The window's uses and names: acquired (its wait stage) before, presented after (frame.c step 6). */
        target->host_uses = false;
        target->before = GPU_USAGE_ACQUIRED, target->after = GPU_USAGE_PRESENT;
    }
    gpu_trap trap;   /* the timer's pool or the capture buffer may fail to be made: an error, not an exit */
    if (setjmp(trap.jump)) {
        lib_message(r->ctx->message, r->ctx->message_user, VKSKY_SEVERITY_ERROR, "vksky_record: %s", trap.message);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    if (e->timer) {
        uint32_t s = e->timer->slot;
        if (!r->timer_made[s]) gpu_timer_create(r->r.ctx, &r->timers[s]), r->timer_made[s] = true;
        f->timer = &r->timers[s];
        r->timer_unread[s] = true;
    }
    if (e->capture) {
        VkDeviceSize size = (VkDeviceSize)r->desc.width * r->desc.height * 4;
        if (!r->capture.size)
            gpu_buffer_create(r->r.ctx, &r->capture, "capture", size, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        target->capture = &r->capture;
        r->captured = true;
    }
    gpu_trap_arm(NULL);
    return VKSKY_SUCCESS;
}

void lib_window_destroy(vksky_renderer *r, bool timers)
{
    for (uint32_t s = 0; timers && s < VKSKY_TIMER_SLOTS; ++s)
        if (r->timer_made[s]) gpu_timer_destroy(r->r.ctx, &r->timers[s]), r->timer_made[s] = false;
    if (r->capture.size) gpu_buffer_destroy(r->r.ctx, &r->capture);
    r->capture = (gpu_buffer){0}, r->captured = false;
}
vksky_result vksky_renderer_get_slot_timings(vksky_renderer *renderer, uint32_t slot, vksky_pass_timing *out,
                                             uint32_t capacity, uint32_t *count)
{
    if (!renderer || !count || (capacity && !out) || slot >= VKSKY_TIMER_SLOTS) return VKSKY_ERROR_INVALID_ARGUMENT;
    *count = 0;
    if (!renderer->timer_made[slot] || !renderer->timer_unread[slot]) return VKSKY_SUCCESS;
    gpu_timer *t = &renderer->timers[slot];
    if (!t->enabled) return VKSKY_ERROR_UNSUPPORTED;
    vksky_result res = lib_timings_read(renderer, t, out, capacity, count);
    if (res == VKSKY_SUCCESS) renderer->timer_unread[slot] = false;   /* a failed read leaves it to read again */
    return res;
}

vksky_result vksky_renderer_get_capture(vksky_renderer *renderer, vksky_readback *out)
{
    if (!renderer || !out || !renderer->captured) return VKSKY_ERROR_INVALID_ARGUMENT;
    gpu_trap trap;
    if (setjmp(trap.jump)) {
        lib_message(renderer->ctx->message, renderer->ctx->message_user, VKSKY_SEVERITY_ERROR, "%s", trap.message);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    /* capture.to_host made the copy available to HOST_READ; on non-coherent memory the invalidate makes it visible. */
    gpu_buffer_invalidate(renderer->r.ctx, &renderer->capture);
    gpu_trap_arm(NULL);
    *out = (vksky_readback){.linear_rgba16f = NULL, .display_rgba8 = renderer->capture.mapped,
                            .width = renderer->desc.width, .height = renderer->desc.height};
    return VKSKY_SUCCESS;
}
