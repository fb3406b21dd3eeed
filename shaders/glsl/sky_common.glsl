/* The sky along a view ray (docs/model.md, "Sky radiance along a view ray"), shared by the fragment and compute
 * sky passes and the sky-view LUT. Expects atmosphere.glsl, the LUT samplers transmittance_lut and
 * multiscatter_lut, and (for the lookup path) skyview_lut. */

vec3 lookup_transmittance(float h, float mu)
{
    return texture(transmittance_lut, transmittance_uv(h, mu, vec2(textureSize(transmittance_lut, 0)))).rgb;
}
/* The sky's irradiance on the ground (per unit sun illuminance) by sun zenith cosine. */
#ifndef GROUND_SKY_IRRADIANCE
#define GROUND_SKY_IRRADIANCE(mu_s) texture(ground_irradiance_lut, vec2(unit_to_sub_uv(multiscatter_x_of_mu_s(mu_s), \
                                            float(textureSize(ground_irradiance_lut, 0).x)), 0.5)).rgb
#endif

vec3 lookup_multiscatter(float h, float mu_s)
{
    return texture(multiscatter_lut, multiscatter_uv(h, mu_s, vec2(textureSize(multiscatter_lut, 0)))).rgb;
}

/* Angle between two unit vectors, accurate for tiny angles (acos of a dot near 1 is not). */
float small_angle(vec3 a, vec3 b) { return 2.0 * asin(clamp(0.5 * length(a - b), 0.0, 1.0)); }

/* From space: move a ray's origin to where it enters the top sphere. False if it misses the atmosphere. */
bool enter_atmosphere(inout float h, inout float mu, inout float mu_s, float nu)
{
    if (h <= top_altitude()) return true;
    float r = ground_radius() + h;
    float gap2 = -top_gap2_of(h);                     /* r^2 - Rt^2 > 0 */
    float disc = r * r * mu * mu - gap2;
    if (mu >= 0.0 || disc < 0.0) return false;
    float t_entry = gap2 / (-r * mu + sqrt(disc));
    float rt = top_radius();
    mu = clamp((r * mu + t_entry) / rt, -1.0, 1.0);
    mu_s = clamp((r * mu_s + t_entry * nu) / rt, -1.0, 1.0);
    h = top_altitude();
    return true;
}

