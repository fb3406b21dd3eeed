#version 450
/* Bloom downsample, compute chain, one level per dispatch (--bloom-downsample levels): the fragment chain's
 * filter as a compute shader, one thread per texel of mip k, sampling mip k-1 (the HDR image for k = 0) through
 * the sampler exactly as bloom_downsample.frag does. The frame spine puts a barrier between the levels. */
#extension GL_GOOGLE_include_directive : require
#include "shared.h"
#include "bloom_filter.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = VKSKY_BINDING_POST_SOURCE) uniform sampler2D src;
layout(set = 0, binding = VKSKY_BINDING_POST_MIP, rgba16f) uniform writeonly image2D dst;
layout(push_constant) uniform Push { PostPush push; };   /* params: xy 1/source size, z 1 = first level, w threshold */

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(dst);
    if (any(greaterThanEqual(p, size))) return;
    vec2 uv = (vec2(p) + 0.5) / vec2(size);
    vec3 s[13];
    for (int i = 0; i < 13; ++i) s[i] = textureLod(src, uv + push.params.xy * BLOOM_TAPS[i], 0.0).rgb;
    imageStore(dst, p, vec4(bloom_filter13(s, push.params.z > 0.5, push.params.w), 1.0));
}
