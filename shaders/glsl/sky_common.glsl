/* The per-pixel sky march (docs/model.md, "Sky radiance along a view ray"), shared by the fragment sky pass
 * (and any other pass that renders the sky). Expects atmosphere.glsl and the two LUT samplers. */

vec3 lookup_transmittance(float h, float mu) { return texture(transmittance_lut, transmittance_uv(h, mu)).rgb; }
vec3 lookup_multiscatter(float h, float mu_s) { return texture(multiscatter_lut, multiscatter_uv(h, mu_s)).rgb; }

/* View ray of a pixel centre: the ray matrix (camera basis scaled by fov/aspect), never an inverse
 * view-projection at planet scale (seed: "Inverse VP fails at planet-centric coordinates"). */
vec3 pixel_view_dir(vec2 pixel_centre, vec2 inv_size, SkyPush p)
{
    vec2 ndc = vec2(2.0 * pixel_centre.x * inv_size.x - 1.0, 1.0 - 2.0 * pixel_centre.y * inv_size.y);
    return normalize(p.forward.xyz + ndc.x * p.right.xyz + ndc.y * p.up.xyz);
}

/* Angle between two unit vectors, accurate for tiny angles (acos of a dot near 1 is not). */
float small_angle(vec3 a, vec3 b) { return 2.0 * asin(clamp(0.5 * length(a - b), 0.0, 1.0)); }

/* Sky radiance seen from altitude h_cam along unit dir v with sun direction s (camera up = +Y). */
vec3 sky_radiance(float h_cam, vec3 v, vec3 s, int steps)
{
    float h = h_cam;
    float mu = v.y;
    float mu_s = s.y;
    float nu = dot(v, s);
    vec3 radiance = vec3(0.0);
    vec3 throughput = vec3(1.0);
    bool sees_atmosphere = true;

    /* From space: move the origin to where the ray enters the top sphere (or see only the sun). */
    if (h > top_altitude()) {
        float r = ground_radius() + h;
        float gap2 = -top_gap2_of(h);                 /* r^2 - Rt^2 > 0 */
        float disc = r * r * mu * mu - gap2;
        if (mu >= 0.0 || disc < 0.0) {
            sees_atmosphere = false;
        } else {
            float t_entry = gap2 / (-r * mu + sqrt(disc));
            float rt = top_radius();
            mu = clamp((r * mu + t_entry) / rt, -1.0, 1.0);
            mu_s = clamp((r * mu_s + t_entry * nu) / rt, -1.0, 1.0);
            h = top_altitude();
        }
    }

    bool hits_ground = sees_atmosphere && ray_hits_ground(h, mu);
    if (sees_atmosphere) {
        float t_max = hits_ground ? distance_to_ground(h, mu) : distance_to_top(h, mu);
        float dt = t_max / float(steps);
        float r = ground_radius() + h;
        float phase_r = rayleigh_phase(nu);
        float phase_m = henyey_greenstein_phase(nu, atmo.mie_absorption.w);
        for (int i = 0; i < steps; ++i) {
            float t = (float(i) + 0.5) * dt;
            float r_t;
            float h_t = altitude_along(h, mu, t, r_t);
            float mu_s_t = clamp((r * mu_s + t * nu) / r_t, -1.0, 1.0);
            Medium m = sample_medium(h_t);
            vec3 sun_t = lookup_transmittance(h_t, mu_s_t);
            vec3 psi = lookup_multiscatter(h_t, mu_s_t);
            /* Single scattering is shadowed by the planet (seed bug 5); multiple scattering is already
             * integrated over the sphere, shadow included, in the LUT (seed bug 9). */
            vec3 source = atmo.sun.rgb * (earth_shadow(h_t, mu_s_t) * sun_t * (m.rayleigh * phase_r + m.mie * phase_m)
                                          + psi * m.scattering);
            radiance += throughput * source * step_integral(m.extinction, dt);
            throughput *= exp(-m.extinction * dt);
        }
    }

    /* Sun disc with limb darkening; hidden where the planet is in the way of this very ray. */
    float angle = small_angle(v, s);
    float radius = atmo.sun.w;
    if (!hits_ground && angle < radius) {
        float x = angle / radius;
        float limb = 1.0 - 0.6 * (1.0 - sqrt(max(0.0, 1.0 - x * x)));
        radiance += atmo.sun.rgb * 10.0 * throughput * limb;
    }
    return clamp(radiance, vec3(0.0), vec3(FP16_MAX));
}
