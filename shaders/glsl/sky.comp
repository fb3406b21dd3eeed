#version 450
/* Sky pass, compute path: one thread per pixel, imageStore into the HDR image (GENERAL layout). Same maths as
 * sky.frag; on GPUs with few fragment units (datacenter parts) this path uses every shader core. */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"
#include "sky_bindings.glsl"
#include "sky_common.glsl"
#include "projection.glsl"
#include "horizon.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = VKSKY_BINDING_OUTPUT, rgba16f) uniform writeonly image2D hdr_out;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(hdr_out)))) return;
    imageStore(hdr_out, p, sky_pixel(vec2(p) + 0.5, push));   /* alpha: the signed distance to the horizon */
}
