#include "sky/passes.h"
#include "sky/shaders.h"

void sky_pass_create(sky_pass *p, const pass_shared *s, const sky_luts *luts)
{
    const gpu_context *ctx = s->ctx;
    VkDescriptorType types[] = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
    p->set_layout = gpu_set_layout(ctx, types, 3, VK_SHADER_STAGE_FRAGMENT_BIT, "sky set layout");
    p->layout = gpu_pipeline_layout(ctx, p->set_layout, sizeof(SkyPush), VK_SHADER_STAGE_FRAGMENT_BIT, "sky layout");
    VkShaderModule fs = gpu_shader_module(ctx, spirv_sky_frag.code, spirv_sky_frag.size, "sky.frag");
    VkFormat format = HDR_FORMAT;
    p->pipeline = gpu_fullscreen_pipeline(ctx, p->layout, s->fullscreen_vs, fs, &format, 1, GPU_BLEND_NONE, "sky");
    vkDestroyShaderModule(ctx->device, fs, NULL);
    p->set = gpu_alloc_set(ctx, s->pool, p->set_layout, "sky set");
    gpu_write_uniform(ctx, p->set, 0, s->atmosphere_ubo.buffer, sizeof(AtmosphereParams));
    gpu_write_sampled(ctx, p->set, 1, luts->transmittance.view, s->linear_clamp);
    gpu_write_sampled(ctx, p->set, 2, luts->multiscatter.view, s->linear_clamp);
}

void sky_pass_destroy(sky_pass *p, const pass_shared *s)
{
    vkDestroyPipeline(s->ctx->device, p->pipeline, NULL);
    vkDestroyPipelineLayout(s->ctx->device, p->layout, NULL);
    vkDestroyDescriptorSetLayout(s->ctx->device, p->set_layout, NULL);
}

void sky_pass_record(const sky_pass *p, VkCommandBuffer cmd, const gpu_image *hdr, const SkyPush *push)
{
    /* DONT_CARE: every pixel is written. */
    gpu_attachment target = {hdr->view, VK_ATTACHMENT_LOAD_OP_DONT_CARE};
    gpu_begin_rendering(cmd, hdr->extent, &target, 1);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p->layout, 0, 1, &p->set, 0, NULL);
    vkCmdPushConstants(cmd, p->layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof *push, push);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
}
