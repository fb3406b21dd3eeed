#include "sky/post.h"

#define SPD_TILE 16               /* bloom_spd.comp's TILE */
#define SPD_COUNTER_ROW 1024      /* bloom_spd.comp's counter_coord */

static void write_image(const gpu_context *ctx, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                        VkImageView view, VkSampler sampler, VkImageLayout layout)
{
    VkDescriptorImageInfo info = {.sampler = sampler, .imageView = view, .imageLayout = layout};
    VkWriteDescriptorSet w = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = set, .dstBinding = binding,
                              .descriptorCount = 1, .descriptorType = type, .pImageInfo = &info};
    vkUpdateDescriptorSets(ctx->device, 1, &w, 0, NULL);
}

static VkPipeline compute_pipeline(const gpu_context *ctx, VkPipelineLayout layout, const sky_spirv *spv,
                                   const char *name)
{
    VkShaderModule m = gpu_shader_module(ctx, spv->code, spv->size, name);
    VkPipeline p = gpu_compute_pipeline(ctx, layout, m, name);
    vkDestroyShaderModule(ctx->device, m, gpu_allocator(ctx->device));
    return p;
}

post_pass_kind post_pass_resolve(post_pass_kind k, const gpu_context *ctx)
{
    if (k != POST_PASS_AUTO) return k;
    return ctx->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? POST_PASS_FRAGMENT : POST_PASS_COMPUTE;
}

static uint32_t tiles(uint32_t n) { return (n + SPD_TILE - 1) / SPD_TILE; }

