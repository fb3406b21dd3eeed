#include "sky/passes.h"
#include "sky/shaders.h"
#include "sky/tonemap_regions.h"

void tonemap_create(tonemap_pass *t, const pass_shared *s, VkImageView hdr_view, VkImageView bloom_view,
                    VkFormat display_format, bool composite)
{
    const gpu_context *ctx = s->ctx;
    t->composite = composite;
    /* The meter's buffer: auto exposure's multiplier (renderer.c points it at the meter). */
    const gpu_slot slots[] = {{VKSKY_BINDING_POST_SOURCE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                              {VKSKY_BINDING_POST_MIP, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                              {VKSKY_BINDING_METER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    t->set_layout = gpu_set_layout(ctx, slots, 3, VK_SHADER_STAGE_FRAGMENT_BIT, "tonemap set layout");
    t->layout = gpu_pipeline_layout(ctx, t->set_layout, sizeof(TonemapPush), VK_SHADER_STAGE_FRAGMENT_BIT, "tonemap layout");
    /* The four-wide spectral build's composite carries the HDR texel's four wavelengths. */
    const sky_spirv *spv = composite ? (s->spectral4 ? &spirv_tonemap_composite_s4 : &spirv_tonemap_composite) : &spirv_tonemap;
    VkShaderModule fs = gpu_shader_module(ctx, spv->code, spv->size, composite ? "tonemap_composite.frag" : "tonemap.frag");
    t->formats[0] = display_format, t->formats[1] = HDR_FORMAT;
    t->pipeline = gpu_fullscreen_pipeline(ctx, t->layout, s->fullscreen_vs, fs, t->formats, composite ? 2 : 1,
                                          GPU_BLEND_NONE, "tonemap");
    /* The far variants come at their first use (tonemap_record): the module stays, and the vertex shader is the
     * renderer's (destroyed after the passes). */
    t->ctx = ctx, t->vs = s->fullscreen_vs, t->fs = fs;
    t->far_pipeline[0] = t->far_pipeline[1] = VK_NULL_HANDLE;
    t->set = gpu_alloc_set(ctx, s->pool, t->set_layout, "tonemap set");
    gpu_write_sampled(ctx, t->set, VKSKY_BINDING_POST_SOURCE, hdr_view, s->linear_clamp);
    gpu_write_sampled(ctx, t->set, VKSKY_BINDING_POST_MIP, bloom_view, s->linear_clamp);
}

void tonemap_destroy(tonemap_pass *t, const pass_shared *s)
{
    vkDestroyPipeline(s->ctx->device, t->pipeline, gpu_allocator(s->ctx->device));
    for (int k = 0; k < 2; ++k) vkDestroyPipeline(s->ctx->device, t->far_pipeline[k], gpu_allocator(s->ctx->device));
    vkDestroyShaderModule(s->ctx->device, t->fs, gpu_allocator(s->ctx->device));
    vkDestroyPipelineLayout(s->ctx->device, t->layout, gpu_allocator(s->ctx->device));
    vkDestroyDescriptorSetLayout(s->ctx->device, t->set_layout, gpu_allocator(s->ctx->device));
}

/* A far-only variant (HDR_FAR 1, 2: the horizon path compiled out, for the regions away from it). */
static VkPipeline far_pipeline(tonemap_pass *t, int hdr_full_size)
{
    if (!t->far_pipeline[hdr_full_size]) {
        int32_t far = hdr_full_size + 1;
        VkSpecializationMapEntry entry = {VKSKY_SPEC_TONEMAP_FAR, 0, sizeof far};
        VkSpecializationInfo spec = {1, &entry, sizeof far, &far};
        t->far_pipeline[hdr_full_size] = gpu_fullscreen_pipeline_spec(
            t->ctx, t->layout, t->vs, t->fs, &spec, t->formats, t->composite ? 2 : 1, GPU_BLEND_NONE,
            hdr_full_size ? "tonemap (far, scale 1)" : "tonemap (far)");
    }
    return t->far_pipeline[hdr_full_size];
}

void tonemap_record(tonemap_pass *t, VkCommandBuffer cmd, VkExtent2D extent, VkImageView display,
                    VkImageView composite, const TonemapPush *push, const tonemap_regions *regions,
                    bool hdr_full_size)
{
    gpu_attachment targets[2] = {{display, VK_ATTACHMENT_LOAD_OP_DONT_CARE}, {composite, VK_ATTACHMENT_LOAD_OP_DONT_CARE}};
    gpu_begin_rendering(cmd, extent, targets, t->composite ? 2 : 1);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, t->layout, 0, 1, &t->set, 0, NULL);
    vkCmdPushConstants(cmd, t->layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof *push, push);
    if (!regions) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, t->pipeline);
        vkCmdDraw(cmd, 3, 1, 0, 0);
    }
    /* The far regions first, then the horizon's: one pipeline switch. Scissors do not overlap: every pixel is
     * written once, by the path the full shader would take for it. */
    for (int pass = 0; regions && pass < 2; ++pass) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pass ? t->pipeline : far_pipeline(t, hdr_full_size));
        for (uint32_t i = 0; i < regions->count; ++i) {
            if (regions->region[i].horizon != (pass == 1)) continue;
            vkCmdSetScissor(cmd, 0, 1, &regions->region[i].rect);
            vkCmdDraw(cmd, 3, 1, 0, 0);
        }
    }
    vkCmdEndRendering(cmd);
}
