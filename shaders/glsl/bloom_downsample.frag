#version 450
/* Bloom downsample: Jimenez's 13-tap filter (SIGGRAPH 2014). The first pass (from the HDR image) applies a
 * Karis average per 2x2 group, which tames the sun's fireflies, and a brightness threshold. */
#extension GL_GOOGLE_include_directive : require
#include "shared.h"

layout(set = 0, binding = 0) uniform sampler2D src;
layout(push_constant) uniform Push { BloomPush push; };
layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_color;

float luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
/* One 2x2 group: its average and its weight (the filter's weight, times 1/(1 + luma) when Karis-averaging). */
void add_group(inout vec3 sum, inout float weight_sum, vec3 a, vec3 b, vec3 c, vec3 d, float w, bool karis)
{
    vec3 avg = 0.25 * (a + b + c + d);
    float wk = karis ? w / (1.0 + luma(avg)) : w;
    sum += wk * avg;
    weight_sum += wk;
}

void main()
{
    vec2 t = push.src_texel.xy;
    vec3 a = texture(src, in_uv + t * vec2(-2, -2)).rgb, b = texture(src, in_uv + t * vec2(0, -2)).rgb;
    vec3 c = texture(src, in_uv + t * vec2(2, -2)).rgb,  d = texture(src, in_uv + t * vec2(-1, -1)).rgb;
    vec3 e = texture(src, in_uv + t * vec2(1, -1)).rgb,  f = texture(src, in_uv + t * vec2(-2, 0)).rgb;
    vec3 g = texture(src, in_uv).rgb,                    h = texture(src, in_uv + t * vec2(2, 0)).rgb;
    vec3 i = texture(src, in_uv + t * vec2(-1, 1)).rgb,  j = texture(src, in_uv + t * vec2(1, 1)).rgb;
    vec3 k = texture(src, in_uv + t * vec2(-2, 2)).rgb,  l = texture(src, in_uv + t * vec2(0, 2)).rgb;
    vec3 m = texture(src, in_uv + t * vec2(2, 2)).rgb;

    bool first = push.src_texel.z > 0.5;
    vec3 sum = vec3(0.0);
    float weight_sum = 0.0;
    add_group(sum, weight_sum, d, e, i, j, 0.5, first);
    add_group(sum, weight_sum, a, b, f, g, 0.125, first);
    add_group(sum, weight_sum, b, c, g, h, 0.125, first);
    add_group(sum, weight_sum, f, g, k, l, 0.125, first);
    add_group(sum, weight_sum, g, h, l, m, 0.125, first);
    vec3 color = sum / weight_sum;
    if (first) {
        /* Brightness threshold: keep only the part of each pixel above it, hue preserved. */
        float lum = luma(color);
        color *= max(lum - push.src_texel.w, 0.0) / max(lum, 1e-4);
    }
    out_color = vec4(min(color, vec3(65504.0)), 1.0);
}
