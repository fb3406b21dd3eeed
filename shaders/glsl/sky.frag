#version 450
/* Sky pass, fragment path: one full-screen triangle into the HDR colour attachment. */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"
#include "sky_bindings.glsl"
#include "sky_common.glsl"

layout(location = 0) out vec4 out_color;

void main()
{
    sky_texel_angle = texel_angle(push);
    vec3 v = pixel_view_dir(gl_FragCoord.xy, push);
    vec3 c = SKY_RADIANCE(push.forward.w, v, push.sun_dir.xyz, push.march);
    out_color = vec4(c, SKY_CLASS(push.forward.w, v, push.sun_dir.xyz));   /* alpha: the class */
}
