/* The passes of a frame. Each owns its pipelines and descriptor sets and records its own dispatch or draw;
 * the frame spine (frame.c) owns their order and every barrier between them. */
#ifndef VKSKY_SKY_PASSES_H
#define VKSKY_SKY_PASSES_H
#include "gpu/barrier.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "shared.h"

#define TRANSMITTANCE_LUT_WIDTH 256
#define TRANSMITTANCE_LUT_HEIGHT 64
#define MULTISCATTER_LUT_SIZE 32
#define BLOOM_MIPS 5
#define HDR_FORMAT VK_FORMAT_R16G16B16A16_SFLOAT

/* What every pass shares: descriptor pool, sampler, the atmosphere uniform buffer, the full-screen vertex shader. */
typedef struct pass_shared {
    const gpu_context *ctx;
    VkDescriptorPool pool;
    VkSampler linear_clamp;
    gpu_buffer atmosphere_ubo;
    VkShaderModule fullscreen_vs;
} pass_shared;

/* --- LUT compute passes (luts.c) --- */
typedef struct sky_luts {
    gpu_image transmittance, multiscatter;
    VkDescriptorSetLayout transmittance_set_layout, multiscatter_set_layout;
    VkPipelineLayout transmittance_layout, multiscatter_layout;
    VkPipeline transmittance_pipeline, multiscatter_pipeline;
    VkDescriptorSet transmittance_set, multiscatter_set;
} sky_luts;
void luts_create(sky_luts *l, const pass_shared *s);
void luts_destroy(sky_luts *l, const pass_shared *s);
void luts_record_transmittance(const sky_luts *l, VkCommandBuffer cmd);
void luts_record_multiscatter(const sky_luts *l, VkCommandBuffer cmd);

/* --- Sky pass (sky_pass.c): per-pixel march into the HDR target --- */
typedef struct sky_pass {
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    VkDescriptorSet set;
} sky_pass;
void sky_pass_create(sky_pass *p, const pass_shared *s, const sky_luts *luts);
void sky_pass_destroy(sky_pass *p, const pass_shared *s);
void sky_pass_record(const sky_pass *p, VkCommandBuffer cmd, const gpu_image *hdr, const SkyPush *push);

/* --- Bloom (bloom.c): 5 downsamples into a mip chain, 4 additive upsamples back to mip 0 --- */
typedef struct bloom_chain {
    gpu_image mips;                          /* half the HDR size at mip 0 */
    uint32_t mip_count;
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline down_pipeline, up_pipeline;
    VkDescriptorSet down_sets[BLOOM_MIPS];   /* down_sets[i] samples the source of mip i */
    VkDescriptorSet up_sets[BLOOM_MIPS];     /* up_sets[i] samples mip i + 1 */
    VkExtent2D hdr_extent;
} bloom_chain;
void bloom_create(bloom_chain *b, const pass_shared *s, const gpu_image *hdr);
void bloom_destroy(bloom_chain *b, const pass_shared *s);
/* Downsample into mip `dst` (from the HDR image for dst 0, else from mip dst - 1). */
void bloom_record_downsample(const bloom_chain *b, VkCommandBuffer cmd, uint32_t dst, float threshold);
/* Upsample mip dst + 1 and add it onto mip dst. */
void bloom_record_upsample(const bloom_chain *b, VkCommandBuffer cmd, uint32_t dst);

/* --- Tone map (tonemap.c): HDR + bloom -> display target (and the linear composite, for EXR output) --- */
typedef struct tonemap_pass {
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    VkDescriptorSet set;
    bool composite;
} tonemap_pass;
/* `bloom_view` may be the HDR view when bloom is off (its strength is then 0). */
void tonemap_create(tonemap_pass *t, const pass_shared *s, VkImageView hdr_view, VkImageView bloom_view,
                    VkFormat display_format, bool composite);
void tonemap_destroy(tonemap_pass *t, const pass_shared *s);
void tonemap_record(const tonemap_pass *t, VkCommandBuffer cmd, VkExtent2D extent, VkImageView display,
                    VkImageView composite, const TonemapPush *push);
#endif
