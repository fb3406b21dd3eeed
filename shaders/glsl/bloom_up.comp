#version 450
/* Bloom upsample, compute chain: mip i += tent(mip i + 1), one thread per texel of mip i (the fragment chain's
 * blend ONE + ONE as a read-modify-write). Both mips stay in GENERAL; they are different subresources. */
#extension GL_GOOGLE_include_directive : require
#include "shared.h"
#include "bloom_filter.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = VKSKY_BINDING_POST_SOURCE) uniform sampler2D src;                 /* mip i + 1 */
layout(set = 0, binding = VKSKY_BINDING_POST_MIP, rgba16f) uniform image2D dst;          /* mip i */
layout(push_constant) uniform Push { PostPush push; };

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(dst);
    if (any(greaterThanEqual(p, size))) return;
    vec2 uv = (vec2(p) + 0.5) / vec2(size);
    vec3 c = imageLoad(dst, p).rgb + min(bloom_tent9(src, uv, push.params.xy), vec3(65504.0));
    imageStore(dst, p, vec4(min(c, vec3(65504.0)), 1.0));
}
