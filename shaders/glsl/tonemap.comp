#version 450
/* Tone map, compute chain: one thread per output pixel. Fused with the last bloom upsample: the fragment chain
 * adds tent(mip 1) onto mip 0 at mip 0's texels and the tone map then samples mip 0 bilinearly; here both are
 * evaluated at the output pixel (bilinear mip 0 + the tent of mip 1 there), so mip 0 is never written twice.
 * Writes the display image (8-bit UNORM storage; sRGB encoded here, storage images cannot be sRGB) and, with
 * VKSKY_COMPOSITE, the scene-linear composite. */
#extension GL_GOOGLE_include_directive : require
#include "shared.h"
#include "bloom_filter.glsl"
#include "tonemap_ops.glsl"
#include "hdr_upsample.glsl"
#include "dither.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = VKSKY_BINDING_POST_SOURCE) uniform sampler2D hdr;
layout(set = 0, binding = VKSKY_BINDING_POST_MIP) uniform sampler2D bloom0;
layout(set = 0, binding = VKSKY_BINDING_POST_MIP + 1) uniform sampler2D bloom1;
layout(set = 0, binding = VKSKY_BINDING_TONEMAP_DISPLAY, rgba8) uniform writeonly image2D display;
#ifdef VKSKY_COMPOSITE
layout(set = 0, binding = VKSKY_BINDING_TONEMAP_COMPOSITE, rgba16f) uniform writeonly image2D composite;
#endif
layout(push_constant) uniform Push { PostPush push; };

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(display);
    if (any(greaterThanEqual(p, size))) return;
    vec2 uv = (vec2(p) + 0.5) / vec2(size);
    vec3 color = hdr_upsample(hdr, uv, size, hdr_rows(textureSize(hdr, 0), push.dither));
    float strength = push.tonemap.z;
    if (strength > 0.0) {
        vec3 b = textureLod(bloom0, uv, 0.0).rgb;
        if (push.bloom.z > 0.5) b += min(bloom_tent9(bloom1, uv, push.bloom.xy), vec3(65504.0));
        color += strength * min(b, vec3(65504.0));
    }
    color = min(color, vec3(65504.0));
#ifdef VKSKY_COMPOSITE
#ifdef SPECTRAL4
    /* The four-wide spectral build: the sky texel's four wavelengths as they are (tonemap_common.glsl). */
    imageStore(composite, p, min(textureLod(hdr, uv, 0.0), vec4(65504.0)));
#else
    imageStore(composite, p, vec4(color, 1.0));
#endif
#endif
    vec3 mapped = tonemap_apply(color, tonemap_exposed(push.tonemap, push.meter));
    imageStore(display, p, vec4(dither_display(mapped, p, push.dither, push.tonemap.w > 0.5), 1.0));
}
