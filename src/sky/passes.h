/* The passes of a frame. Each owns its pipelines and descriptor sets and records its own dispatch or draw;
 * the frame spine (frame.c) owns their order and every barrier between them. */
#ifndef VKSKY_SKY_PASSES_H
#define VKSKY_SKY_PASSES_H
#include "gpu/barrier.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "shared.h"

#include "sky/atmosphere.h"

#define BLOOM_MAX_MIPS 8
#define HDR_FORMAT VK_FORMAT_R16G16B16A16_SFLOAT

/* What every pass shares: descriptor pool, sampler, the atmosphere uniform buffer, the full-screen vertex shader. */
typedef struct pass_shared {
    const gpu_context *ctx;
    VkDescriptorPool pool;
    VkSampler linear_clamp;
    gpu_buffer atmosphere_ubo;
    VkShaderModule fullscreen_vs;
    const VkSpecializationInfo *spec;   /* the scene's variant, for every shader that includes atmosphere.glsl */
    bool spectral4;                     /* the four-wide spectral build's SPIR-V (sky_renderer_desc.spectral4) */
} pass_shared;

/* --- LUT compute passes (luts.c): transmittance and multi-scattering (when the atmosphere changes), sky-view
 * (every frame, fast path) --- */
typedef struct sky_luts {
    gpu_image transmittance, multiscatter, skyview, ground_irradiance;
    VkDescriptorSetLayout transmittance_set_layout, multiscatter_set_layout, skyview_set_layout;
    VkPipelineLayout transmittance_layout, multiscatter_layout, skyview_layout;
    VkPipeline transmittance_pipeline, multiscatter_pipeline, skyview_pipeline;
    VkDescriptorSet transmittance_set, multiscatter_set, skyview_set;
    /* The multiscatter pass's second run with a lit ground: its ground lit by the sky (the ground-irradiance LUT). */
    VkDescriptorSet multiscatter_ground_set;
    /* What readers bind as the multi-scattering LUT: the LUT, or without multi-scattering (no image, no pass)
     * the transmittance LUT as a stand-in the compiled-out code never samples. */
    VkImageView multiscatter_view;
    /* The sky's irradiance on the ground by sun angle (only with a lit ground; else the same kind of stand-in). */
    VkDescriptorSetLayout ground_set_layout;
    VkPipelineLayout ground_layout;
    VkPipeline ground_pipeline;
    VkDescriptorSet ground_set;
    VkImageView ground_irradiance_view;
    uint32_t multiscatter_parts;         /* N x N parts of the multi-scattering atlas (4 in the four-wide build) */
    /* Each pass's pipeline is made at its first record (luts_record_*): a LUT cache hit uploads the transmittance,
     * multi-scattering and ground LUTs and never makes theirs, a march never makes the sky-view LUT's. */
    const pass_shared *shared;
    const struct sky_spirv *transmittance_spv, *multiscatter_spv, *skyview_spv, *ground_spv;
} sky_luts;
/* multiscatter false: no multi-scattering LUT image, pipeline or pass. */
void luts_create(sky_luts *l, const pass_shared *s, const sky_lut_quality *q, bool multiscatter, bool ground);
void luts_destroy(sky_luts *l, const pass_shared *s);
void luts_record_transmittance(sky_luts *l, VkCommandBuffer cmd);
/* sky_lit_ground: the second pass of a lit ground (the ground lit by the sky too: the ground-irradiance LUT). */
void luts_record_multiscatter(sky_luts *l, VkCommandBuffer cmd, bool sky_lit_ground);
void luts_record_skyview(sky_luts *l, VkCommandBuffer cmd, const SkyPush *push);
void luts_record_ground_irradiance(sky_luts *l, VkCommandBuffer cmd);

/* --- Sky pass (sky_pass.c): per-pixel march, or sky-view LUT lookup, into the HDR target; as a full-screen
 * fragment pass or a compute dispatch --- */
