#include "sky/passes.h"
#include "sky/shaders.h"

static VkPipeline compute_pipeline(const pass_shared *s, VkPipelineLayout layout, const sky_spirv *spv, const char *name)
{
    const gpu_context *ctx = s->ctx;
    VkShaderModule m = gpu_shader_module(ctx, spv->code, spv->size, name);
    VkPipeline p = gpu_compute_pipeline_spec(ctx, layout, m, s->spec, name);
    vkDestroyShaderModule(ctx->device, m, gpu_allocator(ctx->device));
    return p;
}

void luts_create(sky_luts *l, const pass_shared *s, const sky_lut_quality *q, bool multiscatter, bool ground)
{
    *l = (sky_luts){0};
    const gpu_context *ctx = s->ctx;
    VkFormat format = q->lut_f32 ? VK_FORMAT_R32G32B32A32_SFLOAT : HDR_FORMAT;
    /* Written by compute (storage), then sampled by compute and fragment shaders; copied out by tests and the LUT
     * cache, copied in by the LUT cache (sky/lut_cache.h). */
    VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                              VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    /* The four-wide build (s->spectral4): its own SPIR-V, and the atlas's D in a fourth part (Psi takes all four
     * channels of the first). */
    bool s4 = s->spectral4;
    l->multiscatter_parts = s4 ? VKSKY_MULTISCATTER_PARTS4 : VKSKY_MULTISCATTER_PARTS;
    gpu_image_create(ctx, &l->transmittance, "transmittance LUT", format, (uint32_t)q->transmittance_width,
                     (uint32_t)q->transmittance_height, 1, usage);
    if (multiscatter)
        /* VKSKY_MULTISCATTER_PARTS N x N parts side by side: Psi (and D), the second bounce's other moments, its
         * zonal moments (one image, one descriptor, one barrier; the texel-centre sub-UV keeps each part's
         * bilinear taps inside it). */
        gpu_image_create(ctx, &l->multiscatter, "multiscatter LUT", format,
                         l->multiscatter_parts * (uint32_t)q->multiscatter_size, (uint32_t)q->multiscatter_size, 1,
                         usage);
    l->multiscatter_view = multiscatter ? l->multiscatter.view : l->transmittance.view;
    gpu_image_create(ctx, &l->skyview, "skyview LUT", HDR_FORMAT, (uint32_t)q->skyview_width,
                     (uint32_t)q->skyview_height, 1, usage);

    const VkDescriptorType UBO = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, SAMPLED = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                           STORAGE = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    /* Binding numbers: shaders/glsl/bindings.h, one slot per resource in every pass. */
    const gpu_slot t_slots[] = {{VKSKY_BINDING_ATMOSPHERE, UBO}, {VKSKY_BINDING_OUTPUT, STORAGE}};
    l->transmittance_set_layout = gpu_set_layout(ctx, t_slots, 2, VK_SHADER_STAGE_COMPUTE_BIT, "transmittance set layout");
    l->transmittance_layout = gpu_pipeline_layout(ctx, l->transmittance_set_layout, 0, 0, "transmittance layout");
    l->transmittance_spv = s4 ? (q->lut_f32 ? &spirv_transmittance_lut_f32_s4 : &spirv_transmittance_lut_s4)
                              : q->lut_f32 ? &spirv_transmittance_lut_f32 : &spirv_transmittance_lut;
    l->transmittance_set = gpu_alloc_set(ctx, s->pool, l->transmittance_set_layout, "transmittance set");
    gpu_write_uniform(ctx, l->transmittance_set, VKSKY_BINDING_ATMOSPHERE, s->atmosphere_ubo.buffer,
                      sizeof(AtmosphereParams));
    gpu_write_storage(ctx, l->transmittance_set, VKSKY_BINDING_OUTPUT, l->transmittance.view);

    /* The ground-irradiance LUT exists before the multiscatter LUT's sets: the second multiscatter pass reads it. */
    if (ground) gpu_image_create(ctx, &l->ground_irradiance, "ground irradiance LUT", format, 64, 1, 1, usage);
    if (multiscatter) {
        const gpu_slot m_slots[] = {{VKSKY_BINDING_ATMOSPHERE, UBO}, {VKSKY_BINDING_TRANSMITTANCE_LUT, SAMPLED},
                                    {VKSKY_BINDING_GROUND_IRRADIANCE_LUT, SAMPLED}, {VKSKY_BINDING_OUTPUT, STORAGE}};
        l->multiscatter_set_layout = gpu_set_layout(ctx, m_slots, 4, VK_SHADER_STAGE_COMPUTE_BIT, "multiscatter set layout");
        l->multiscatter_layout = gpu_pipeline_layout(ctx, l->multiscatter_set_layout, sizeof(MultiscatterPush),
                                                     VK_SHADER_STAGE_COMPUTE_BIT, "multiscatter layout");
        l->multiscatter_spv = s4 ? (q->lut_f32 ? &spirv_multiscatter_lut_f32_s4 : &spirv_multiscatter_lut_s4)
                                 : q->lut_f32 ? &spirv_multiscatter_lut_f32 : &spirv_multiscatter_lut;
        l->multiscatter_set = gpu_alloc_set(ctx, s->pool, l->multiscatter_set_layout, "multiscatter set");
        gpu_write_uniform(ctx, l->multiscatter_set, VKSKY_BINDING_ATMOSPHERE, s->atmosphere_ubo.buffer,
                          sizeof(AtmosphereParams));
        gpu_write_sampled(ctx, l->multiscatter_set, VKSKY_BINDING_TRANSMITTANCE_LUT, l->transmittance.view,
                          s->linear_clamp);
        gpu_write_storage(ctx, l->multiscatter_set, VKSKY_BINDING_OUTPUT, l->multiscatter.view);
        /* The first pass never samples the ground-irradiance slot (its push constant says so): the transmittance
         * LUT stands in, readable by then. The second pass (a lit ground only) binds the real one. */
        gpu_write_sampled(ctx, l->multiscatter_set, VKSKY_BINDING_GROUND_IRRADIANCE_LUT, l->transmittance.view,
                          s->linear_clamp);
        if (ground) {
            l->multiscatter_ground_set = gpu_alloc_set(ctx, s->pool, l->multiscatter_set_layout, "multiscatter set (sky-lit ground)");
            gpu_write_uniform(ctx, l->multiscatter_ground_set, VKSKY_BINDING_ATMOSPHERE, s->atmosphere_ubo.buffer,
                              sizeof(AtmosphereParams));
            gpu_write_sampled(ctx, l->multiscatter_ground_set, VKSKY_BINDING_TRANSMITTANCE_LUT, l->transmittance.view,
                              s->linear_clamp);
            gpu_write_sampled(ctx, l->multiscatter_ground_set, VKSKY_BINDING_GROUND_IRRADIANCE_LUT,
                              l->ground_irradiance.view, s->linear_clamp);
            gpu_write_storage(ctx, l->multiscatter_ground_set, VKSKY_BINDING_OUTPUT, l->multiscatter.view);
        }
    }

    if (ground) {
        const gpu_slot g_slots[] = {{VKSKY_BINDING_ATMOSPHERE, UBO}, {VKSKY_BINDING_TRANSMITTANCE_LUT, SAMPLED},
                                    {VKSKY_BINDING_MULTISCATTER_LUT, SAMPLED}, {VKSKY_BINDING_OUTPUT, STORAGE}};
        l->ground_set_layout = gpu_set_layout(ctx, g_slots, 4, VK_SHADER_STAGE_COMPUTE_BIT, "ground irradiance set layout");
        l->ground_layout = gpu_pipeline_layout(ctx, l->ground_set_layout, 0, 0, "ground irradiance layout");
        l->ground_spv = s4 ? &spirv_ground_irradiance_lut_s4 : &spirv_ground_irradiance_lut;
        l->ground_set = gpu_alloc_set(ctx, s->pool, l->ground_set_layout, "ground irradiance set");
        gpu_write_uniform(ctx, l->ground_set, VKSKY_BINDING_ATMOSPHERE, s->atmosphere_ubo.buffer,
                          sizeof(AtmosphereParams));
        gpu_write_sampled(ctx, l->ground_set, VKSKY_BINDING_TRANSMITTANCE_LUT, l->transmittance.view, s->linear_clamp);
        gpu_write_sampled(ctx, l->ground_set, VKSKY_BINDING_MULTISCATTER_LUT, l->multiscatter_view, s->linear_clamp);
        gpu_write_storage(ctx, l->ground_set, VKSKY_BINDING_OUTPUT, l->ground_irradiance.view);
    }
    l->ground_irradiance_view = ground ? l->ground_irradiance.view : l->transmittance.view;

    const gpu_slot v_slots[] = {{VKSKY_BINDING_ATMOSPHERE, UBO}, {VKSKY_BINDING_TRANSMITTANCE_LUT, SAMPLED},
                                {VKSKY_BINDING_MULTISCATTER_LUT, SAMPLED}, {VKSKY_BINDING_GROUND_IRRADIANCE_LUT, SAMPLED},
                                {VKSKY_BINDING_OUTPUT, STORAGE}};
    l->skyview_set_layout = gpu_set_layout(ctx, v_slots, 5, VK_SHADER_STAGE_COMPUTE_BIT, "skyview set layout");
    l->skyview_layout = gpu_pipeline_layout(ctx, l->skyview_set_layout, sizeof(SkyPush), VK_SHADER_STAGE_COMPUTE_BIT,
                                            "skyview layout");
    l->skyview_spv = s4 ? &spirv_skyview_lut_s4 : &spirv_skyview_lut;
    l->shared = s;   /* the pipelines above are made at their first record, with s's variant (spec constants) */
    l->skyview_set = gpu_alloc_set(ctx, s->pool, l->skyview_set_layout, "skyview set");
    gpu_write_uniform(ctx, l->skyview_set, VKSKY_BINDING_ATMOSPHERE, s->atmosphere_ubo.buffer, sizeof(AtmosphereParams));
    gpu_write_sampled(ctx, l->skyview_set, VKSKY_BINDING_TRANSMITTANCE_LUT, l->transmittance.view, s->linear_clamp);
    gpu_write_sampled(ctx, l->skyview_set, VKSKY_BINDING_MULTISCATTER_LUT, l->multiscatter_view, s->linear_clamp);
    gpu_write_sampled(ctx, l->skyview_set, VKSKY_BINDING_GROUND_IRRADIANCE_LUT, l->ground_irradiance_view,
                      s->linear_clamp);
    gpu_write_storage(ctx, l->skyview_set, VKSKY_BINDING_OUTPUT, l->skyview.view);
}

