#include "sky/passes.h"
#include "sky/shaders.h"

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
    VkFormat formats[2] = {display_format, HDR_FORMAT};
    t->pipeline = gpu_fullscreen_pipeline(ctx, t->layout, s->fullscreen_vs, fs, formats, composite ? 2 : 1,
                                          GPU_BLEND_NONE, "tonemap");
    vkDestroyShaderModule(ctx->device, fs, gpu_allocator(ctx->device));
    t->set = gpu_alloc_set(ctx, s->pool, t->set_layout, "tonemap set");
    gpu_write_sampled(ctx, t->set, VKSKY_BINDING_POST_SOURCE, hdr_view, s->linear_clamp);
    gpu_write_sampled(ctx, t->set, VKSKY_BINDING_POST_MIP, bloom_view, s->linear_clamp);
}

void tonemap_destroy(tonemap_pass *t, const pass_shared *s)
{
    vkDestroyPipeline(s->ctx->device, t->pipeline, gpu_allocator(s->ctx->device));
    vkDestroyPipelineLayout(s->ctx->device, t->layout, gpu_allocator(s->ctx->device));
    vkDestroyDescriptorSetLayout(s->ctx->device, t->set_layout, gpu_allocator(s->ctx->device));
}

void tonemap_record(const tonemap_pass *t, VkCommandBuffer cmd, VkExtent2D extent, VkImageView display,
                    VkImageView composite, const TonemapPush *push)
{
    gpu_attachment targets[2] = {{display, VK_ATTACHMENT_LOAD_OP_DONT_CARE}, {composite, VK_ATTACHMENT_LOAD_OP_DONT_CARE}};
    gpu_begin_rendering(cmd, extent, targets, t->composite ? 2 : 1);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, t->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, t->layout, 0, 1, &t->set, 0, NULL);
    vkCmdPushConstants(cmd, t->layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof *push, push);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
}