static void create_bloom(post_compute *p, const pass_shared *s, const gpu_image *hdr, const bloom_chain *b)
{
    const gpu_context *ctx = s->ctx;
    const VkDescriptorType SAMPLED = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, STORAGE = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    /* Counters: one per tile of levels 1 .. mip_count - 1 (level 0 tiles depend on nothing), 1024 a row. */
    p->counter_count = 0;
    for (uint32_t k = 1; k < b->mip_count; ++k) {
        VkExtent2D e = gpu_mip_extent(b->mips.extent, k);
        p->counter_count += tiles(e.width) * tiles(e.height);
    }
    uint32_t n = p->counter_count ? p->counter_count : 1;
    gpu_image_create(ctx, &p->counters, "spd counters", VK_FORMAT_R32_UINT, n < SPD_COUNTER_ROW ? n : SPD_COUNTER_ROW,
                     (n + SPD_COUNTER_ROW - 1) / SPD_COUNTER_ROW, 1,
                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    p->level0_tiles = (VkExtent2D){tiles(b->mips.extent.width), tiles(b->mips.extent.height)};

    /* The single pass: the HDR image (sampled), 8 mip bindings (levels past the chain repeat its last mip; the
     * shader never touches them), the counters. */
    gpu_slot spd_slots[2 + BLOOM_MAX_MIPS] = {{VKSKY_BINDING_POST_SOURCE, SAMPLED}, {VKSKY_BINDING_SPD_COUNTERS, STORAGE}};
    for (uint32_t k = 0; k < BLOOM_MAX_MIPS; ++k) spd_slots[2 + k] = (gpu_slot){VKSKY_BINDING_POST_MIP + k, STORAGE};
    p->spd_set_layout = gpu_set_layout(ctx, spd_slots, 2 + BLOOM_MAX_MIPS, VK_SHADER_STAGE_COMPUTE_BIT, "bloom spd set layout");
    p->spd_layout = gpu_pipeline_layout(ctx, p->spd_set_layout, sizeof(PostPush), VK_SHADER_STAGE_COMPUTE_BIT, "bloom spd layout");
    /* Written in the Vulkan memory model at device scope: without vulkanMemoryModelDeviceScope (optional even in
     * Vulkan 1.3) there is no single pass, and frame.c records the per-level downsample instead. */
    if (ctx->memory_model_device_scope)
        p->spd_pipeline = compute_pipeline(ctx, p->spd_layout, &spirv_bloom_spd, "bloom spd");
    p->spd_set = gpu_alloc_set(ctx, p->pool, p->spd_set_layout, "bloom spd set");
    write_image(ctx, p->spd_set, VKSKY_BINDING_POST_SOURCE, SAMPLED, hdr->view, s->linear_clamp, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    for (uint32_t k = 0; k < BLOOM_MAX_MIPS; ++k) {
        uint32_t m = k < b->mip_count ? k : b->mip_count - 1;
        write_image(ctx, p->spd_set, VKSKY_BINDING_POST_MIP + k, STORAGE, b->mips.mip_views[m], VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL);
    }
    write_image(ctx, p->spd_set, VKSKY_BINDING_SPD_COUNTERS, STORAGE, p->counters.view, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL);

    /* Upsamples: mip i + 1 sampled (GENERAL: the whole chain stays in GENERAL), mip i read-modify-written. */
    const gpu_slot up_slots[] = {{VKSKY_BINDING_POST_SOURCE, SAMPLED}, {VKSKY_BINDING_POST_MIP, STORAGE}};
    p->up_set_layout = gpu_set_layout(ctx, up_slots, 2, VK_SHADER_STAGE_COMPUTE_BIT, "bloom up set layout");
    p->up_layout = gpu_pipeline_layout(ctx, p->up_set_layout, sizeof(PostPush), VK_SHADER_STAGE_COMPUTE_BIT, "bloom up layout");
    p->up_pipeline = compute_pipeline(ctx, p->up_layout, &spirv_bloom_up_comp, "bloom upsample (compute)");
    p->down_pipeline = compute_pipeline(ctx, p->up_layout, &spirv_bloom_down_comp, "bloom downsample (compute)");
    for (uint32_t k = 0; k < b->mip_count; ++k) {
        p->down_sets[k] = gpu_alloc_set(ctx, p->pool, p->up_set_layout, "bloom down set");
        if (k == 0)
            write_image(ctx, p->down_sets[k], VKSKY_BINDING_POST_SOURCE, SAMPLED, hdr->view, s->linear_clamp, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        else
            write_image(ctx, p->down_sets[k], VKSKY_BINDING_POST_SOURCE, SAMPLED, b->mips.mip_views[k - 1], s->linear_clamp, VK_IMAGE_LAYOUT_GENERAL);
        write_image(ctx, p->down_sets[k], VKSKY_BINDING_POST_MIP, STORAGE, b->mips.mip_views[k], VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL);
    }
    for (uint32_t i = 0; i + 1 < b->mip_count; ++i) {
        p->up_sets[i] = gpu_alloc_set(ctx, p->pool, p->up_set_layout, "bloom up set");
        write_image(ctx, p->up_sets[i], VKSKY_BINDING_POST_SOURCE, SAMPLED, b->mips.mip_views[i + 1], s->linear_clamp, VK_IMAGE_LAYOUT_GENERAL);
        write_image(ctx, p->up_sets[i], VKSKY_BINDING_POST_MIP, STORAGE, b->mips.mip_views[i], VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL);
    }
}

/* The tone map's bindings but the display's: the HDR image, bloom mips 0 and 1 (the HDR image in their place without
 * a chain: never sampled, strength 0). */
static void write_tonemap_sources(const pass_shared *s, VkDescriptorSet set, const gpu_image *hdr,
                                  const bloom_chain *bloom)
{
    const gpu_context *ctx = s->ctx;
    const VkDescriptorType SAMPLED = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    write_image(ctx, set, VKSKY_BINDING_POST_SOURCE, SAMPLED, hdr->view, s->linear_clamp, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    for (uint32_t i = 0; i < 2; ++i) {
        if (bloom) {
            VkImageView v = bloom->mips.mip_views[i < bloom->mip_count ? i : 0];
            write_image(ctx, set, VKSKY_BINDING_POST_MIP + i, SAMPLED, v, s->linear_clamp, VK_IMAGE_LAYOUT_GENERAL);
        } else {
            write_image(ctx, set, VKSKY_BINDING_POST_MIP + i, SAMPLED, hdr->view, s->linear_clamp,
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        }
    }
}

void post_compute_create(post_compute *p, const pass_shared *s, const gpu_image *hdr, const bloom_chain *bloom,
                         VkImageView display, VkImageView composite, bool host_targets)
{
    const gpu_context *ctx = s->ctx;
    *p = (post_compute){.tonemap = display != VK_NULL_HANDLE, .composite = composite != VK_NULL_HANDLE,
                        .mip_count = bloom ? bloom->mip_count : 0, .host_tonemap = host_targets};
    /* The host's sets (POST_HOST_SETS, each 3 samplers, 1 storage image, the meter) beside the own ones. */
    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 24 + 3 * POST_HOST_SETS},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 32 + POST_HOST_SETS},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1 + POST_HOST_SETS}};   /* the tone map's meter */
    VkDescriptorPoolCreateInfo info = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                       .maxSets = 20 + POST_HOST_SETS, .poolSizeCount = 3, .pPoolSizes = sizes};
    VK_CHECK(vkCreateDescriptorPool(ctx->device, &info, gpu_allocator(ctx->device), &p->pool));
    if (bloom) create_bloom(p, s, hdr, bloom);
    if (!p->tonemap && !p->host_tonemap) return;
    const VkDescriptorType SAMPLED = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, STORAGE = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    const gpu_slot slots[] = {{VKSKY_BINDING_POST_SOURCE, SAMPLED}, {VKSKY_BINDING_POST_MIP, SAMPLED},
                              {VKSKY_BINDING_POST_MIP + 1, SAMPLED}, {VKSKY_BINDING_TONEMAP_DISPLAY, STORAGE},
                              {VKSKY_BINDING_METER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                              {VKSKY_BINDING_TONEMAP_COMPOSITE, STORAGE}};
    /* The meter's buffer (auto exposure; renderer.c points it at the meter), the composite last (only with it). */
    p->tonemap_set_layout = gpu_set_layout(ctx, slots, p->composite ? 6 : 5, VK_SHADER_STAGE_COMPUTE_BIT, "tonemap (compute) set layout");
    p->tonemap_layout = gpu_pipeline_layout(ctx, p->tonemap_set_layout, sizeof(PostPush), VK_SHADER_STAGE_COMPUTE_BIT,
                                            "tonemap (compute) layout");
    p->tonemap_pipeline = compute_pipeline(ctx, p->tonemap_layout,
                                           p->composite ? (s->spectral4 ? &spirv_tonemap_composite_comp_s4
                                                                        : &spirv_tonemap_composite_comp)
                                                        : &spirv_tonemap_comp,
                                           "tonemap (compute)");
    for (uint32_t i = 0; p->host_tonemap && i < POST_HOST_SETS; ++i) {
        p->host_sets[i] = gpu_alloc_set(ctx, p->pool, p->tonemap_set_layout, "tonemap (compute, host) set");
        write_tonemap_sources(s, p->host_sets[i], hdr, bloom);
    }
    if (!p->tonemap) return;
    p->tonemap_set = gpu_alloc_set(ctx, p->pool, p->tonemap_set_layout, "tonemap (compute) set");
    write_tonemap_sources(s, p->tonemap_set, hdr, bloom);
    write_image(ctx, p->tonemap_set, VKSKY_BINDING_TONEMAP_DISPLAY, STORAGE, display, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL);
    if (p->composite) write_image(ctx, p->tonemap_set, VKSKY_BINDING_TONEMAP_COMPOSITE, STORAGE, composite, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL);
}

VkDescriptorSet post_host_set(post_compute *p, const gpu_context *ctx, VkImageView view)
{
    int pick = 0;
    ++p->host_clock;
    for (int i = 0; i < POST_HOST_SETS; ++i) {
        if (p->host_views[i] == view && p->host_used[i]) {
            p->host_used[i] = p->host_clock;
            return p->host_sets[i];
        }
        if (p->host_used[i] < p->host_used[pick]) pick = i;
    }
    write_image(ctx, p->host_sets[pick], VKSKY_BINDING_TONEMAP_DISPLAY, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, view,
                VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL);
    p->host_views[pick] = view, p->host_used[pick] = p->host_clock;
    return p->host_sets[pick];
}

void post_compute_destroy(post_compute *p, const pass_shared *s)
{
    VkDevice d = s->ctx->device;
    if (p->down_pipeline) vkDestroyPipeline(d, p->down_pipeline, gpu_allocator(d));
    VkPipeline pipelines[3] = {p->spd_pipeline, p->up_pipeline, p->tonemap_pipeline};
    VkPipelineLayout layouts[3] = {p->spd_layout, p->up_layout, p->tonemap_layout};
    VkDescriptorSetLayout set_layouts[3] = {p->spd_set_layout, p->up_set_layout, p->tonemap_set_layout};
    for (int i = 0; i < 3; ++i) {
        if (pipelines[i]) vkDestroyPipeline(d, pipelines[i], gpu_allocator(d));
        if (layouts[i]) vkDestroyPipelineLayout(d, layouts[i], gpu_allocator(d));
        if (set_layouts[i]) vkDestroyDescriptorSetLayout(d, set_layouts[i], gpu_allocator(d));
    }
    gpu_image_destroy(s->ctx, &p->counters);
    vkDestroyDescriptorPool(d, p->pool, gpu_allocator(d));
    *p = (post_compute){0};
}

void post_record_clear_counters(const post_compute *p, VkCommandBuffer cmd)
{
    VkClearColorValue zero = {.uint32 = {0, 0, 0, 0}};
    VkImageSubresourceRange one = gpu_color_range(0, 1);
    vkCmdClearColorImage(cmd, p->counters.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &one);
}

void post_record_downsample(const post_compute *p, VkCommandBuffer cmd, float threshold)
{
    PostPush push = {.params = {(float)p->mip_count, threshold, 0.0f, 0.0f}};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->spd_pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->spd_layout, 0, 1, &p->spd_set, 0, NULL);
    vkCmdPushConstants(cmd, p->spd_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, p->level0_tiles.width, p->level0_tiles.height, 1);
}

