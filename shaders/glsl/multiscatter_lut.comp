#version 450
/* Multi-scattering LUT (Hillaire 2020, section 5.5): Psi(h, mu_s) = L_2nd / (1 - f_ms), per unit sun
 * illuminance, from 64 sphere directions x 20 steps per texel, and the second bounce's moments of L_2nd's
 * directions (docs/model.md). Three N x N parts side by side (VKSKY_MULTISCATTER_PARTS): Psi^(1/4) and D;
 * Q_zz, Q_xz, m_x, m_z; the zonal moments E[P_l(w_up)] of degrees 3 to 6. Reads the transmittance LUT, and with a
 * lit ground in its second pass the ground-irradiance LUT (the ground lit by the sky too; frame_luts.c). */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"

/* One workgroup per texel, its 64 threads share the sphere directions (Hillaire's layout): per-thread work
 * stays small at any direction count, and a shared-memory sum combines them. */
#define THREADS 64
#ifndef PHASE_CELL
#define PHASE_CELL 4
#endif
layout(local_size_x = THREADS) in;
layout(set = 0, binding = VKSKY_BINDING_TRANSMITTANCE_LUT) uniform sampler2D transmittance_lut;
#ifndef LUT_FORMAT
#define LUT_FORMAT rgba16f
#endif
layout(set = 0, binding = VKSKY_BINDING_OUTPUT, LUT_FORMAT) uniform writeonly image2D multiscatter_out;
/* The sky's irradiance on the ground (the second pass of a lit ground; else a stand-in never sampled). */
layout(set = 0, binding = VKSKY_BINDING_GROUND_IRRADIANCE_LUT) uniform sampler2D ground_irradiance_lut;
layout(push_constant) uniform MultiscatterPushBlock { MultiscatterPush ms_push; };

#ifdef SPECTRAL4
#define MULTISCATTER_PARTS VKSKY_MULTISCATTER_PARTS4   /* D in a fourth part: Psi fills the first's four channels */
#else
#define MULTISCATTER_PARTS VKSKY_MULTISCATTER_PARTS
#endif

shared spectrum_t shared_l[THREADS];
shared spectrum_t shared_f[THREADS];
shared float shared_x[THREADS];
shared vec4 shared_m[THREADS];
shared vec4 shared_z[THREADS];

