#include "sky/passes.h"
#include "sky/shaders.h"

/* One pipeline per (kind, mode), each from its own SPIR-V variant: no per-pixel branch on the mode. Mode 3 is the
 * sky-view lookup from 10 km up, blending into the march on the way to space and marching the rays near the
 * horizon (shaders/glsl/horizon.glsl): its own variant, because on lavapipe a march merely present in the
 * lookup shader costs every pixel (measured: 8x the lookup's sky pass with no pixel marching). */
#define SKY_MODE_BLEND 3
static const sky_spirv *variant(int kind, int mode, bool spectral4)
{
    static const sky_spirv *const table[2][4] = {
        {&spirv_sky_march_frag, &spirv_sky_lookup_frag, &spirv_sky_fill_frag, &spirv_sky_blend_frag},
        {&spirv_sky_march_comp, &spirv_sky_lookup_comp, &spirv_sky_fill_comp, &spirv_sky_blend_comp}};
    /* The four-wide spectral build's (no fill: a benchmark's floor, never spectral). */
    static const sky_spirv *const table4[2][4] = {
        {&spirv_sky_march_frag_s4, &spirv_sky_lookup_frag_s4, &spirv_sky_fill_frag, &spirv_sky_blend_frag_s4},
        {&spirv_sky_march_comp_s4, &spirv_sky_lookup_comp_s4, &spirv_sky_fill_comp, &spirv_sky_blend_comp_s4}};
    return spectral4 ? table4[kind][mode] : table[kind][mode];
}

static VkPipeline make_pipeline(const sky_pass *p, const pass_shared *s, int kind, int mode)
{
    static const char *const names_km[2][4] = {
        {"sky march (fragment)", "sky lookup (fragment)", "sky fill (fragment)", "sky blend (fragment)"},
        {"sky march (compute)", "sky lookup (compute)", "sky fill (compute)", "sky blend (compute)"}};
    const char *name = names_km[kind][mode];
    const sky_spirv *spv = variant(kind, mode, s->spectral4);
    VkFormat format = HDR_FORMAT;
    VkShaderModule m = gpu_shader_module(s->ctx, spv->code, spv->size, name);
    VkPipeline pipeline = kind == SKY_PASS_FRAGMENT
        ? gpu_fullscreen_pipeline_spec(s->ctx, p->layouts[kind], s->fullscreen_vs, m, s->spec, &format, 1,
                                       GPU_BLEND_NONE, name)
        : gpu_compute_pipeline_spec(s->ctx, p->layouts[kind], m, s->spec, name);
    vkDestroyShaderModule(s->ctx->device, m, gpu_allocator(s->ctx->device));
    return pipeline;
}