void luts_destroy(sky_luts *l, const pass_shared *s)
{
    VkDevice d = s->ctx->device;
    VkPipeline pipelines[] = {l->transmittance_pipeline, l->multiscatter_pipeline, l->skyview_pipeline, l->ground_pipeline};
    VkPipelineLayout layouts[] = {l->transmittance_layout, l->multiscatter_layout, l->skyview_layout, l->ground_layout};
    VkDescriptorSetLayout set_layouts[] = {l->transmittance_set_layout, l->multiscatter_set_layout,
                                           l->skyview_set_layout, l->ground_set_layout};
    for (int i = 0; i < 4; ++i) {
        vkDestroyPipeline(d, pipelines[i], gpu_allocator(d));
        vkDestroyPipelineLayout(d, layouts[i], gpu_allocator(d));
        vkDestroyDescriptorSetLayout(d, set_layouts[i], gpu_allocator(d));
    }
    gpu_image_destroy(s->ctx, &l->transmittance);
    gpu_image_destroy(s->ctx, &l->multiscatter);
    gpu_image_destroy(s->ctx, &l->skyview);
    gpu_image_destroy(s->ctx, &l->ground_irradiance);
    *l = (sky_luts){0};
}

static void dispatch(VkCommandBuffer cmd, VkPipeline pipeline, VkPipelineLayout layout, VkDescriptorSet set,
                     const gpu_image *target)
{
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, NULL);
    vkCmdDispatch(cmd, (target->extent.width + 7) / 8, (target->extent.height + 7) / 8, 1);
}

