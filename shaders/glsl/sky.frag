#version 450
/* Sky pass, fragment path: one full-screen triangle into the HDR colour attachment. */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"
#include "sky_bindings.glsl"
#include "sky_common.glsl"
#include "projection.glsl"

layout(location = 0) out vec4 out_color;

void main()
{
    bool inside;
    vec3 v = pixel_view_dir(gl_FragCoord.xy, push, inside);
    sky_texel_angle = texel_angle(push);
    vec3 c = inside ? SKY_RADIANCE(push.forward.w, v, push.sun_dir.xyz, push.march) : vec3(0.0);
    out_color = vec4(c, inside ? SKY_CLASS(push.forward.w, v, push.sun_dir.xyz) : 1.0);   /* alpha: the class */
}
