#include "sky/passes.h"
#include "sky/shaders.h"

void bloom_create(bloom_chain *b, const pass_shared *s, const gpu_image *hdr, uint32_t mips, uint32_t start)
{
    const gpu_context *ctx = s->ctx;
    b->hdr_extent = hdr->extent;
    /* Mip 0 at half the HDR size, or (start 1) a quarter: the first downsample's 13 taps then reach +-2 HDR
     * texels around each quarter-size texel's centre, which still covers its 4x4 footprint. */
    uint32_t w = hdr->extent.width >> (1 + start), h = hdr->extent.height >> (1 + start);
    /* A full mip chain of a w x h image has floor(log2(max(w, h))) + 1 levels; keep every mip >= 2 pixels. */
    uint32_t fit = 1;
    while (fit < BLOOM_MAX_MIPS && (w >> fit) >= 2 && (h >> fit) >= 2) ++fit;
    b->mip_count = mips < fit ? mips : fit;
    gpu_image_create(ctx, &b->mips, "bloom mips", HDR_FORMAT, w ? w : 1, h ? h : 1, b->mip_count,
                     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT);

    const gpu_slot slots[] = {{VKSKY_BINDING_POST_SOURCE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}};
    b->set_layout = gpu_set_layout(ctx, slots, 1, VK_SHADER_STAGE_FRAGMENT_BIT, "bloom set layout");
    b->layout = gpu_pipeline_layout(ctx, b->set_layout, sizeof(BloomPush), VK_SHADER_STAGE_FRAGMENT_BIT, "bloom layout");
    VkFormat format = HDR_FORMAT;
    VkShaderModule down = gpu_shader_module(ctx, spirv_bloom_downsample.code, spirv_bloom_downsample.size, "bloom_downsample.frag");
    VkShaderModule up = gpu_shader_module(ctx, spirv_bloom_upsample.code, spirv_bloom_upsample.size, "bloom_upsample.frag");
    b->down_pipeline = gpu_fullscreen_pipeline(ctx, b->layout, s->fullscreen_vs, down, &format, 1, GPU_BLEND_NONE, "bloom downsample");
    /* Upsample adds onto what the downsample left in the mip: blend ONE + ONE with load op LOAD. */
    b->up_pipeline = gpu_fullscreen_pipeline(ctx, b->layout, s->fullscreen_vs, up, &format, 1, GPU_BLEND_ADDITIVE, "bloom upsample");
    vkDestroyShaderModule(ctx->device, down, gpu_allocator(ctx->device));
    vkDestroyShaderModule(ctx->device, up, gpu_allocator(ctx->device));
    for (uint32_t i = 0; i < b->mip_count; ++i) {
        b->down_sets[i] = gpu_alloc_set(ctx, s->pool, b->set_layout, "bloom downsample set");
        gpu_write_sampled(ctx, b->down_sets[i], VKSKY_BINDING_POST_SOURCE, i == 0 ? hdr->view : b->mips.mip_views[i - 1], s->linear_clamp);
        if (i + 1 < b->mip_count) {
            b->up_sets[i] = gpu_alloc_set(ctx, s->pool, b->set_layout, "bloom upsample set");
            gpu_write_sampled(ctx, b->up_sets[i], VKSKY_BINDING_POST_SOURCE, b->mips.mip_views[i + 1], s->linear_clamp);
        }
    }
}

void bloom_destroy(bloom_chain *b, const pass_shared *s)
{
    VkDevice d = s->ctx->device;
    vkDestroyPipeline(d, b->down_pipeline, gpu_allocator(d));
    vkDestroyPipeline(d, b->up_pipeline, gpu_allocator(d));
    vkDestroyPipelineLayout(d, b->layout, gpu_allocator(d));
    vkDestroyDescriptorSetLayout(d, b->set_layout, gpu_allocator(d));
    gpu_image_destroy(s->ctx, &b->mips);
}

static void draw(const bloom_chain *b, VkCommandBuffer cmd, VkPipeline pipeline, VkDescriptorSet set, uint32_t dst,
                 VkAttachmentLoadOp load, VkExtent2D src_extent, float first, float threshold)
{
    gpu_attachment target = {b->mips.mip_views[dst], load};
    gpu_begin_rendering(cmd, gpu_mip_extent(b->mips.extent, dst), &target, 1);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, b->layout, 0, 1, &set, 0, NULL);
    BloomPush push = {.src_texel = {1.0f / (float)src_extent.width, 1.0f / (float)src_extent.height, first, threshold}};
    vkCmdPushConstants(cmd, b->layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push, &push);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
}

void bloom_record_downsample(const bloom_chain *b, VkCommandBuffer cmd, uint32_t dst, float threshold)
{
    VkExtent2D src = dst == 0 ? b->hdr_extent : gpu_mip_extent(b->mips.extent, dst - 1);
    draw(b, cmd, b->down_pipeline, b->down_sets[dst], dst, VK_ATTACHMENT_LOAD_OP_DONT_CARE, src, dst == 0 ? 1.0f : 0.0f,
         threshold);
}

void bloom_record_upsample(const bloom_chain *b, VkCommandBuffer cmd, uint32_t dst)
{
    draw(b, cmd, b->up_pipeline, b->up_sets[dst], dst, VK_ATTACHMENT_LOAD_OP_LOAD,
         gpu_mip_extent(b->mips.extent, dst + 1), 0.0f, 0.0f);
}
