#version 450
/* Ground-irradiance LUT: the sky's irradiance on a horizontal ground point (altitude 0), per unit sun
 * illuminance, by sun zenith cosine (the multi-scattering LUT's mu_s mapping). One 64-thread workgroup per texel;
 * the threads share cosine-weighted hemisphere directions and march the sky (single + multiple scattering, no
 * sun disc) with the LUTs: E = pi x mean radiance. Computed with the other LUTs, only when the ground is lit. */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"

#define THREADS 64
layout(local_size_x = THREADS) in;
layout(set = 0, binding = VKSKY_BINDING_TRANSMITTANCE_LUT) uniform sampler2D transmittance_lut;
layout(set = 0, binding = VKSKY_BINDING_MULTISCATTER_LUT) uniform sampler2D multiscatter_lut;
#ifndef LUT_FORMAT
#define LUT_FORMAT rgba16f
#endif
layout(set = 0, binding = VKSKY_BINDING_OUTPUT, LUT_FORMAT) uniform writeonly image2D irradiance_out;
/* Upward directions never meet the ground: no ground term inside this march. */
#define GROUND_SKY_IRRADIANCE(mu_s) spectrum_t(0.0)
#include "sky_common.glsl"

shared spectrum_t shared_e[THREADS];
const int SQRT_DIRS = 16;
const int STEPS = 16;

void main()
{
    uint thread = gl_LocalInvocationIndex;
    float n = float(imageSize(irradiance_out).x);
    float mu_s = multiscatter_mu_s_of_x(sub_uv_to_unit((float(gl_WorkGroupID.x) + 0.5) / n, n));
    vec3 sun = vec3(sqrt(max(0.0, 1.0 - mu_s * mu_s)), mu_s, 0.0);
    vec4 march = vec4(STEPS, STEPS, 0.5, 100.0);
    spectrum_t sum = spectrum_t(0.0);
    for (int d = int(thread); d < SQRT_DIRS * SQRT_DIRS; d += THREADS) {
        /* Cosine-weighted stratified hemisphere: cos(theta) = sqrt(1 - u). */
        float u = (float(d / SQRT_DIRS) + 0.5) / float(SQRT_DIRS);
        float phi = 2.0 * PI * (float(d % SQRT_DIRS) + 0.5) / float(SQRT_DIRS);
        float cos_t = sqrt(1.0 - u), sin_t = sqrt(u);
        vec3 v = vec3(sin_t * cos(phi), cos_t, sin_t * sin(phi));
        spectrum_t throughput;
        bool hits_ground;
        sum += sky_march(0.0, v, sun, march, 2.0, throughput, hits_ground);
    }
    shared_e[thread] = sum;
    for (uint stride = THREADS / 2; stride > 0; stride /= 2) {
        barrier();
        if (thread < stride) shared_e[thread] += shared_e[thread + stride];
    }
    if (thread != 0) return;
    /* sky_march's radiance carries the sun's illuminance: divide it out (per unit illuminance). */
    spectrum_t e = PI * shared_e[0] / float(SQRT_DIRS * SQRT_DIRS) / max(atmo.sun.CH, spectrum_t(1e-20));
    imageStore(irradiance_out, ivec2(gl_WorkGroupID.x, 0), SPECTRUM_TO_VEC4(min(e, spectrum_t(FP16_MAX)), 1.0));
}
