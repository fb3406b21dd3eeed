#include "sky/passes.h"
#include "sky/shaders.h"

void luts_create(sky_luts *l, const pass_shared *s)
{
    const gpu_context *ctx = s->ctx;
    /* Written by compute (storage), then sampled by compute (multiscatter) and fragment (sky); copied out by tests. */
    VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    gpu_image_create(ctx, &l->transmittance, "transmittance LUT", HDR_FORMAT, TRANSMITTANCE_LUT_WIDTH,
                     TRANSMITTANCE_LUT_HEIGHT, 1, usage);
    gpu_image_create(ctx, &l->multiscatter, "multiscatter LUT", HDR_FORMAT, MULTISCATTER_LUT_SIZE,
                     MULTISCATTER_LUT_SIZE, 1, usage);

    VkDescriptorType t_types[] = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
    l->transmittance_set_layout = gpu_set_layout(ctx, t_types, 2, VK_SHADER_STAGE_COMPUTE_BIT, "transmittance set layout");
    l->transmittance_layout = gpu_pipeline_layout(ctx, l->transmittance_set_layout, 0, 0, "transmittance layout");
    VkShaderModule t_mod = gpu_shader_module(ctx, spirv_transmittance_lut.code, spirv_transmittance_lut.size, "transmittance_lut.comp");
    l->transmittance_pipeline = gpu_compute_pipeline(ctx, l->transmittance_layout, t_mod, "transmittance LUT");
    vkDestroyShaderModule(ctx->device, t_mod, NULL);
    l->transmittance_set = gpu_alloc_set(ctx, s->pool, l->transmittance_set_layout, "transmittance set");
    gpu_write_uniform(ctx, l->transmittance_set, 0, s->atmosphere_ubo.buffer, sizeof(AtmosphereParams));
    gpu_write_storage(ctx, l->transmittance_set, 1, l->transmittance.view);

    VkDescriptorType m_types[] = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                  VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
    l->multiscatter_set_layout = gpu_set_layout(ctx, m_types, 3, VK_SHADER_STAGE_COMPUTE_BIT, "multiscatter set layout");
    l->multiscatter_layout = gpu_pipeline_layout(ctx, l->multiscatter_set_layout, 0, 0, "multiscatter layout");
    VkShaderModule m_mod = gpu_shader_module(ctx, spirv_multiscatter_lut.code, spirv_multiscatter_lut.size, "multiscatter_lut.comp");
    l->multiscatter_pipeline = gpu_compute_pipeline(ctx, l->multiscatter_layout, m_mod, "multiscatter LUT");
    vkDestroyShaderModule(ctx->device, m_mod, NULL);
    l->multiscatter_set = gpu_alloc_set(ctx, s->pool, l->multiscatter_set_layout, "multiscatter set");
    gpu_write_uniform(ctx, l->multiscatter_set, 0, s->atmosphere_ubo.buffer, sizeof(AtmosphereParams));
    gpu_write_sampled(ctx, l->multiscatter_set, 1, l->transmittance.view, s->linear_clamp);
    gpu_write_storage(ctx, l->multiscatter_set, 2, l->multiscatter.view);
}

void luts_destroy(sky_luts *l, const pass_shared *s)
{
    VkDevice d = s->ctx->device;
    vkDestroyPipeline(d, l->transmittance_pipeline, NULL);
    vkDestroyPipeline(d, l->multiscatter_pipeline, NULL);
    vkDestroyPipelineLayout(d, l->transmittance_layout, NULL);
    vkDestroyPipelineLayout(d, l->multiscatter_layout, NULL);
    vkDestroyDescriptorSetLayout(d, l->transmittance_set_layout, NULL);
    vkDestroyDescriptorSetLayout(d, l->multiscatter_set_layout, NULL);
    gpu_image_destroy(s->ctx, &l->transmittance);
    gpu_image_destroy(s->ctx, &l->multiscatter);
}

void luts_record_transmittance(const sky_luts *l, VkCommandBuffer cmd)
{
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, l->transmittance_pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, l->transmittance_layout, 0, 1, &l->transmittance_set, 0, NULL);
    vkCmdDispatch(cmd, TRANSMITTANCE_LUT_WIDTH / 8, TRANSMITTANCE_LUT_HEIGHT / 8, 1);
}

void luts_record_multiscatter(const sky_luts *l, VkCommandBuffer cmd)
{
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, l->multiscatter_pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, l->multiscatter_layout, 0, 1, &l->multiscatter_set, 0, NULL);
    vkCmdDispatch(cmd, MULTISCATTER_LUT_SIZE / 8, MULTISCATTER_LUT_SIZE / 8, 1);
}
