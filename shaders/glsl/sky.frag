#version 450
/* Sky pass: per-pixel march of the atmosphere into the HDR target. */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"

layout(set = 0, binding = 1) uniform sampler2D transmittance_lut;
layout(set = 0, binding = 2) uniform sampler2D multiscatter_lut;
layout(push_constant) uniform Push { SkyPush push; };
layout(location = 0) out vec4 out_color;

#include "sky_common.glsl"

void main()
{
    vec3 v = pixel_view_dir(gl_FragCoord.xy, vec2(push.up.w, push.sun_dir.w), push);
    out_color = vec4(sky_radiance(push.forward.w, v, push.sun_dir.xyz, int(push.right.w)), 1.0);
}
