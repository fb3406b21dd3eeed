#version 450
/* Multi-scattering LUT (Hillaire 2020, section 5.5): Psi(h, mu_s) = L_2nd / (1 - f_ms), per unit sun
 * illuminance, from 64 sphere directions x 20 steps per texel. Reads the transmittance LUT. */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D transmittance_lut;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D multiscatter_out;

void main()
{
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, imageSize(multiscatter_out)))) return;
    vec2 uv = (vec2(texel) + 0.5) / MULTISCATTER_N;
    float mu_s = sub_uv_to_unit(uv.x, MULTISCATTER_N) * 2.0 - 1.0;
    /* Seed bug 1: clamp 10 m above the ground so no direction starts exactly on the sphere. */
    float h = clamp(sub_uv_to_unit(uv.y, MULTISCATTER_N) * top_altitude(), MULTISCATTER_MIN_ALTITUDE, top_altitude());
    vec3 sun = vec3(sqrt(max(0.0, 1.0 - mu_s * mu_s)), mu_s, 0.0);

    int sqrt_dirs = int(atmo.lut_steps.z);
    int steps = int(atmo.lut_steps.y);
    vec3 l_2nd = vec3(0.0);
    vec3 f_ms = vec3(0.0);
    for (int i = 0; i < sqrt_dirs; ++i) {
        for (int j = 0; j < sqrt_dirs; ++j) {
            float theta = 2.0 * PI * (float(i) + 0.5) / float(sqrt_dirs);
            float phi = acos(1.0 - 2.0 * (float(j) + 0.5) / float(sqrt_dirs));
            vec3 dir = vec3(cos(theta) * sin(phi), cos(phi), sin(theta) * sin(phi));
            float mu = dir.y;
            float nu = dot(dir, sun);
            float r = ground_radius() + h;
            /* Inclusive ground test (seed bug 1): rays toward the ground stop there. */
            float t_max = ray_hits_ground(h, mu) ? distance_to_ground(h, mu) : distance_to_top(h, mu);
            float dt = t_max / float(steps);
            vec3 throughput = vec3(1.0);
            vec3 l_dir = vec3(0.0);
            vec3 f_dir = vec3(0.0);
            for (int k = 0; k < steps; ++k) {
                float t = (float(k) + 0.5) * dt;
                float r_t;
                float h_t = altitude_along(h, mu, t, r_t);
                float mu_s_t = clamp((r * mu_s + t * nu) / r_t, -1.0, 1.0);
                Medium m = sample_medium(h_t);
                vec3 sun_t = texture(transmittance_lut, transmittance_uv(h_t, mu_s_t)).rgb;
                vec3 integral = step_integral(m.extinction, dt);
                /* Earth shadow baked in (seed bug 9); the isotropic phase 1/(4 pi) on the scattered light only. */
                l_dir += throughput * m.scattering * sun_t * earth_shadow(h_t, mu_s_t) / (4.0 * PI) * integral;
                f_dir += throughput * m.scattering * integral;
                throughput *= exp(-m.extinction * dt);
            }
            l_2nd += l_dir;
            f_ms += f_dir;
        }
    }
    /* The 4 pi solid angle cancels the isotropic phase: a plain mean over directions (seed bug 2). */
    float inv_n = 1.0 / float(sqrt_dirs * sqrt_dirs);
    l_2nd *= inv_n;
    f_ms *= inv_n;
    vec3 psi = l_2nd / max(1.0 - f_ms, vec3(1e-6));
    imageStore(multiscatter_out, texel, vec4(min(psi, vec3(FP16_MAX)), 1.0));
}
