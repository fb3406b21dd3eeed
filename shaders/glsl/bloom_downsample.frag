#version 450
/* Bloom downsample (fragment chain): one level per pass, the filter in bloom_filter.glsl. */
#extension GL_GOOGLE_include_directive : require
#include "shared.h"
#include "bloom_filter.glsl"

layout(set = 0, binding = VKSKY_BINDING_POST_SOURCE) uniform sampler2D src;
layout(push_constant) uniform Push { BloomPush push; };
layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_color;

void main()
{
    vec2 t = push.src_texel.xy;
    vec3 s[13];
    for (int i = 0; i < 13; ++i) s[i] = texture(src, in_uv + t * BLOOM_TAPS[i]).rgb;
    out_color = vec4(bloom_filter13(s, push.src_texel.z > 0.5, push.src_texel.w), 1.0);
}
