#version 450
/* The host's own tone map: exposure, Reinhard, into an sRGB swapchain image (the format encodes). */
layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(push_constant) uniform Push { float exposure; } push;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
void main()
{
    vec3 c = texture(hdr, uv).rgb * push.exposure;
    color = vec4(c / (1.0 + c), 1.0);
}
