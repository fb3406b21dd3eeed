#version 450
/* Bloom upsample: 9-tap tent filter of the smaller mip, added (blend ONE + ONE, load op LOAD) onto the larger
 * mip's downsampled contents. */
#extension GL_GOOGLE_include_directive : require
#include "shared.h"

layout(set = 0, binding = 0) uniform sampler2D src;
layout(push_constant) uniform Push { BloomPush push; };
layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_color;

void main()
{
    vec2 t = push.src_texel.xy;
    vec3 c = 4.0 * texture(src, in_uv).rgb;
    c += 2.0 * (texture(src, in_uv + vec2(t.x, 0)).rgb + texture(src, in_uv - vec2(t.x, 0)).rgb
              + texture(src, in_uv + vec2(0, t.y)).rgb + texture(src, in_uv - vec2(0, t.y)).rgb);
    c += texture(src, in_uv + t).rgb + texture(src, in_uv - t).rgb
       + texture(src, in_uv + vec2(t.x, -t.y)).rgb + texture(src, in_uv + vec2(-t.x, t.y)).rgb;
    out_color = vec4(min(c / 16.0, vec3(65504.0)), 0.0);
}