/* One thread per texel of a mip (8x8 groups), the per-level pipelines' shared layout. */
static void dispatch_mip(const post_compute *p, VkCommandBuffer cmd, VkPipeline pipeline, VkDescriptorSet set,
                         const PostPush *push, VkExtent2D size)
{
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->up_layout, 0, 1, &set, 0, NULL);
    vkCmdPushConstants(cmd, p->up_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof *push, push);
    vkCmdDispatch(cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
}

void post_record_downsample_level(const post_compute *p, const bloom_chain *bloom, VkCommandBuffer cmd, uint32_t dst,
                                  VkExtent2D hdr_extent, float threshold)
{
    VkExtent2D src = dst == 0 ? hdr_extent : gpu_mip_extent(bloom->mips.extent, dst - 1);
    PostPush push = {.params = {1.0f / (float)src.width, 1.0f / (float)src.height, dst == 0 ? 1.0f : 0.0f, threshold}};
    dispatch_mip(p, cmd, p->down_pipeline, p->down_sets[dst], &push, gpu_mip_extent(bloom->mips.extent, dst));
}

void post_record_upsample(const post_compute *p, const bloom_chain *bloom, VkCommandBuffer cmd, uint32_t dst)
{
    VkExtent2D src = gpu_mip_extent(bloom->mips.extent, dst + 1);
    PostPush push = {.params = {1.0f / (float)src.width, 1.0f / (float)src.height, 0.0f, 0.0f}};
    dispatch_mip(p, cmd, p->up_pipeline, p->up_sets[dst], &push, gpu_mip_extent(bloom->mips.extent, dst));
}

void post_record_tonemap(const post_compute *p, const bloom_chain *bloom, VkCommandBuffer cmd, VkExtent2D extent,
                         const TonemapPush *tm)
{
    post_record_tonemap_set(p, bloom, cmd, extent, tm, p->tonemap_set);
}

void post_record_tonemap_set(const post_compute *p, const bloom_chain *bloom, VkCommandBuffer cmd, VkExtent2D extent,
                             const TonemapPush *tm, VkDescriptorSet set)
{
    PostPush push = {.tonemap = tm->params, .dither = tm->dither, .meter = tm->meter};
    if (p->mip_count > 1) {
        VkExtent2D m1 = gpu_mip_extent(bloom->mips.extent, 1);
        push.bloom = (vksky_vec4){1.0f / (float)m1.width, 1.0f / (float)m1.height, 1.0f, 0.0f};
    }
    if (!p->mip_count) push.tonemap.z = 0.0f;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->tonemap_pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->tonemap_layout, 0, 1, &set, 0, NULL);
    vkCmdPushConstants(cmd, p->tonemap_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, (extent.width + 7) / 8, (extent.height + 7) / 8, 1);
}
