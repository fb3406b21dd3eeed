#version 450
/* Lambert from the sun: radiance = albedo / pi x E x max(n . s, 0), E the sun's illuminance in vksky's units
 * (vksky_luts.sun_illuminance: the same units as the sky vksky writes). Alpha 1: geometry covers the pixel. */
layout(push_constant) uniform Push { mat4 view_proj; vec4 sun_dir; vec4 sun_illuminance; } push;
layout(location = 0) in vec3 v_normal;
layout(location = 1) in float v_albedo;
layout(location = 0) out vec4 color;
void main()
{
    float lambert = max(dot(normalize(v_normal), push.sun_dir.xyz), 0.0);
    color = vec4(v_albedo / 3.14159265 * push.sun_illuminance.rgb * lambert, 1.0);
}