/* The march: in-scattered radiance along the ray (no sun disc) and the ray's transmittance. */
vec3 sky_march(float h_cam, vec3 v, vec3 s, vec4 march, float distribution, out vec3 throughput,
               out bool hits_ground)
{
    float h = h_cam;
    float mu = v.y;
    float mu_s = s.y;
    float nu = dot(v, s);
    vec3 radiance = vec3(0.0);
    throughput = vec3(1.0);
    hits_ground = false;
    bool from_space = h > top_altitude();
    if (!enter_atmosphere(h, mu, mu_s, nu)) return radiance;

    hits_ground = ray_hits_ground(h, mu);
    float t_max = hits_ground ? distance_to_ground(h, mu) : distance_to_top(h, mu);
    /* Fixed count (min = max) or Hillaire's count growing with the path length. */
    float steps = floor(mix(march.x, march.y, clamp(t_max / max(march.w, 1e-6), 0.0, 1.0)));
    float r = ground_radius() + h;
    float phase_r = rayleigh_phase(nu);
    float phase_m = mie_phase(nu, atmo.mie_absorption.w);
    /* Step boundaries at t_max (i/N)^p: p = 1 uniform, p = 2 Hillaire's quadratic spacing, which puts short
     * steps near the camera where an upward or horizontal ray meets the dense, thin Mie layer. A ray that
     * enters from space starts in the thinnest air, so it keeps uniform steps. */
    float p = from_space ? 1.0 : distribution;
    float t_prev = 0.0;
    for (float i = 0.0; i < steps; i += 1.0) {
        float u = (i + 1.0) / steps;
        float t_next = t_max * (p == 2.0 ? u * u : p == 1.0 ? u : pow(u, p));   /* pow costs exp + log per step */
        float dt = t_next - t_prev;
        float t = t_prev + march.z * dt;
        t_prev = t_next;
        float r_t;
        float h_t = altitude_along(h, mu, t, r_t);
        float mu_s_t = clamp((r * mu_s + t * nu) / r_t, -1.0, 1.0);
        Medium m = sample_medium(h_t);
        vec3 step_t = exp(-m.extinction * dt);
        vec3 sun_t = lookup_transmittance(h_t, mu_s_t);
        vec3 psi = HAS_MULTISCATTER ? lookup_multiscatter(h_t, mu_s_t) : vec3(0.0);
        /* Single scattering is shadowed by the planet (seed bug 5); multiple scattering is already integrated
         * over the sphere, shadow included, in the LUT (seed bug 9). */
        vec3 source = atmo.sun.rgb * (earth_shadow(h_t, mu_s_t) * sun_t * (m.rayleigh * phase_r + m.mie * phase_m)
                                      + psi * m.scattering);
        radiance += throughput * source * step_integral(m.extinction, dt, step_t);
        throughput *= step_t;
    }
    /* A lit ground (albedo > 0): Lambertian, lit by the sun through the atmosphere and by the sky (the
     * ground-irradiance LUT: the sky's irradiance on the ground per unit sun illuminance, by sun angle). */
    if (HAS_GROUND && hits_ground) {
        float mu_s_g = clamp((r * mu_s + t_max * nu) / ground_radius(), -1.0, 1.0);
        vec3 sun_g = lookup_transmittance(0.0, mu_s_g) * earth_shadow(0.0, mu_s_g) * max(mu_s_g, 0.0);
        radiance += throughput * atmo.sun.rgb * (sun_g + GROUND_SKY_IRRADIANCE(mu_s_g)) * atmo.ground.rgb / PI;
    }
    return radiance;
}

/* Sun disc with limb darkening, seen through the ray's transmittance; hidden where the planet is in the way of
 * this very ray. */
vec3 sun_disc(vec3 v, vec3 s, vec3 throughput, bool hits_ground)
{
    float angle = small_angle(v, s);
    float radius = atmo.sun.w;
    if (!HAS_SUN_DISC || hits_ground || angle >= radius) return vec3(0.0);
    float x = angle / radius;
    float limb = 1.0 - atmo.ground.w * (1.0 - sqrt(max(0.0, 1.0 - x * x)));
    return atmo.sun.rgb * 10.0 * throughput * limb;
}

vec3 sky_radiance(float h_cam, vec3 v, vec3 s, vec4 march, float distribution)
{
    vec3 throughput;
    bool hits_ground;
    vec3 radiance = sky_march(h_cam, v, s, march, distribution, throughput, hits_ground);
    return clamp(radiance + sun_disc(v, s, throughput, hits_ground), vec3(0.0), vec3(FP16_MAX));
}

#ifdef VKSKY_SKYVIEW_LOOKUP
/* The fast path (camera inside the atmosphere): one sky-view LUT lookup plus the sun disc, whose transmittance
 * comes from the transmittance LUT. */
vec3 sky_radiance_lookup(float h_cam, vec3 v, vec3 s)
{
    vec2 hv = v.xz, hs = s.xz;
    float lv = length(hv), ls = length(hs);
    float cos_azimuth = (lv > 1e-6 && ls > 1e-6) ? dot(hv, hs) / (lv * ls) : 1.0;
    vec2 uv = skyview_uv(h_cam, v.y, cos_azimuth, vec2(textureSize(skyview_lut, 0)));
    vec3 radiance = texture(skyview_lut, uv).rgb;
    /* Only pixels inside the sun's disc pay for its transmittance lookup. */
    if (HAS_SUN_DISC && small_angle(v, s) < atmo.sun.w) {
        bool hits_ground = ray_hits_ground(h_cam, v.y);
        vec3 throughput = hits_ground ? vec3(0.0) : lookup_transmittance(h_cam, v.y);
        radiance += sun_disc(v, s, throughput, hits_ground);
    }
    return clamp(radiance, vec3(0.0), vec3(FP16_MAX));
}
#endif
