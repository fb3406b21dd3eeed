#version 450
/* Bloom upsample (fragment chain): 9-tap tent filter of the smaller mip, added (blend ONE + ONE, load op LOAD)
 * onto the larger mip's downsampled contents. */
#extension GL_GOOGLE_include_directive : require
#include "shared.h"
#include "bloom_filter.glsl"

layout(set = 0, binding = VKSKY_BINDING_POST_SOURCE) uniform sampler2D src;
layout(push_constant) uniform Push { BloomPush push; };
layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_color;

void main()
{
    out_color = vec4(min(bloom_tent9(src, in_uv, push.src_texel.xy), vec3(65504.0)), 0.0);
}
