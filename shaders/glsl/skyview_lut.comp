#version 450
/* Sky-view LUT (Hillaire 2020, section 5.3): the in-scattered radiance (no sun disc) around the camera in
 * (azimuth from the sun, view zenith angle), recomputed every frame for the camera's altitude and the sun. */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = VKSKY_BINDING_TRANSMITTANCE_LUT) uniform sampler2D transmittance_lut;
layout(set = 0, binding = VKSKY_BINDING_MULTISCATTER_LUT) uniform sampler2D multiscatter_lut;
layout(set = 0, binding = VKSKY_BINDING_OUTPUT, rgba16f) uniform writeonly image2D skyview_out;
layout(set = 0, binding = VKSKY_BINDING_GROUND_IRRADIANCE_LUT) uniform sampler2D ground_irradiance_lut;
layout(push_constant) uniform Push { SkyPush push; };
#include "sky_common.glsl"

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(skyview_out);
    if (any(greaterThanEqual(p, size))) return;
    float h = push.forward.w;
    float mu, cos_azimuth;
    skyview_params((vec2(p) + 0.5) / vec2(size), h, vec2(size), mu, cos_azimuth);
    /* Local frame: up = +Y, the sun in the XY plane. */
    float mu_s = push.sun_dir.y;
    vec3 s = vec3(sqrt(max(0.0, 1.0 - mu_s * mu_s)), mu_s, 0.0);
    float sin_theta = sqrt(max(0.0, 1.0 - mu * mu));
    vec3 v = vec3(sin_theta * cos_azimuth, mu, sin_theta * sqrt(max(0.0, 1.0 - cos_azimuth * cos_azimuth)));
    spectrum_t throughput;
    bool hits_ground;
    spectrum_t radiance = sky_march(h, v, s, push.march, push.sun_dir.w, throughput, hits_ground);
    imageStore(skyview_out, p, SPECTRUM_TO_VEC4(min(radiance, spectrum_t(FP16_MAX)), 1.0));
}
