/* The spectral groups summed on the GPU through the API (include/vksky.h "ABI 4"; sky/spectral_sum.h): the sum's
 * handle, and the step a group's frame records in place of its readback copies (api_record.c). */
#include "lib/lib_internal.h"
#include "gpu/fail.h"
#include <math.h>
#include <setjmp.h>
#include <stdlib.h>

vksky_result vksky_spectral_sum_create(vksky_context *context, uint32_t width, uint32_t height,
                                       vksky_spectral_sum **out)
{
    if (out) *out = NULL;
    if (!context || !out || width == 0 || height == 0 || width > 16384 || height > 16384) {
        if (context)
            lib_message(context->message, context->message_user, VKSKY_SEVERITY_ERROR,
                        "vksky_spectral_sum_create: %ux%u; accepted 1..16384 each, and an output pointer", width, height);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    vksky_spectral_sum *sum = calloc(1, sizeof *sum);
    if (!sum) return VKSKY_ERROR_OUT_OF_MEMORY;
    sum->ctx = context;
    const gpu_trace_sink *was = lib_trace_begin(context);
    gpu_trap trap;
    if (setjmp(trap.jump)) {
        lib_trace_end(was);
        lib_message(context->message, context->message_user, VKSKY_SEVERITY_ERROR, "%s", trap.message);
        spectral_sum_destroy(&sum->s);
        free(sum);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    spectral_sum_create(&sum->s, &context->gpu, width, height);
    gpu_trap_arm(NULL);
    lib_trace_end(was);
    context->renderers++;   /* the context's destroy waits for it as for a renderer */
    *out = sum;
    return VKSKY_SUCCESS;
}

void vksky_spectral_sum_destroy(vksky_spectral_sum *sum)
{
    if (!sum) return;
    spectral_sum_destroy(&sum->s);
    sum->ctx->renderers--;
    free(sum);
}

vksky_result vksky_spectral_sum_get(vksky_spectral_sum *sum, const float **rgba32f)
{
    if (!sum || !rgba32f) return VKSKY_ERROR_INVALID_ARGUMENT;
    gpu_buffer_invalidate(&sum->ctx->gpu, &sum->s.resolved);
    *rgba32f = sum->s.resolved.mapped;
    return VKSKY_SUCCESS;
}

vksky_result lib_spectral_sum_step(const vksky_renderer *r, const vksky_frame_spectral_sum *e, spectral_sum_step *out)
{
    const vksky_context *c = r->ctx;
    const char *bad = NULL;
    if (!e->sum || e->sum->ctx != c) bad = "a sum of the renderer's context";
    else if (!r->readback || !r->per_pass) bad = "a renderer with a spectral group's scene and a vksky_readback_config";
    else if (e->sum->s.extent.width != r->desc.width || e->sum->s.extent.height != r->desc.height)
        bad = "a sum of the renderer's size";
    else if (e->group >= VKSKY_SPECTRAL_SUM_GROUPS_MAX) bad = "group 0..16";
    if (bad) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_record: vksky_frame_spectral_sum: needs %s", bad);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    for (int k = 0; k < 4; ++k)
        for (int q = 0; q < 3; ++q)
            if (!isfinite(e->xyz_weights[k][q])) {
                lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                            "vksky_record: vksky_frame_spectral_sum: a weight is not a finite number");
                return VKSKY_ERROR_INVALID_ARGUMENT;
            }
    *out = (spectral_sum_step){.sum = &e->sum->s, .group = e->group};
    /* Three to a pass: the fourth channel is the composite's coverage (its weight 0), the resolve's alpha. */
    spectral_sum_push_fill(&out->push, e->xyz_weights, e->first, e->last, r->per_pass == 3, r->desc.width);
    return VKSKY_SUCCESS;
}
