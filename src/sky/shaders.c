#include "sky/shaders.h"
#include "shader_key.h"
#include "sky_shader_key.h"
#include "transmittance_lut_comp.h"
#include "multiscatter_lut_comp.h"
#include "transmittance_lut_f32_comp.h"
#include "multiscatter_lut_f32_comp.h"
#include "skyview_lut_comp.h"
#include "ground_irradiance_lut_comp.h"
#include "sky_march_comp.h"
#include "sky_fill_comp.h"
#include "sky_fill_frag.h"
#include "sky_lookup_comp.h"
#include "sky_lookup_frag.h"
#include "sky_blend_comp.h"
#include "sky_blend_frag.h"
#include "fullscreen_vert.h"
#include "sky_march_frag.h"
#include "bloom_downsample_frag.h"
#include "bloom_upsample_frag.h"
#include "tonemap_frag.h"
#include "tonemap_composite_frag.h"
#include "transmittance_lut_s4_comp.h"
#include "transmittance_lut_f32_s4_comp.h"
#include "multiscatter_lut_s4_comp.h"
#include "multiscatter_lut_f32_s4_comp.h"
#include "skyview_lut_s4_comp.h"
#include "ground_irradiance_lut_s4_comp.h"
#include "sky_march_s4_frag.h"
#include "sky_lookup_s4_frag.h"
#include "sky_blend_s4_frag.h"
#include "sky_march_s4_comp.h"
#include "sky_lookup_s4_comp.h"
#include "sky_blend_s4_comp.h"
#include "tonemap_composite_s4_frag.h"
#include "tonemap_composite_s4_comp.h"

#define SPIRV(var) {var, sizeof var}
const sky_spirv spirv_transmittance_lut = SPIRV(spv_transmittance_lut_comp);
const sky_spirv spirv_multiscatter_lut = SPIRV(spv_multiscatter_lut_comp);
const sky_spirv spirv_transmittance_lut_f32 = SPIRV(spv_transmittance_lut_f32_comp);
const sky_spirv spirv_multiscatter_lut_f32 = SPIRV(spv_multiscatter_lut_f32_comp);
const sky_spirv spirv_skyview_lut = SPIRV(spv_skyview_lut_comp);
const sky_spirv spirv_ground_irradiance_lut = SPIRV(spv_ground_irradiance_lut_comp);
const sky_spirv spirv_sky_march_comp = SPIRV(spv_sky_march_comp);
const sky_spirv spirv_sky_fill_comp = SPIRV(spv_sky_fill_comp);
const sky_spirv spirv_sky_fill_frag = SPIRV(spv_sky_fill_frag);
const sky_spirv spirv_sky_lookup_comp = SPIRV(spv_sky_lookup_comp);
const sky_spirv spirv_sky_lookup_frag = SPIRV(spv_sky_lookup_frag);
const sky_spirv spirv_sky_blend_comp = SPIRV(spv_sky_blend_comp);
const sky_spirv spirv_sky_blend_frag = SPIRV(spv_sky_blend_frag);
const sky_spirv spirv_fullscreen_vert = SPIRV(spv_fullscreen_vert);
const sky_spirv spirv_sky_march_frag = SPIRV(spv_sky_march_frag);
const sky_spirv spirv_bloom_downsample = SPIRV(spv_bloom_downsample_frag);
const sky_spirv spirv_bloom_upsample = SPIRV(spv_bloom_upsample_frag);
const sky_spirv spirv_tonemap = SPIRV(spv_tonemap_frag);
const sky_spirv spirv_tonemap_composite = SPIRV(spv_tonemap_composite_frag);
const sky_spirv spirv_transmittance_lut_s4 = SPIRV(spv_transmittance_lut_s4_comp);
const sky_spirv spirv_transmittance_lut_f32_s4 = SPIRV(spv_transmittance_lut_f32_s4_comp);
const sky_spirv spirv_multiscatter_lut_s4 = SPIRV(spv_multiscatter_lut_s4_comp);
const sky_spirv spirv_multiscatter_lut_f32_s4 = SPIRV(spv_multiscatter_lut_f32_s4_comp);
const sky_spirv spirv_skyview_lut_s4 = SPIRV(spv_skyview_lut_s4_comp);
const sky_spirv spirv_ground_irradiance_lut_s4 = SPIRV(spv_ground_irradiance_lut_s4_comp);
const sky_spirv spirv_sky_march_frag_s4 = SPIRV(spv_sky_march_s4_frag);
const sky_spirv spirv_sky_lookup_frag_s4 = SPIRV(spv_sky_lookup_s4_frag);
const sky_spirv spirv_sky_blend_frag_s4 = SPIRV(spv_sky_blend_s4_frag);
const sky_spirv spirv_sky_march_comp_s4 = SPIRV(spv_sky_march_s4_comp);
const sky_spirv spirv_sky_lookup_comp_s4 = SPIRV(spv_sky_lookup_s4_comp);
const sky_spirv spirv_sky_blend_comp_s4 = SPIRV(spv_sky_blend_s4_comp);
const sky_spirv spirv_tonemap_composite_s4 = SPIRV(spv_tonemap_composite_s4_frag);
const sky_spirv spirv_tonemap_composite_comp_s4 = SPIRV(spv_tonemap_composite_s4_comp);

const char *sky_shaders_key(void) { return VKSKY_SHADER_KEY; }
const char *sky_image_shaders_key(void) { return VKSKY_SKY_SHADER_KEY; }
