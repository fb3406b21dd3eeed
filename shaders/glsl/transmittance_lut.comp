#version 450
/* Transmittance LUT: T(h, mu) = exp(-optical depth to the top of the atmosphere), 256x64, one texel per thread. */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
#ifndef LUT_FORMAT
#define LUT_FORMAT rgba16f
#endif
layout(set = 0, binding = VKSKY_BINDING_OUTPUT, LUT_FORMAT) uniform writeonly image2D transmittance_out;

void main()
{
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, imageSize(transmittance_out)))) return;
    vec2 size = vec2(imageSize(transmittance_out));
    vec2 uv = (vec2(texel) + 0.5) / size;
    float h, mu;
    transmittance_params(uv, size, h, mu);

    int steps = int(atmo.lut_steps.x);
    float dt = distance_to_top(h, mu) / float(steps);
    /* Simpson's rule per step (ends and midpoint, the end shared with the next step): 40 midpoint samples
     * miss ~3e-3 of transmittance where a step is longer than Mie's 1.2 km scale height or straddles the
     * perigee of a grazing ray; Simpson's error there is ~1e-5. */
    spectrum_t optical_depth = spectrum_t(0.0);
    float r_t;
    spectrum_t sigma_a = sample_medium(h).extinction;
    for (int i = 0; i < steps; ++i) {
        spectrum_t sigma_m = sample_medium(altitude_along(h, mu, (float(i) + 0.5) * dt, r_t)).extinction;
        spectrum_t sigma_b = sample_medium(altitude_along(h, mu, float(i + 1) * dt, r_t)).extinction;
        optical_depth += dt / 6.0 * (sigma_a + 4.0 * sigma_m + sigma_b);
        sigma_a = sigma_b;
    }
    imageStore(transmittance_out, texel, SPECTRUM_TO_VEC4(exp(-optical_depth), 1.0));
}
