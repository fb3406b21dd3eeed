/* The spectral groups summed on the GPU (issue 32; docs/spectral.md "The sum on the GPU"): a float32 accumulation
 * image that each group's frame adds its scene-linear image into, times its channels' XYZ weights
 * (shaders/glsl/spectral_sum.comp), and a host-visible buffer the last group resolves the sum into, linear Rec.709:
 * one readback a frame. The frame spine records the step in place of a group frame's readback copies (frame.c). */
#ifndef VKSKY_SKY_SPECTRAL_SUM_H
#define VKSKY_SKY_SPECTRAL_SUM_H
#include "gpu/barrier.h"
#include "gpu/context.h"
#include "gpu/resources.h"
#include "shared.h"
#include <stdbool.h>

#define SPECTRAL_SUM_SETS 17   /* one descriptor set per group: 48 wavelengths three to a pass, plus one */

typedef struct spectral_sum {
    const gpu_context *ctx;
    VkExtent2D extent;
    gpu_image accum;               /* RGBA32F: X, Y, Z, unused; GENERAL once written */
    gpu_buffer resolved;           /* host-visible: width x height x vec4 (linear Rec.709, alpha) */
    bool accum_written;            /* a step was recorded: the image is in GENERAL, its last use a compute RW */
    VkSampler nearest;
    VkDescriptorPool pool;
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    VkDescriptorSet set[SPECTRAL_SUM_SETS];
    VkImageView bound[SPECTRAL_SUM_SETS];   /* the group image each set names (written again when it changes) */
} spectral_sum;

/* One group's step of a frame (frame_desc.sum). */
typedef struct spectral_sum_step {
    spectral_sum *sum;
    uint32_t group;                /* < SPECTRAL_SUM_SETS: the descriptor set naming this group's image */
    SpectralSumPush push;          /* weights, first / last, alpha, width, the matrix (spectral_sum_push_fill) */
} spectral_sum_step;

void spectral_sum_create(spectral_sum *s, const gpu_context *ctx, uint32_t width, uint32_t height);
void spectral_sum_destroy(spectral_sum *s);
/* The push constants of a step: weights[c] the XYZ per unit of channel c, the matrix spectrum_xyz_to_rec709's. */
void spectral_sum_push_fill(SpectralSumPush *p, const double weights[4][3], bool first, bool last, bool alpha_from_group,
                            uint32_t width);
/* The step after a group frame's tone map, recorded by the frame spine (frame.c, record_spectral_sum: its barriers):
 * the group image named in the step's descriptor set (before the barriers), then the dispatch. */
void spectral_sum_bind(const spectral_sum_step *step, const gpu_image *group_image);
void spectral_sum_dispatch(const spectral_sum_step *step, VkCommandBuffer cmd);
#endif