void sky_pass_create(sky_pass *p, const pass_shared *s, const sky_luts *luts)
{
    const gpu_context *ctx = s->ctx;
    const VkDescriptorType UBO = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, SAMPLED = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    const gpu_slot slots[] = {{VKSKY_BINDING_ATMOSPHERE, UBO}, {VKSKY_BINDING_TRANSMITTANCE_LUT, SAMPLED},
                              {VKSKY_BINDING_MULTISCATTER_LUT, SAMPLED}, {VKSKY_BINDING_SKYVIEW_LUT, SAMPLED},
                              {VKSKY_BINDING_GROUND_IRRADIANCE_LUT, SAMPLED},
                              {VKSKY_BINDING_OUTPUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    VkShaderStageFlags stages[2] = {VK_SHADER_STAGE_FRAGMENT_BIT, VK_SHADER_STAGE_COMPUTE_BIT};
    const char *names[2] = {"sky (fragment)", "sky (compute)"};
    for (int kind = 0; kind < 2; ++kind) {
        /* VKSKY_BINDING_OUTPUT (the HDR storage image) is the compute path's; the fragment layout leaves it unused. */
        p->set_layouts[kind] = gpu_set_layout(ctx, slots, 6, stages[kind], names[kind]);
        p->layouts[kind] = gpu_pipeline_layout(ctx, p->set_layouts[kind], sizeof(SkyPush), stages[kind], names[kind]);
        p->sets[kind] = gpu_alloc_set(ctx, s->pool, p->set_layouts[kind], names[kind]);
        VkDescriptorSet set = p->sets[kind];
        gpu_write_uniform(ctx, set, VKSKY_BINDING_ATMOSPHERE, s->atmosphere_ubo.buffer, sizeof(AtmosphereParams));
        gpu_write_sampled(ctx, set, VKSKY_BINDING_TRANSMITTANCE_LUT, luts->transmittance.view, s->linear_clamp);
        gpu_write_sampled(ctx, set, VKSKY_BINDING_MULTISCATTER_LUT, luts->multiscatter_view, s->linear_clamp);
        gpu_write_sampled(ctx, set, VKSKY_BINDING_SKYVIEW_LUT, luts->skyview.view, s->linear_clamp);
        gpu_write_sampled(ctx, set, VKSKY_BINDING_GROUND_IRRADIANCE_LUT, luts->ground_irradiance_view, s->linear_clamp);
        /* Every (kind, mode) pipeline is built at its first use (sky_pass_record): a run draws with one kind and
         * one or two modes, and lavapipe compiles at creation even with a warm shader cache (with validation, the
         * six it did not use cost ~150 ms of CPU in every process: issue 27 items 3 and 5). The blend variant, the
         * largest shader, was already made this way. */
        for (int mode = 0; mode < 4; ++mode) p->pipelines[kind][mode] = VK_NULL_HANDLE;
    }
    p->shared = s;
}

void sky_pass_set_target(sky_pass *p, const pass_shared *s, const gpu_image *hdr)
{
    gpu_write_storage(s->ctx, p->sets[SKY_PASS_COMPUTE], VKSKY_BINDING_OUTPUT, hdr->view);
}

void sky_pass_destroy(sky_pass *p, const pass_shared *s)
{
    VkDevice d = s->ctx->device;
    for (int kind = 0; kind < 2; ++kind) {
        for (int mode = 0; mode < 4; ++mode) vkDestroyPipeline(d, p->pipelines[kind][mode], gpu_allocator(d));
        vkDestroyPipelineLayout(d, p->layouts[kind], gpu_allocator(d));
        vkDestroyDescriptorSetLayout(d, p->set_layouts[kind], gpu_allocator(d));
    }
    *p = (sky_pass){0};
}

void sky_pass_record(sky_pass *p, VkCommandBuffer cmd, sky_pass_kind kind, sky_mode mode,
                     const gpu_image *hdr, const SkyPush *push)
{
    VkPipelineBindPoint bind = kind == SKY_PASS_COMPUTE ? VK_PIPELINE_BIND_POINT_COMPUTE : VK_PIPELINE_BIND_POINT_GRAPHICS;
    VkShaderStageFlags stage = kind == SKY_PASS_COMPUTE ? VK_SHADER_STAGE_COMPUTE_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
    if (kind == SKY_PASS_FRAGMENT) {
        /* DONT_CARE: every pixel is written. */
        gpu_attachment target = {hdr->view, VK_ATTACHMENT_LOAD_OP_DONT_CARE};
        gpu_begin_rendering(cmd, hdr->extent, &target, 1);
    }
    /* The lookup above a tenth of the atmosphere's height (horizon.w > 0: the march's weight near the horizon) is
     * the blend. */
    int variant_mode = mode == SKY_MODE_SKYVIEW && push->horizon.w > 0.0f ? SKY_MODE_BLEND : (int)mode;
    if (!p->pipelines[kind][variant_mode]) p->pipelines[kind][variant_mode] = make_pipeline(p, p->shared, kind, variant_mode);
    vkCmdBindPipeline(cmd, bind, p->pipelines[kind][variant_mode]);
    vkCmdBindDescriptorSets(cmd, bind, p->layouts[kind], 0, 1, &p->sets[kind], 0, NULL);
    vkCmdPushConstants(cmd, p->layouts[kind], stage, 0, sizeof *push, push);
    if (kind == SKY_PASS_FRAGMENT) {
        vkCmdDraw(cmd, 3, 1, 0, 0);
        vkCmdEndRendering(cmd);
    } else {
        vkCmdDispatch(cmd, (hdr->extent.width + 7) / 8, (hdr->extent.height + 7) / 8, 1);
    }
}
