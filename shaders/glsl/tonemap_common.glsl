/* Tone map: exposure, then clamp / Reinhard / ACES (Narkowicz's fit), to the display target. With
 * VKSKY_COMPOSITE it also writes the scene-linear HDR + bloom composite (the EXR's pixels). */
#include "shared.h"
#include "tonemap_ops.glsl"

layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(set = 0, binding = 1) uniform sampler2D bloom;
layout(push_constant) uniform Push { TonemapPush push; };
layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_display;
#ifdef VKSKY_COMPOSITE
layout(location = 1) out vec4 out_linear;
#endif

void main()
{
    vec3 color = texture(hdr, in_uv).rgb;
    if (push.params.z > 0.0) color += push.params.z * texture(bloom, in_uv).rgb;
    color = min(color, vec3(65504.0));
#ifdef VKSKY_COMPOSITE
    out_linear = vec4(color, 1.0);
#endif
    out_display = vec4(tonemap_apply(color, push.params), 1.0);
}
