/* Shader modules, descriptor set layouts and the two pipeline shapes vksky uses: compute, and a full-screen
 * triangle with dynamic rendering. Knows nothing of skies. */
#ifndef VKSKY_GPU_PIPELINE_H
#define VKSKY_GPU_PIPELINE_H
#include "gpu/context.h"

VkShaderModule gpu_shader_module(const gpu_context *ctx, const uint32_t *code, size_t size, const char *name);

/* One binding of a set layout: its number (the renderer names them in shaders/glsl/bindings.h) and type. */
typedef struct gpu_slot {
    uint32_t binding;
    VkDescriptorType type;
} gpu_slot;
/* A set layout from a list of slots (at most 16), all visible to `stages`. */
VkDescriptorSetLayout gpu_set_layout(const gpu_context *ctx, const gpu_slot *slots, uint32_t count,
                                     VkShaderStageFlags stages, const char *name);
VkPipelineLayout gpu_pipeline_layout(const gpu_context *ctx, VkDescriptorSetLayout set_layout, uint32_t push_size,
                                     VkShaderStageFlags push_stages, const char *name);
VkPipeline gpu_compute_pipeline(const gpu_context *ctx, VkPipelineLayout layout, VkShaderModule module,
                                const char *name);
/* With specialization constants (NULL: none). */
VkPipeline gpu_compute_pipeline_spec(const gpu_context *ctx, VkPipelineLayout layout, VkShaderModule module,
                                     const VkSpecializationInfo *spec, const char *name);

typedef enum gpu_blend { GPU_BLEND_NONE, GPU_BLEND_ADDITIVE } gpu_blend;
VkPipeline gpu_fullscreen_pipeline(const gpu_context *ctx, VkPipelineLayout layout, VkShaderModule vert,
                                   VkShaderModule frag, const VkFormat *color_formats, uint32_t color_count,
                                   gpu_blend blend, const char *name);
/* With specialization constants for the fragment shader (NULL: none). */
VkPipeline gpu_fullscreen_pipeline_spec(const gpu_context *ctx, VkPipelineLayout layout, VkShaderModule vert,
                                        VkShaderModule frag, const VkSpecializationInfo *frag_spec,
                                        const VkFormat *color_formats, uint32_t color_count, gpu_blend blend,
                                        const char *name);

/* Descriptor writes, terse. */
void gpu_write_uniform(const gpu_context *ctx, VkDescriptorSet set, uint32_t binding, VkBuffer buffer, VkDeviceSize size);
void gpu_write_sampled(const gpu_context *ctx, VkDescriptorSet set, uint32_t binding, VkImageView view, VkSampler sampler);
void gpu_write_storage(const gpu_context *ctx, VkDescriptorSet set, uint32_t binding, VkImageView view);
VkDescriptorSet gpu_alloc_set(const gpu_context *ctx, VkDescriptorPool pool, VkDescriptorSetLayout layout, const char *name);
VkSampler gpu_linear_clamp_sampler(const gpu_context *ctx, const char *name);

/* Begin dynamic rendering over a full image view (one or more colour attachments). */
typedef struct gpu_attachment { VkImageView view; VkAttachmentLoadOp load; } gpu_attachment;
void gpu_begin_rendering(VkCommandBuffer cmd, VkExtent2D extent, const gpu_attachment *attachments, uint32_t count);
#endif
