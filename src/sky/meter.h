/* Auto exposure's meter on the GPU (issue 32): the log-average luminance of the HDR image in two compute dispatches
 * (shaders/glsl/meter.comp), written into a small buffer that the tone map of the same frame reads. No CPU round
 * trip, no second render. The frame spine (frame.c) records it between the sky pass and the post chain and owns its
 * barriers; the buffer holds one result per frame in flight (VKSKY_METER_SLOTS) for the host to read afterwards. */
#ifndef VKSKY_SKY_METER_H
#define VKSKY_SKY_METER_H
#include "sky/passes.h"

/* What the host reads back from a slot (shared.h's result: meter.comp). */
typedef struct meter_result {
    float log_average;           /* cd/m2 (the light_scale divided out) */
    float ev100;                 /* log2(log_average 100 / 12.5) */
    float multiplier;            /* the tone map's: 1 / (light_scale 1.2 2^EV100) */
    float count;                 /* texels counted */
} meter_result;

typedef struct meter_pass {
    gpu_buffer buffer;           /* vec4 result[VKSKY_METER_SLOTS], vec4 adapted, then vec2 partial[tiles] */
    VkExtent2D tiles;            /* pass 0's workgroups: one per VKSKY_METER_TILE^2 texels of the HDR image */
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;         /* made at the first dispatch: most runs never meter (EXR, relative units) */
    VkDescriptorSet set;
    const gpu_context *ctx;
} meter_pass;

/* For an HDR image (its view sampled; the set from the renderer's size pool). */
void meter_create(meter_pass *m, const pass_shared *s, VkDescriptorPool pool, const gpu_image *hdr);
void meter_destroy(meter_pass *m, const pass_shared *s);
/* Point a descriptor set's VKSKY_BINDING_METER at the meter's buffer (the tone maps' sets). */
void meter_write_descriptor(const gpu_context *ctx, VkDescriptorSet set, const meter_pass *m);
/* Pass 0 (per-tile sums of rows first_row .. first_row + rows - 1 of the HDR image: a band's own rows; rows 0: every
 * row; a fisheye's texels outside its circle never: whole_row0 is the whole image's row of the HDR image's row 0) and
 * pass 1 (the average into result[slot]); the spine puts a barrier between them.
 * scale: the HDR image's units per cd/m2; all_pixels: a lit ground (every texel counts; else sky texels only);
 * ease: temporal adaptation, the fraction of the way from the last frame's EV100 to the metered one (0 or >= 1:
 * none, the metered EV100). */
void meter_record_tiles(meter_pass *m, VkCommandBuffer cmd, double scale, bool all_pixels, uint32_t first_row,
                        uint32_t rows, bool fisheye, int whole_row0);
void meter_record_average(meter_pass *m, VkCommandBuffer cmd, double scale, bool all_pixels, uint32_t slot,
                          double ease);
/* The result of a slot, once the frame that wrote it is done (its fence waited); invalidates the mapping. */
meter_result meter_read(const gpu_context *ctx, const meter_pass *m, uint32_t slot);
#endif
