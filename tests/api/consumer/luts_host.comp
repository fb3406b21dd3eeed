#version 460
#extension GL_GOOGLE_include_directive : require
// A host's compute shader reading vksky's LUTs through the installed include: row 0 the transmittance from 1 km
// along zenith cosines 0.05..1, row 1 the multi-scattering term there for the sun at those cosines, row 2 the sky-view
// LUT's radiance from 1 m towards the sun's azimuth. Compiled by tests/api (api_render luts, the drop probe) and by
// tests/api/api_install.sh against an installed prefix.
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D transmittance_lut;
layout(set = 0, binding = 1) uniform sampler2D multiscatter_lut;
layout(set = 0, binding = 2) uniform sampler2D skyview_lut;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D result;
layout(push_constant) uniform Host { vec4 radii_km; } host;   // x bottom, y top (vksky_luts)
#define VKSKY_BOTTOM_RADIUS_KM host.radii_km.x
#define VKSKY_TOP_RADIUS_KM host.radii_km.y
#define VKSKY_TRANSMITTANCE_LUT transmittance_lut
#define VKSKY_MULTISCATTER_LUT multiscatter_lut
#define VKSKY_SKYVIEW_LUT skyview_lut
#include "vksky_luts.glsl"

float ground_radius() { return 0.0; }   // the host's own names stay its own after the include

void main()
{
    int i = int(gl_GlobalInvocationID.x), n = imageSize(result).x;
    if (i >= n) return;
    float mu = mix(0.05, 1.0, float(i) / float(n - 1));
    imageStore(result, ivec2(i, 0), vec4(vksky_transmittance(1.0, mu), 1.0 + ground_radius()));
    imageStore(result, ivec2(i, 1), vec4(vksky_multiscatter(1.0, mu), 1.0));
    imageStore(result, ivec2(i, 2), vec4(vksky_skyview(0.001, mu, 1.0), 1.0));
}
