/* Readback slots (include/vksky.h, "Readback slots"): a host's readback ring names the pair of host-visible buffers
 * each frame's copies go to; the ring itself (slots in turn, command buffers, fences, waits) is the host's. And the
 * renderer's costs for the command line's --timings (vksky_renderer_get_stats). */
#include "lib/lib_internal.h"

void lib_readback_slots_init(vksky_renderer *r)
{
    r->slot_count = r->readback ? 1 : 0;
    if (!r->readback) return;
    r->slot_linear[0] = r->r.readback_linear, r->slot_display[0] = r->r.readback_display;
}

void lib_readback_slots_destroy(vksky_renderer *r)
{
    if (!r->readback) return;
    for (uint32_t s = 1; s < r->slot_count; ++s) {
        gpu_buffer_destroy(r->r.ctx, &r->slot_linear[s]);
        gpu_buffer_destroy(r->r.ctx, &r->slot_display[s]);
    }
    r->slot_count = 1;
    /* The renderer destroys its own pair. */
    r->r.readback_linear = r->slot_linear[0], r->r.readback_display = r->slot_display[0];
}

void lib_readback_select(vksky_renderer *r, uint32_t slot)
{
    r->r.readback_linear = r->slot_linear[slot], r->r.readback_display = r->slot_display[slot];
}

vksky_result vksky_renderer_set_readback_slots(vksky_renderer *renderer, uint32_t count)
{
    if (!renderer) return VKSKY_ERROR_INVALID_ARGUMENT;
    vksky_context *c = renderer->ctx;
    if (!renderer->readback || count < 1 || count > VKSKY_READBACK_SLOTS_MAX) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_renderer_set_readback_slots: %u slots%s; accepted 1..%u on a renderer with a "
                    "vksky_readback_config", count, renderer->readback ? "" : " without a readback config",
                    VKSKY_READBACK_SLOTS_MAX);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    gpu_trap trap;
    if (setjmp(trap.jump)) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR, "%s", trap.message);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    lib_readback_slots_destroy(renderer);
    /* The other slots: the same sizes as the renderer's own pair (as the command line's ring made them). */
    for (uint32_t s = 1; s < count; ++s) {
        gpu_buffer_create(renderer->r.ctx, &renderer->slot_linear[s], "readback linear (ring)",
                          renderer->slot_linear[0].size, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        gpu_buffer_create(renderer->r.ctx, &renderer->slot_display[s], "readback display (ring)",
                          renderer->slot_display[0].size, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        renderer->slot_count = s + 1;
    }
    gpu_trap_arm(NULL);
    return VKSKY_SUCCESS;
}

vksky_result vksky_renderer_get_readback_slot(vksky_renderer *renderer, uint32_t slot, vksky_readback *out)
{
    if (!renderer || !out || !renderer->readback || slot >= renderer->slot_count) return VKSKY_ERROR_INVALID_ARGUMENT;
    /* Another thread may be recording into other slots: only this slot's buffers are touched here. */
    const gpu_buffer *linear = &renderer->slot_linear[slot], *display = &renderer->slot_display[slot];
    gpu_trap trap;   /* thread-local: this thread's own */
    if (setjmp(trap.jump)) {
        lib_message(renderer->ctx->message, renderer->ctx->message_user, VKSKY_SEVERITY_ERROR, "%s", trap.message);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    /* The frame's last barrier made the copies available to HOST_READ; the host waited for its fence; on
     * non-coherent memory the invalidate makes them visible. */
    gpu_buffer_invalidate(renderer->r.ctx, linear);
    gpu_buffer_invalidate(renderer->r.ctx, display);
    gpu_trap_arm(NULL);
    *out = (vksky_readback){.linear_rgba16f = linear->mapped, .display_rgba8 = display->mapped,
                            .width = renderer->desc.width, .height = renderer->desc.height};
    return VKSKY_SUCCESS;
}

/* The report's states are the renderer's, in its order (sky/renderer.h). */
_Static_assert(SKY_LUT_CACHE_OFF == (int)VKSKY_LUT_CACHE_OFF && SKY_LUT_CACHE_HIT == (int)VKSKY_LUT_CACHE_HIT &&
               SKY_LUT_CACHE_MISS == (int)VKSKY_LUT_CACHE_COMPUTED && SKY_LUT_CACHE_STORED == (int)VKSKY_LUT_CACHE_STORED &&
               SKY_LUT_CACHE_UNWRITABLE == (int)VKSKY_LUT_CACHE_NOT_STORED, "the LUT cache's states");

vksky_result vksky_renderer_get_stats(const vksky_renderer *renderer, vksky_renderer_stats *out)
{
    if (!renderer || !out) return VKSKY_ERROR_INVALID_ARGUMENT;
    *out = (vksky_renderer_stats){.pipelines_ms = renderer->r.pipelines_ms,
                                  .variant_builds = (uint32_t)renderer->r.variant_builds,
                                  .lut_cache = (vksky_lut_cache_state)renderer->r.lut_cache};
    return VKSKY_SUCCESS;
}
