/* The spectral groups summed on the GPU (sky/spectral_sum.h, shaders/glsl/spectral_sum.comp). */
#include "sky/spectral_sum.h"
#include "gpu/pipeline.h"
#include "model/spectrum.h"
#include "spectral_sum_comp.h"
#include <string.h>

enum { BINDING_GROUP = VKSKY_BINDING_SPECTRAL_GROUP, BINDING_SUM = VKSKY_BINDING_SPECTRAL_SUM,
       BINDING_RESOLVED = VKSKY_BINDING_SPECTRAL_RESOLVED, TILE = 8 };

void spectral_sum_create(spectral_sum *s, const gpu_context *ctx, uint32_t width, uint32_t height)
{
    *s = (spectral_sum){.ctx = ctx, .extent = {width, height}};
    gpu_image_create(ctx, &s->accum, "spectral_sum", VK_FORMAT_R32G32B32A32_SFLOAT, width, height, 1,
                     VK_IMAGE_USAGE_STORAGE_BIT);
    gpu_buffer_create(ctx, &s->resolved, "spectral resolved", (VkDeviceSize)width * height * 16,
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    VkSamplerCreateInfo sinfo = {.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO, .magFilter = VK_FILTER_NEAREST,
                                 .minFilter = VK_FILTER_NEAREST,
                                 .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                 .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                 .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE};
    VK_CHECK(vkCreateSampler(ctx->device, &sinfo, gpu_allocator(ctx->device), &s->nearest));
    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, SPECTRAL_SUM_SETS},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, SPECTRAL_SUM_SETS},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, SPECTRAL_SUM_SETS}};
    VkDescriptorPoolCreateInfo pinfo = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                        .maxSets = SPECTRAL_SUM_SETS, .poolSizeCount = 3, .pPoolSizes = sizes};
    VK_CHECK(vkCreateDescriptorPool(ctx->device, &pinfo, gpu_allocator(ctx->device), &s->pool));
    const gpu_slot slots[] = {{BINDING_GROUP, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                              {BINDING_SUM, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                              {BINDING_RESOLVED, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    s->set_layout = gpu_set_layout(ctx, slots, 3, VK_SHADER_STAGE_COMPUTE_BIT, "spectral_sum");
    s->layout = gpu_pipeline_layout(ctx, s->set_layout, sizeof(SpectralSumPush), VK_SHADER_STAGE_COMPUTE_BIT,
                                    "spectral_sum");
    VkShaderModule mod = gpu_shader_module(ctx, spv_spectral_sum_comp, sizeof spv_spectral_sum_comp,
                                           "spectral_sum.comp");
    s->pipeline = gpu_compute_pipeline(ctx, s->layout, mod, "spectral_sum");
    vkDestroyShaderModule(ctx->device, mod, gpu_allocator(ctx->device));
    VkDescriptorBufferInfo out = {.buffer = s->resolved.buffer, .offset = 0, .range = s->resolved.size};
    for (uint32_t k = 0; k < SPECTRAL_SUM_SETS; ++k) {
        s->set[k] = gpu_alloc_set(ctx, s->pool, s->set_layout, "spectral_sum");
        gpu_write_storage(ctx, s->set[k], BINDING_SUM, s->accum.view);
        VkWriteDescriptorSet w = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = s->set[k],
                                  .dstBinding = BINDING_RESOLVED, .descriptorCount = 1,
                                  .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &out};
        vkUpdateDescriptorSets(ctx->device, 1, &w, 0, NULL);
    }
}

void spectral_sum_destroy(spectral_sum *s)
{
    if (!s->ctx) return;
    VkDevice d = s->ctx->device;
    if (s->pipeline) vkDestroyPipeline(d, s->pipeline, gpu_allocator(d));
    if (s->layout) vkDestroyPipelineLayout(d, s->layout, gpu_allocator(d));
    if (s->set_layout) vkDestroyDescriptorSetLayout(d, s->set_layout, gpu_allocator(d));
    if (s->pool) vkDestroyDescriptorPool(d, s->pool, gpu_allocator(d));
    if (s->nearest) vkDestroySampler(d, s->nearest, gpu_allocator(d));
    gpu_buffer_destroy(s->ctx, &s->resolved);
    gpu_image_destroy(s->ctx, &s->accum);
    *s = (spectral_sum){0};
}

void spectral_sum_push_fill(SpectralSumPush *p, const double weights[4][3], bool first, bool last, bool alpha_from_group,
                            uint32_t width)
{
    memset(p, 0, sizeof *p);
    for (int c = 0; c < 4; ++c)
        p->weight[c] = (vksky_vec4){(float)weights[c][0], (float)weights[c][1], (float)weights[c][2], 0.0f};
    p->mode = (vksky_vec4){first ? 1.0f : 0.0f, last ? 1.0f : 0.0f, alpha_from_group ? 1.0f : 0.0f, (float)width};
    /* The matrix's rows, from the one definition (model/spectrum.c) applied to the unit vectors. */
    double col[3][3];
    for (int k = 0; k < 3; ++k) {
        double e[3] = {k == 0, k == 1, k == 2};
        spectrum_xyz_to_rec709(e, col[k]);
    }
    for (int r = 0; r < 3; ++r)
        p->to_rec709[r] = (vksky_vec4){(float)col[0][r], (float)col[1][r], (float)col[2][r], 0.0f};
}

void spectral_sum_bind(const spectral_sum_step *step, const gpu_image *group_image)
{
    spectral_sum *s = step->sum;
    if (s->bound[step->group] != group_image->view) {   /* a renderer made or resized since: its image named again */
        gpu_write_sampled(s->ctx, s->set[step->group], BINDING_GROUP, group_image->view, s->nearest);
        s->bound[step->group] = group_image->view;
    }
}

void spectral_sum_dispatch(const spectral_sum_step *step, VkCommandBuffer cmd)
{
    const spectral_sum *s = step->sum;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s->layout, 0, 1, &s->set[step->group], 0, NULL);
    vkCmdPushConstants(cmd, s->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof step->push, &step->push);
    vkCmdDispatch(cmd, (s->extent.width + TILE - 1) / TILE, (s->extent.height + TILE - 1) / TILE, 1);
}
