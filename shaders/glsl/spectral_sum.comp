#version 450
/* The spectral sum (issue 32, docs/spectral.md "The sum on the GPU"): one dispatch per wavelength group, after the
 * group's frame. It adds the group's scene-linear image (the renderer's composite, RGBA16F: one wavelength per
 * channel) times each channel's XYZ weights into the float32 accumulation image; after the last group it turns the
 * XYZ sum into linear Rec.709 (D65, the matrix of spectrum_xyz_to_rec709, pushed) and writes it, RGBA float32, into the
 * host-visible output buffer: one readback a frame instead of one per group. */
#extension GL_GOOGLE_include_directive : require
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = VKSKY_BINDING_SPECTRAL_GROUP) uniform sampler2D group_image;
layout(set = 0, binding = VKSKY_BINDING_SPECTRAL_SUM, rgba32f) uniform image2D sum;
layout(std430, set = 0, binding = VKSKY_BINDING_SPECTRAL_RESOLVED) writeonly buffer Resolved { vec4 pixel[]; } resolved;
layout(push_constant) uniform Push { SpectralSumPush push; };

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(sum);
    if (any(greaterThanEqual(p, size))) return;
    vec4 v = texelFetch(group_image, p, 0);
    vec3 xyz = push.mode.x > 0.5 ? vec3(0.0) : imageLoad(sum, p).xyz;
    xyz += push.weight[0].xyz * v.x;
    xyz += push.weight[1].xyz * v.y;
    xyz += push.weight[2].xyz * v.z;
    xyz += push.weight[3].xyz * v.w;
    if (push.mode.y < 0.5) {
        imageStore(sum, p, vec4(xyz, 0.0));
        return;
    }
    float alpha = push.mode.z > 0.5 ? v.w : 1.0;
    resolved.pixel[p.y * int(push.mode.w) + p.x] = vec4(dot(push.to_rec709[0].xyz, xyz), dot(push.to_rec709[1].xyz, xyz),
                                                     dot(push.to_rec709[2].xyz, xyz), alpha);
}
