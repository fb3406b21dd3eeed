/* SPIR-V of the compute post chain (kept apart from shaders.c so the two chains' lists do not interleave). */
#include "sky/post.h"
#include "sky/shaders.h"
#include "bloom_spd_comp.h"
#include "bloom_up_comp.h"
#include "bloom_down_comp.h"
#include "tonemap_comp.h"
#include "tonemap_composite_comp.h"

#define SPIRV(var) {var, sizeof var}
const sky_spirv spirv_bloom_spd = SPIRV(spv_bloom_spd_comp);
const sky_spirv spirv_bloom_up_comp = SPIRV(spv_bloom_up_comp);
const sky_spirv spirv_bloom_down_comp = SPIRV(spv_bloom_down_comp);
const sky_spirv spirv_tonemap_comp = SPIRV(spv_tonemap_comp);
const sky_spirv spirv_tonemap_composite_comp = SPIRV(spv_tonemap_composite_comp);