/* FILL writes a constant: the bandwidth floor benchmarks compare against. */
typedef enum sky_mode { SKY_MODE_MARCH = 0, SKY_MODE_SKYVIEW = 1, SKY_MODE_FILL = 2 } sky_mode;
/* AUTO: fragment on a CPU implementation (lavapipe: ~10 % faster), compute on GPUs (datacenter parts run fragment
 * shaders on a few units only: 30x slower on an H200). */
typedef enum sky_pass_kind { SKY_PASS_FRAGMENT = 0, SKY_PASS_COMPUTE = 1, SKY_PASS_AUTO = 2 } sky_pass_kind;
typedef struct sky_pass {
    VkDescriptorSetLayout set_layouts[2];        /* [kind] */
    VkPipelineLayout layouts[2];                 /* [kind] */
    VkPipeline pipelines[2][4];                  /* [kind][mode] (3: lookup into march), made at first use */
    VkDescriptorSet sets[2];                     /* [kind]; the compute set also holds the HDR storage image */
    const pass_shared *shared;                   /* for the pipelines, made at their first use */
} sky_pass;
void sky_pass_create(sky_pass *p, const pass_shared *s, const sky_luts *luts);
void sky_pass_destroy(sky_pass *p, const pass_shared *s);
/* Point the compute path's storage binding at (a new) HDR image. */
void sky_pass_set_target(sky_pass *p, const pass_shared *s, const gpu_image *hdr);
void sky_pass_record(sky_pass *p, VkCommandBuffer cmd, sky_pass_kind kind, sky_mode mode,
                     const gpu_image *hdr, const SkyPush *push);

/* --- Bloom (bloom.c): N downsamples into a mip chain (5 by default), N-1 additive upsamples back to mip 0 --- */
typedef struct bloom_chain {
    gpu_image mips;                          /* half the HDR size at mip 0 */
    uint32_t mip_count;
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline down_pipeline, up_pipeline;
    VkDescriptorSet down_sets[BLOOM_MAX_MIPS];   /* down_sets[i] samples the source of mip i */
    VkDescriptorSet up_sets[BLOOM_MAX_MIPS];     /* up_sets[i] samples mip i + 1 */
    VkExtent2D hdr_extent;
} bloom_chain;
/* `mips` downsamples (5 by default), fewer if the image is too small for them; mip 0 at 1/2 (start 0) or 1/4
 * (start 1) of the HDR size. */
void bloom_create(bloom_chain *b, const pass_shared *s, const gpu_image *hdr, uint32_t mips, uint32_t start);
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
    VkPipeline far_pipeline[2];   /* hdr_upsample.glsl's far path only (the regions away from the horizon); [1]:
                                     the sky image is the output's size. Made at their first use: a run uses one
                                     of them, or none (no regions), and each is a pipeline to compile */
    VkDescriptorSet set;
    bool composite;
    const gpu_context *ctx;       /* what the far variants are made from, kept until then */
    VkShaderModule vs, fs;
    VkFormat formats[2];
} tonemap_pass;
/* `bloom_view` may be the HDR view when bloom is off (its strength is then 0). */
void tonemap_create(tonemap_pass *t, const pass_shared *s, VkImageView hdr_view, VkImageView bloom_view,
                    VkFormat display_format, bool composite);
void tonemap_destroy(tonemap_pass *t, const pass_shared *s);
/* `regions` (sky/tonemap_regions.h): each drawn by its pipeline under its scissor; NULL: the whole target, full.
 * hdr_full_size: the sky image is `extent` (render scale 1). */
typedef struct tonemap_regions tonemap_regions;
void tonemap_record(tonemap_pass *t, VkCommandBuffer cmd, VkExtent2D extent, VkImageView display,
                    VkImageView composite, const TonemapPush *push, const tonemap_regions *regions,
                    bool hdr_full_size);
#endif
