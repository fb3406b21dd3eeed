/* Tone map: exposure, then clamp / Reinhard / ACES (Narkowicz's fit), to the display target. With
 * VKSKY_COMPOSITE it also writes the scene-linear HDR + bloom composite (the EXR's pixels). */
#include "shared.h"
#include "tonemap_ops.glsl"
#include "hdr_upsample.glsl"
#include "dither.glsl"

layout(set = 0, binding = VKSKY_BINDING_POST_SOURCE) uniform sampler2D hdr;
layout(set = 0, binding = VKSKY_BINDING_POST_MIP) uniform sampler2D bloom;
layout(push_constant) uniform Push { TonemapPush push; };
layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_display;
#ifdef VKSKY_COMPOSITE
layout(location = 1) out vec4 out_linear;
#endif

void main()
{
    /* The output's size from the pixel centre and its uv (the full-screen triangle's uv is (x + 0.5) / width). */
    ivec2 out_size = ivec2(round(gl_FragCoord.xy / in_uv));
    vec3 color = hdr_upsample(hdr, in_uv, out_size, hdr_rows(textureSize(hdr, 0), push.dither));
    if (push.params.z > 0.0) color += push.params.z * texture(bloom, in_uv).rgb;
    color = min(color, vec3(65504.0));
#ifdef VKSKY_COMPOSITE
#ifdef SPECTRAL4
    /* The four-wide spectral build: the sky texel's four wavelengths as they are (render scale 1, no bloom: the host
     * sums the groups' linear images into colour; docs/spectral.md "Four to a texel"). */
    out_linear = min(textureLod(hdr, in_uv, 0.0), vec4(65504.0));
#else
    out_linear = vec4(color, 1.0);
#endif
#endif
    vec3 mapped = tonemap_apply(color, tonemap_exposed(push.params, push.meter));
    out_display = vec4(dither_display(mapped, ivec2(gl_FragCoord.xy), push.dither, push.params.w > 0.5), 1.0);
}