void luts_record_transmittance(sky_luts *l, VkCommandBuffer cmd)
{
    if (!l->transmittance_pipeline)
        l->transmittance_pipeline = compute_pipeline(l->shared, l->transmittance_layout, l->transmittance_spv,
                                                     "transmittance LUT");
    dispatch(cmd, l->transmittance_pipeline, l->transmittance_layout, l->transmittance_set, &l->transmittance);
}

void luts_record_multiscatter(sky_luts *l, VkCommandBuffer cmd, bool sky_lit_ground)
{
    if (!l->multiscatter_pipeline)
        l->multiscatter_pipeline = compute_pipeline(l->shared, l->multiscatter_layout, l->multiscatter_spv,
                                                    "multiscatter LUT");
    /* One 64-thread workgroup per texel (the threads share the sphere directions). */
    MultiscatterPush push = {.ground = {sky_lit_ground ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f}};
    VkDescriptorSet set = sky_lit_ground ? l->multiscatter_ground_set : l->multiscatter_set;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, l->multiscatter_pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, l->multiscatter_layout, 0, 1, &set, 0, NULL);
    vkCmdPushConstants(cmd, l->multiscatter_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, l->multiscatter.extent.width / l->multiscatter_parts, l->multiscatter.extent.height, 1);   /* a workgroup a texel */
}

void luts_record_skyview(sky_luts *l, VkCommandBuffer cmd, const SkyPush *push)
{
    if (!l->skyview_pipeline)
        l->skyview_pipeline = compute_pipeline(l->shared, l->skyview_layout, l->skyview_spv, "skyview LUT");
    vkCmdPushConstants(cmd, l->skyview_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof *push, push);
    dispatch(cmd, l->skyview_pipeline, l->skyview_layout, l->skyview_set, &l->skyview);
}

void luts_record_ground_irradiance(sky_luts *l, VkCommandBuffer cmd)
{
    if (!l->ground_pipeline)
        l->ground_pipeline = compute_pipeline(l->shared, l->ground_layout, l->ground_spv, "ground irradiance LUT");
    /* One 64-thread workgroup per texel (the threads share the hemisphere directions). */
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, l->ground_pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, l->ground_layout, 0, 1, &l->ground_set, 0, NULL);
    vkCmdDispatch(cmd, l->ground_irradiance.extent.width, 1, 1);
}
