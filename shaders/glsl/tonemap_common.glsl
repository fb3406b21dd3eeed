/* Tone map: exposure, then clamp / Reinhard / ACES (Narkowicz's fit), to the display target. With
 * VKSKY_COMPOSITE it also writes the scene-linear HDR + bloom composite (the EXR's pixels). */
#include "shared.h"

layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(set = 0, binding = 1) uniform sampler2D bloom;
layout(push_constant) uniform Push { TonemapPush push; };
layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_display;
#ifdef VKSKY_COMPOSITE
layout(location = 1) out vec4 out_linear;
#endif

vec3 aces_fitted(vec3 x)
{
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
vec3 srgb_encode(vec3 c)
{
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main()
{
    vec3 color = texture(hdr, in_uv).rgb;
    if (push.params.z > 0.0) color += push.params.z * texture(bloom, in_uv).rgb;
    color = min(color, vec3(65504.0));
#ifdef VKSKY_COMPOSITE
    out_linear = vec4(color, 1.0);
#endif
    vec3 x = color * push.params.x;
    int op = int(push.params.y);
    vec3 mapped = op == VKSKY_TONEMAP_ACES ? aces_fitted(x)
                : op == VKSKY_TONEMAP_REINHARD ? x / (1.0 + x)
                : clamp(x, 0.0, 1.0);
    if (push.params.w > 0.5) mapped = srgb_encode(mapped);
    out_display = vec4(mapped, 1.0);
}
