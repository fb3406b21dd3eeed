#version 460
#extension GL_GOOGLE_include_directive : require
// A host's compute shader reading vksky's LUTs through the installed include (compiled by tests/api/api_install.sh).
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D transmittance_lut;
layout(set = 0, binding = 1) uniform sampler2D multiscatter_lut;
layout(set = 0, binding = 2) uniform sampler2D skyview_lut;
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D result;
layout(push_constant) uniform Host { vec4 radii_km; vec4 sun; } host;   // x bottom, y top; sun: xyz direction
#define VKSKY_BOTTOM_RADIUS_KM host.radii_km.x
#define VKSKY_TOP_RADIUS_KM host.radii_km.y
#define VKSKY_TRANSMITTANCE_LUT transmittance_lut
#define VKSKY_MULTISCATTER_LUT multiscatter_lut
#define VKSKY_SKYVIEW_LUT skyview_lut
#include "vksky_luts.glsl"

float ground_radius() { return 0.0; }   // the host's own names stay its own

void main()
{
    vec2 uv = (vec2(gl_GlobalInvocationID.xy) + 0.5) / vec2(imageSize(result));
    float mu = 2.0 * uv.x - 1.0, h = 100.0 * uv.y;
    vec3 c = vksky_transmittance(h, host.sun.y) * vksky_skyview(0.001, mu, 1.0) + vksky_multiscatter(h, mu);
    imageStore(result, ivec2(gl_GlobalInvocationID.xy), vec4(c, ground_radius()));
}
