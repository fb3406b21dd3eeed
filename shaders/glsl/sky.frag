#version 450
/* Sky pass, fragment path: one full-screen triangle into the HDR colour attachment. */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"
#include "sky_bindings.glsl"
#include "sky_common.glsl"
#include "projection.glsl"
#include "horizon.glsl"

layout(location = 0) out vec4 out_color;

void main()
{
    out_color = sky_pixel(gl_FragCoord.xy, push);   /* alpha: the signed distance to the horizon */
}