void main()
{
    ivec2 texel = ivec2(gl_WorkGroupID.xy);
    uint thread = gl_LocalInvocationIndex;
    vec2 size = vec2(imageSize(multiscatter_out)) * vec2(1.0 / float(MULTISCATTER_PARTS), 1.0); /* a part */
    vec2 t_size = vec2(textureSize(transmittance_lut, 0));
    vec2 uv = (vec2(texel) + 0.5) / size;
    float mu_s = multiscatter_mu_s_of_x(sub_uv_to_unit(uv.x, size.x));
    /* Seed bug 1: clamp 10 m above the ground so no direction starts exactly on the sphere. */
    float h = clamp(multiscatter_h_of_y(sub_uv_to_unit(uv.y, size.y)), MULTISCATTER_MIN_ALTITUDE, top_altitude());
    vec3 sun = vec3(sqrt(max(0.0, 1.0 - mu_s * mu_s)), mu_s, 0.0);
    const bool real_phase = SUN_VISIBILITY != VKSKY_SUN_VISIBILITY_LESSON_FADE;

    int sqrt_dirs = int(atmo.lut_steps.z);
    int dir_count = sqrt_dirs * sqrt_dirs;
    int steps = int(atmo.lut_steps.y);
    spectrum_t l_2nd = spectrum_t(0.0);
    spectrum_t f_ms = spectrum_t(0.0);
    /* Green L2 weighted by the moments' functions of the direction, in the texel's frame x toward the sun's
     * azimuth, y up, z across: D by dir_x^2 - dir_z^2; Q_zz (up) by dir_y^2 - 1/3, Q_xz by dir_x dir_y; the
     * first moment by dir_x and dir_y. */
    float l_x = 0.0;
    vec4 l_m = vec4(0.0);
    /* ... and by the Legendre polynomials P_3 .. P_6 of dir_y (the zonal moments: L2's part symmetric about the
     * vertical, the bright band of long paths along the horizon, to the degree Mie's forward lobe needs). */
    vec4 l_z = vec4(0.0);
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
        spectrum_t throughput = spectrum_t(1.0);
        spectrum_t l_dir = spectrum_t(0.0);
        /* The first bounce's phase (sunlight scattered at the sample toward the texel's point, cosine nu): the
         * lesson's isotropic one, or the real Rayleigh and Mie phases, which give L2 its true directions (docs/model.md
         * "Multiple scattering"; the moments below carry them into the second bounce). */
        float phase_r = 1.0 / (4.0 * PI), phase_m = 1.0 / (4.0 * PI);
        if (real_phase) {
            /* The phases' mean over the direction's cell (PHASE_CELL^2 midpoints): with few directions the point
             * value of Mie's forward lobe, narrower than a cell, aliases (the reference's cell_phases). */
            phase_r = 0.0;
            phase_m = 0.0;
            for (int a = 0; a < PHASE_CELL; ++a) {
                float mu_a = 1.0 - 2.0 * (float(j) + (float(a) + 0.5) / float(PHASE_CELL)) / float(sqrt_dirs);
                float sin_a = sqrt(max(0.0, 1.0 - mu_a * mu_a));
                for (int b = 0; b < PHASE_CELL; ++b) {
                    float theta_b = 2.0 * PI * (float(i) + (float(b) + 0.5) / float(PHASE_CELL)) / float(sqrt_dirs);
                    float nu_ab = cos(theta_b) * sin_a * sun.x + mu_a * sun.y;
                    phase_r += rayleigh_phase(nu_ab);
                    phase_m += mie_phase(nu_ab, MIE_G);
                }
            }
            phase_r /= float(PHASE_CELL * PHASE_CELL);
            phase_m /= float(PHASE_CELL * PHASE_CELL);
        }
        for (int k = 0; k < steps; ++k) {
            float t = (float(k) + 0.5) * dt;
            float r_t;
            float h_t = altitude_along(h, mu, t, r_t);
            float mu_s_t = clamp((r * mu_s + t * nu) / r_t, -1.0, 1.0);
            Medium m = sample_medium(h_t);
            float mu_t;
            float visible = sun_visibility(h_t, mu_s_t, mu_t);
            spectrum_t sun_t = texture(transmittance_lut, transmittance_uv(h_t, mu_t, t_size)).CH;
            spectrum_t step_t = exp(-m.extinction * dt);
            spectrum_t integral = step_integral(m.extinction, dt, step_t);
            /* Earth shadow baked in (seed bug 9); the first bounce's phase on the scattered light only. */
            l_dir += throughput * (m.rayleigh * phase_r + m.mie * phase_m) * sun_t * visible * integral;
            f_ms += throughput * m.scattering * integral;
            throughput *= step_t;
        }
        /* The ground bounce: the lit ground seen along this direction, Lambertian (per unit illuminance),
         * scattered again like the rest of L_2nd. Hillaire's lights it by the sun alone (the first pass); the second
         * pass adds the sky's irradiance, the ground-irradiance LUT made from the first pass's LUT (13 % of the
         * ground's light at sun 30 deg, albedo 0.3: without it the ground's bounce into the sky is 18 % low). */
        if (HAS_GROUND && ray_hits_ground(h, mu)) {
            float mu_s_g = clamp((r * mu_s + t_max * nu) / ground_radius(), -1.0, 1.0);
            /* The lesson's bounce has no shadow term (the cosine does it); the penumbra's has its visible part. */
            float mu_t_g = mu_s_g;
            float visible_g = SUN_VISIBILITY == VKSKY_SUN_VISIBILITY_LESSON_FADE ? 1.0 : sun_visibility(0.0, mu_s_g, mu_t_g);
            spectrum_t sun_g = texture(transmittance_lut, transmittance_uv(0.0, mu_t_g, t_size)).CH;
            spectrum_t e_g = sun_g * visible_g * max(mu_t_g, 0.0);
            if (ms_push.ground.x != 0.0) {
                float n_g = float(textureSize(ground_irradiance_lut, 0).x);
                e_g += texture(ground_irradiance_lut, ground_irradiance_uv(mu_s_g, n_g)).CH;
            }
            l_dir += throughput * e_g * atmo.ground.CH / PI;
        }
        l_2nd += l_dir;
        l_x += l_dir.g * (dir.x * dir.x - dir.z * dir.z);
        l_m += l_dir.g * vec4(dir.y * dir.y - 1.0 / 3.0, dir.x * dir.y, dir.x, dir.y);
        l_z += l_dir.g * legendre_3456(dir.y);
    }
    shared_l[thread] = l_2nd;
    shared_f[thread] = f_ms;
    shared_x[thread] = l_x;
    shared_m[thread] = l_m;
    shared_z[thread] = l_z;
    /* Tree sum over the workgroup; barrier() orders the shared-memory writes and reads between steps. */
    for (uint stride = THREADS / 2; stride > 0; stride /= 2) {
        barrier();
        if (thread < stride) {
            shared_l[thread] += shared_l[thread + stride];
            shared_f[thread] += shared_f[thread + stride];
            shared_x[thread] += shared_x[thread + stride];
            shared_m[thread] += shared_m[thread + stride];
            shared_z[thread] += shared_z[thread + stride];
        }
    }
    if (thread != 0) return;
    /* The 4 pi solid angle cancels the isotropic phase: a plain mean over directions (seed bug 2). */
    float inv_n = 1.0 / float(dir_count);
    l_2nd = shared_l[0] * inv_n;
    f_ms = shared_f[0] * inv_n;
    spectrum_t psi = l_2nd / max(1.0 - f_ms, spectrum_t(1e-6));
    /* Stored as Psi^(1/4) (MULTISCATTER_ENCODE_POWER, atmosphere.glsl): across the terminator Psi falls by
     * orders of magnitude over a few texels, and the sampler's linear interpolation of Psi itself overshoots there
     * (the sky low opposite the sun at twilight, 4 % at sun -4 deg); interpolating the fourth root follows a
     * near-exponential fall 4x better, and fp16 keeps the small values' relative precision. */
    /* The second bounce's moments: each E[f(dir)] over L2 (green) x 1 - f_ms^2, the share of Psi that keeps L2's
     * angular distribution (the second and third orders; later ones tend to isotropy: docs/model.md); the view
     * march turns them into a factor on each phase's part of the Psi term (ms_phase_factor, sky_common.glsl).
     * All 0 for the lesson's model (its second bounce is isotropic). */
    float share = real_phase && shared_l[0].g > 0.0 ? (1.0 - f_ms.g * f_ms.g) / shared_l[0].g : 0.0;
    float d = clamp(shared_x[0] * share, -1.0, 1.0);
    vec4 moments = clamp(shared_m[0] * share, vec4(-1.0), vec4(1.0));
    vec4 zonal = clamp(shared_z[0] * share, vec4(-1.0), vec4(1.0));
#ifdef SPECTRAL4
    imageStore(multiscatter_out, texel, sqrt(sqrt(min(psi, spectrum_t(FP16_MAX)))));
    imageStore(multiscatter_out, texel + ivec2(3 * int(size.x), 0), vec4(d, 0.0, 0.0, 0.0));
#else
    imageStore(multiscatter_out, texel, vec4(sqrt(sqrt(min(psi, vec3(FP16_MAX)))), d));
#endif
    imageStore(multiscatter_out, texel + ivec2(int(size.x), 0), moments);
    imageStore(multiscatter_out, texel + ivec2(2 * int(size.x), 0), zonal);
}
