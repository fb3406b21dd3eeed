/* The compute post chain (post.c): bloom downsample in one dispatch (single-pass, bloom_spd.comp), the upsample
 * chain as compute dispatches, the tone map as a compute dispatch fused with the last upsample. The fragment
 * chain (bloom.c, tonemap.c) stays; --post-pass chooses, the frame spine (frame.c) records either and owns every
 * barrier. */
#ifndef VKSKY_SKY_POST_H
#define VKSKY_SKY_POST_H
#include "sky/passes.h"
#include "sky/shaders.h"

/* AUTO: like the sky pass, compute on GPUs, fragment on a CPU implementation. */
typedef enum post_pass_kind { POST_PASS_FRAGMENT = 0, POST_PASS_COMPUTE = 1, POST_PASS_AUTO = 2 } post_pass_kind;
/* The compute chain's downsample: one dispatch per level (the default: measured faster on an H100, docs/perf/),
 * or every level in one dispatch (the single pass, SPD-style). */
typedef enum bloom_downsample_kind { BLOOM_DOWN_LEVELS = 0, BLOOM_DOWN_SINGLE_PASS = 1 } bloom_downsample_kind;

/* AUTO resolved for the device (fragment on a CPU implementation, compute otherwise). */
post_pass_kind post_pass_resolve(post_pass_kind k, const gpu_context *ctx);

#define POST_HOST_SETS 8

typedef struct post_compute {
    VkDescriptorPool pool;                   /* its own: the sets below are rebuilt with the size */
    gpu_image counters;                      /* R32UI, one per level >= 1 tile: the single pass's tile counters */
    uint32_t counter_count;
    VkExtent2D level0_tiles;                 /* the dispatch: one workgroup per 16x16 tile of bloom mip 0 */
    VkDescriptorSetLayout spd_set_layout, up_set_layout, tonemap_set_layout;
    VkPipelineLayout spd_layout, up_layout, tonemap_layout;
    VkPipeline spd_pipeline, up_pipeline, tonemap_pipeline;
    VkDescriptorSet spd_set, tonemap_set;
    VkDescriptorSet up_sets[BLOOM_MAX_MIPS]; /* up_sets[i]: mip i += tent(mip i + 1) */
    VkPipeline down_pipeline;                /* per-level downsample (bloom_down.comp), same layout as the upsample */
    VkDescriptorSet down_sets[BLOOM_MAX_MIPS]; /* down_sets[k]: mip k from mip k - 1 (the HDR image for k = 0) */
    bool tonemap, composite;                 /* a compute tone map (own display image), writing the composite */
    uint32_t mip_count;                      /* 0: no bloom chain */
    /* The compute tone map into a library host's R8G8B8A8_UNORM storage image (vksky_display_config): a set per host
     * view, the least recently used rewritten for a new one (as host_frame.c's): a command buffer of one of the last
     * POST_HOST_SETS - 1 views may be pending. The meter's binding is written by renderer.c. */
    bool host_tonemap;
    VkDescriptorSet host_sets[POST_HOST_SETS];
    VkImageView host_views[POST_HOST_SETS];
    uint64_t host_used[POST_HOST_SETS], host_clock;
} post_compute;

/* `bloom` NULL: no chain (the tone map binds the HDR image in its place, strength 0). `display`: an 8-bit UNORM
 * storage view of the display image (VK_NULL_HANDLE: no compute tone map, e.g. a swapchain target); `composite`
 * the composite's view or VK_NULL_HANDLE. */
/* `host_targets`: also the sets of the tone map into a host's storage view (post_host_set). */
void post_compute_create(post_compute *p, const pass_shared *s, const gpu_image *hdr, const bloom_chain *bloom,
                         VkImageView display, VkImageView composite, bool host_targets);
/* The tone map's set naming the host's view (an R8G8B8A8_UNORM storage view): one already written for it, else the
 * least recently used one rewritten (no allocation per frame). */
VkDescriptorSet post_host_set(post_compute *p, const gpu_context *ctx, VkImageView view);
void post_compute_destroy(post_compute *p, const pass_shared *s);
/* Zero the tile counters (a clear command; the spine puts barriers around it). */
void post_record_clear_counters(const post_compute *p, VkCommandBuffer cmd);
/* Every bloom level in one dispatch. */
void post_record_downsample(const post_compute *p, VkCommandBuffer cmd, float threshold);
/* One level: mip dst from mip dst - 1 (the HDR image for 0), as the fragment chain does it. */
void post_record_downsample_level(const post_compute *p, const bloom_chain *bloom, VkCommandBuffer cmd, uint32_t dst,
                                  VkExtent2D hdr_extent, float threshold);
/* mip dst += tent(mip dst + 1). */
void post_record_upsample(const post_compute *p, const bloom_chain *bloom, VkCommandBuffer cmd, uint32_t dst);
/* HDR + bloom (mip 0 + the tent of mip 1: the last upsample, fused) -> display (+ composite). */
void post_record_tonemap(const post_compute *p, const bloom_chain *bloom, VkCommandBuffer cmd, VkExtent2D extent,
                         const TonemapPush *tm);
/* The same into the image of `set` (post_host_set's: a host's storage view). */
void post_record_tonemap_set(const post_compute *p, const bloom_chain *bloom, VkCommandBuffer cmd, VkExtent2D extent,
                             const TonemapPush *tm, VkDescriptorSet set);

extern const sky_spirv spirv_bloom_spd, spirv_bloom_up_comp, spirv_bloom_down_comp, spirv_tonemap_comp, spirv_tonemap_composite_comp;
#endif
