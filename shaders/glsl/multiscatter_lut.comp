#version 450
/* Multi-scattering LUT (Hillaire 2020, section 5.5): Psi(h, mu_s) = L_2nd / (1 - f_ms), per unit sun
 * illuminance, from 64 sphere directions x 20 steps per texel. Reads the transmittance LUT. */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"

/* One workgroup per texel, its 64 threads share the sphere directions (Hillaire's layout): per-thread work
 * stays small at any direction count, and a shared-memory sum combines them. */
#define THREADS 64
layout(local_size_x = THREADS) in;
layout(set = 0, binding = 1) uniform sampler2D transmittance_lut;
#ifndef LUT_FORMAT
#define LUT_FORMAT rgba16f
#endif
layout(set = 0, binding = 2, LUT_FORMAT) uniform writeonly image2D multiscatter_out;

shared vec3 shared_l[THREADS];
shared vec3 shared_f[THREADS];
shared float shared_x[THREADS];

void main()
{
    ivec2 texel = ivec2(gl_WorkGroupID.xy);
    uint thread = gl_LocalInvocationIndex;
    vec2 size = vec2(imageSize(multiscatter_out));
    vec2 t_size = vec2(textureSize(transmittance_lut, 0));
    vec2 uv = (vec2(texel) + 0.5) / size;
    float mu_s = multiscatter_mu_s_of_x(sub_uv_to_unit(uv.x, size.x));
    /* Seed bug 1: clamp 10 m above the ground so no direction starts exactly on the sphere. */
    float h = clamp(multiscatter_h_of_y(sub_uv_to_unit(uv.y, size.y)), MULTISCATTER_MIN_ALTITUDE, top_altitude());
    vec3 sun = vec3(sqrt(max(0.0, 1.0 - mu_s * mu_s)), mu_s, 0.0);
    /* The weight of the real phases in the first bounce: the point's own sun occlusion (0 for the lesson's model:
     * isotropic; see the reference's multiscatter.c and docs/model.md). */
    float mu_t_point;
    float shade = SUN_VISIBILITY == VKSKY_SUN_VISIBILITY_LESSON_FADE ? 0.0 : 1.0 - sun_visibility(h, mu_s, mu_t_point);

    int sqrt_dirs = int(atmo.lut_steps.z);
    int dir_count = sqrt_dirs * sqrt_dirs;
    int steps = int(atmo.lut_steps.y);
    vec3 l_2nd = vec3(0.0);
    vec3 f_ms = vec3(0.0);
    float l_x = 0.0;   /* green L2 weighted by dir_x^2 - dir_z^2 (toward the sun's azimuth vs across it) */
    for (int d = int(thread); d < dir_count; d += THREADS) {
        int i = d / sqrt_dirs, j = d - i * sqrt_dirs;
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
        /* The first bounce's phase (sunlight scattered at the sample toward the texel's point, cosine nu):
         * isotropic where the point is lit, the real Rayleigh and Mie phases where it is in the earth's shadow
         * (docs/model.md "Multiple scattering"): there the light comes forward-scattered from lit air sunward. */
        float phase_r = 1.0 / (4.0 * PI) + shade * (rayleigh_phase(nu) - 1.0 / (4.0 * PI));
        float phase_m = 1.0 / (4.0 * PI) + shade * (mie_phase(nu, atmo.mie_absorption.w) - 1.0 / (4.0 * PI));
        for (int k = 0; k < steps; ++k) {
            float t = (float(k) + 0.5) * dt;
            float r_t;
            float h_t = altitude_along(h, mu, t, r_t);
            float mu_s_t = clamp((r * mu_s + t * nu) / r_t, -1.0, 1.0);
            Medium m = sample_medium(h_t);
            float mu_t;
            float visible = sun_visibility(h_t, mu_s_t, mu_t);
            vec3 sun_t = texture(transmittance_lut, transmittance_uv(h_t, mu_t, t_size)).rgb;
            vec3 step_t = exp(-m.extinction * dt);
            vec3 integral = step_integral(m.extinction, dt, step_t);
            /* Earth shadow baked in (seed bug 9); the first bounce's phase on the scattered light only. */
            l_dir += throughput * (m.rayleigh * phase_r + m.mie * phase_m) * sun_t * visible * integral;
            f_ms += throughput * m.scattering * integral;
            throughput *= step_t;
        }
        /* Hillaire's ground bounce: the sunlit ground seen along this direction, Lambertian (per unit
         * illuminance), scattered again like the rest of L_2nd. */
        if (HAS_GROUND && ray_hits_ground(h, mu)) {
            float mu_s_g = clamp((r * mu_s + t_max * nu) / ground_radius(), -1.0, 1.0);
            /* The lesson's bounce has no shadow term (the cosine does it); the penumbra's has its visible part. */
            float mu_t_g = mu_s_g;
            float visible_g = SUN_VISIBILITY == VKSKY_SUN_VISIBILITY_LESSON_FADE ? 1.0 : sun_visibility(0.0, mu_s_g, mu_t_g);
            vec3 sun_g = texture(transmittance_lut, transmittance_uv(0.0, mu_t_g, t_size)).rgb;
            l_dir += throughput * sun_g * visible_g * max(mu_t_g, 0.0) * atmo.ground.rgb / PI;
        }
        l_2nd += l_dir;
        l_x += l_dir.g * (dir.x * dir.x - dir.z * dir.z);
    }
    shared_l[thread] = l_2nd;
    shared_f[thread] = f_ms;
    shared_x[thread] = l_x;
    /* Tree sum over the workgroup; barrier() orders the shared-memory writes and reads between steps. */
    for (uint stride = THREADS / 2; stride > 0; stride /= 2) {
        barrier();
        if (thread < stride) {
            shared_l[thread] += shared_l[thread + stride];
            shared_f[thread] += shared_f[thread + stride];
            shared_x[thread] += shared_x[thread + stride];
        }
    }
    if (thread != 0) return;
    /* The 4 pi solid angle cancels the isotropic phase: a plain mean over directions (seed bug 2). */
    float inv_n = 1.0 / float(dir_count);
    l_2nd = shared_l[0] * inv_n;
    f_ms = shared_f[0] * inv_n;
    vec3 psi = l_2nd / max(1.0 - f_ms, vec3(1e-6));
    /* Stored as Psi^(1/4) (MULTISCATTER_ENCODE_POWER, atmosphere.glsl): across the terminator Psi falls by
     * orders of magnitude over a few texels, and the sampler's linear interpolation of Psi itself overshoots there
     * (the sky low opposite the sun at twilight, 4 % at sun -4 deg); interpolating the fourth root follows a
     * near-exponential fall 4x better, and fp16 keeps the small values' relative precision. */
    /* Alpha: the second bounce's anisotropy D = E[dir_x^2 - dir_z^2] of L2 (green) x (1 - f_ms) (L2's share of Psi)
     * x the point's own occlusion (only in the shadow, as the first bounce's real phases): the view march scales the
     * Rayleigh part of the Psi term by 1 + (3/8) D (v_x^2 - v_y^2) (docs/model.md). 0 for the lesson's model. */
    float aniso = shared_l[0].g > 0.0 ? shared_x[0] / shared_l[0].g * (1.0 - f_ms.g) * shade : 0.0;
    imageStore(multiscatter_out, texel, vec4(sqrt(sqrt(min(psi, vec3(FP16_MAX)))), clamp(aniso, -1.0, 1.0)));
}
