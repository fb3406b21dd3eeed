/* SPIR-V compiled from shaders/glsl at build time, embedded in the binary. */
#ifndef VKSKY_SKY_SHADERS_H
#define VKSKY_SKY_SHADERS_H
#include <stddef.h>
#include <stdint.h>

typedef struct sky_spirv { const uint32_t *code; size_t size; } sky_spirv;
extern const sky_spirv spirv_transmittance_lut, spirv_transmittance_lut_f32, spirv_multiscatter_lut,
    spirv_multiscatter_lut_f32, spirv_skyview_lut, spirv_ground_irradiance_lut, spirv_fullscreen_vert, spirv_sky_march_frag, spirv_sky_lookup_frag,
    spirv_sky_march_comp, spirv_sky_lookup_comp, spirv_sky_fill_frag, spirv_sky_fill_comp, spirv_sky_blend_frag,
    spirv_sky_blend_comp,
    spirv_bloom_downsample, spirv_bloom_upsample, spirv_tonemap, spirv_tonemap_composite;
/* The four-wide spectral build (SPECTRAL4; docs/spectral.md "Four to a texel"). */
extern const sky_spirv spirv_transmittance_lut_s4, spirv_transmittance_lut_f32_s4, spirv_multiscatter_lut_s4,
    spirv_multiscatter_lut_f32_s4, spirv_skyview_lut_s4, spirv_ground_irradiance_lut_s4, spirv_sky_march_frag_s4,
    spirv_sky_lookup_frag_s4, spirv_sky_blend_frag_s4, spirv_sky_march_comp_s4, spirv_sky_lookup_comp_s4,
    spirv_sky_blend_comp_s4, spirv_tonemap_composite_s4, spirv_tonemap_composite_comp_s4;
/* A hash of all the embedded SPIR-V (generated at build time): the pipeline cache's build key. */
const char *sky_shaders_key(void);
/* A hash of the sky image's SPIR-V only (the LUT and sky passes, RGB and four-wide): what the measured quality tables
 * record (app/quality), so a change to the post chain or the composite does not unmeasure them. */
const char *sky_image_shaders_key(void);
#endif
