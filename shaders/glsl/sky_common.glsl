/* The sky along a view ray (docs/model.md, "Sky radiance along a view ray"), shared by the fragment and compute
 * sky passes and the sky-view LUT. Expects atmosphere.glsl, the LUT samplers transmittance_lut and
 * multiscatter_lut, and (for the lookup path) skyview_lut. */

spectrum_t lookup_transmittance(float h, float mu)
{
    return texture(transmittance_lut, transmittance_uv(h, mu, vec2(textureSize(transmittance_lut, 0)))).CH;
}
/* The sky's irradiance on the ground (per unit sun illuminance) by sun zenith cosine. */
#ifndef GROUND_SKY_IRRADIANCE
#define GROUND_SKY_IRRADIANCE(mu_s) texture(ground_irradiance_lut, ground_irradiance_uv(mu_s, \
                                            float(textureSize(ground_irradiance_lut, 0).x))).CH
#endif

/* Psi and the second bounce's moments at a point (docs/model.md "Multiple scattering"). */
struct MultiScatter {
    spectrum_t psi; /* per unit sun illuminance */
    float d;        /* E[w_x^2 - w_y^2] of L2 x its share of Psi (x toward the sun's azimuth, y across, z up) */
    vec4 moments;   /* Q_zz = E[w_z^2] - 1/3, Q_xz = E[w_x w_z], m_x = E[w_x], m_z = E[w_z], likewise weighted */
    vec4 zonal;     /* E[P_l(w_z)] for l = 3 .. 6, likewise weighted */
};

/* The LUT's three parts (multiscatter_lut.comp): Psi^(1/4) and D, the other moments of degree <= 2, the zonal
 * moments; the sub-UV of one N x N part, scaled by 1/3, stays within it. The lesson's model has no moments (one
 * fetch). */
#ifdef SPECTRAL4
#define MULTISCATTER_PARTS VKSKY_MULTISCATTER_PARTS4
#else
#define MULTISCATTER_PARTS VKSKY_MULTISCATTER_PARTS
#endif
MultiScatter lookup_multiscatter(float h, float mu_s)
{
    const float part = 1.0 / float(MULTISCATTER_PARTS);
    vec2 part_size = vec2(textureSize(multiscatter_lut, 0)) * vec2(part, 1.0);
    vec2 uv = multiscatter_uv(h, mu_s, part_size) * vec2(part, 1.0);
    vec4 left = texture(multiscatter_lut, uv);
    spectrum_t root2 = left.CH * left.CH;
    MultiScatter ms;
    ms.psi = root2 * root2;
#ifndef SPECTRAL4
    ms.d = left.a;
#endif
    bool lesson = SUN_VISIBILITY == VKSKY_SUN_VISIBILITY_LESSON_FADE;
#ifdef SPECTRAL4
    ms.d = lesson ? 0.0 : texture(multiscatter_lut, uv + vec2(3.0 * part, 0.0)).r;   /* the fourth part: D */
#endif
    ms.moments = lesson ? vec4(0.0) : texture(multiscatter_lut, uv + vec2(part, 0.0));
    ms.zonal = lesson ? vec4(0.0) : texture(multiscatter_lut, uv + vec2(2.0 * part, 0.0));
    return ms;
}

/* A phase's Legendre coefficients k_1 .. k_6 (p = sum (2l + 1) k_l P_l / (4 pi)). */
struct PhaseLegendre {
    vec2 low;    /* k_1, k_2 */
    vec4 zonal;  /* k_3 .. k_6 */
};
const PhaseLegendre RAYLEIGH_LEGENDRE = PhaseLegendre(vec2(0.0, 0.1), vec4(0.0)); /* exact: degree 2 */

/* The Mie phase's: Henyey-Greenstein g^l; Cornette-Shanks, (3 / (2 (2 + g^2))) (1 + nu^2) times HG's series,
 * re-expanded with nu^2 P_l = a_l P_(l+2) + b_l P_l + c_l P_(l-2) (docs/model.md). */
PhaseLegendre mie_legendre(float g)
{
    float hg[9];  /* (2l + 1) g^l, l = 0 .. 8 */
    float gl = 1.0;
    for (int l = 0; l <= 8; ++l) {
        hg[l] = float(2 * l + 1) * gl;
        gl *= g;
    }
    float k[7];
    for (int l = 1; l <= 6; ++l) {
        if (MIE_PHASE == VKSKY_MIE_PHASE_CORNETTE_SHANKS) {
            float fl = float(l), below = fl - 2.0, above = fl + 2.0;
            float b = (2.0 * fl * fl + 2.0 * fl - 1.0) / ((2.0 * fl - 1.0) * (2.0 * fl + 3.0));
            float a = (below + 1.0) * (below + 2.0) / ((2.0 * below + 1.0) * (2.0 * below + 3.0));
            float c = above * (above - 1.0) / ((2.0 * above - 1.0) * (2.0 * above + 1.0));
            float sum = hg[l] * (1.0 + b) + (l >= 2 ? hg[max(l - 2, 0)] * a : 0.0) + hg[l + 2] * c;
            k[l] = 3.0 / (2.0 * (2.0 + g * g)) * sum / float(2 * l + 1);
        } else {
            k[l] = hg[l] / float(2 * l + 1);
        }
    }
    return PhaseLegendre(vec2(k[1], k[2]), vec4(k[3], k[4], k[5], k[6]));
}

/* The factor on one phase's part of the Psi term for a view direction v (v_x toward the sun's azimuth, v_z up)
 * from the second bounce's moments: the phase averaged over L2's directions relative to the isotropic 1/(4 pi),
 * L2 cut to its spherical harmonics of degree <= 2 and its zonal part to degree 6:
 * 1 + 3 k1 v.m + (15/2) k2 v.Q.v + sum_(l=3..6) (2l + 1) k_l E[P_l(w_z)] P_l(v_z) (Rayleigh: k = (0, 1/10),
 * exact). Never below 0. The reference's ms_phase_factor is the same. */
float ms_phase_factor(MultiScatter ms, float v_x, float v_z, PhaseLegendre k)
{
    float v_y2 = max(0.0, (1.0 - v_z) * (1.0 + v_z) - v_x * v_x);
    float vqv = 0.5 * ms.d * (v_x * v_x - v_y2) + 0.5 * ms.moments.x * (3.0 * v_z * v_z - 1.0) +
                2.0 * ms.moments.y * v_x * v_z;
    float zonal = dot(vec4(7.0, 9.0, 11.0, 13.0) * k.zonal * ms.zonal, legendre_3456(v_z));
    return max(0.0, 1.0 + 3.0 * k.low.x * (v_x * ms.moments.z + v_z * ms.moments.w) + 7.5 * k.low.y * vqv + zonal);
}

/* The angular size of a texel of the image being rendered (radians), or 0: point sampling. The sky pass sets it
 * (texel_angle) before it evaluates a pixel, the composite pass from its own push (composite.comp); sun_drawn_radius
 * reads it. */
float sky_texel_angle = 0.0;
/* A texel's larger angular side, by projection (projection.glsl; right.w and up.w are 1 / the whole image's size):
 * perspective at the view axis 2 tan(fov/2) / height (and the same across); equirect 2 pi / width; a cube face's
 * centre 2 / face size; the equidistant fisheye pi / width. */
float texel_angle(SkyPush p)
{
    int kind = int(p.projection.x);
    if (kind == VKSKY_PROJECTION_EQUIRECT) return 6.2831853 * p.right.w;
    if (kind == VKSKY_PROJECTION_CUBEMAP) return 2.0 * p.right.w;
    if (kind == VKSKY_PROJECTION_FISHEYE) return 3.1415927 * p.right.w;
    return 2.0 * max(length(p.right.xyz) * p.right.w, length(p.up.xyz) * p.up.w);
}

/* The ray's class decided once per pixel from the host's horizon (horizon.glsl): -1 none (each ray asks the sphere,
 * as the LUT passes and the composite do), 0 the ray ends on the ground, 1 it does not. One decision for the whole
 * pixel, so float rounding in the sphere test at a grazing ray can never put a sky sample on the ground. */
int sky_forced_class = -1;
bool ray_class_ground(float h, float mu)
{
    return sky_forced_class >= 0 ? sky_forced_class == 0 : ray_hits_ground(h, mu);
}

/* Angle between two unit vectors, accurate for tiny angles (acos of a dot near 1 is not). */
float small_angle(vec3 a, vec3 b) { return 2.0 * asin(clamp(0.5 * length(a - b), 0.0, 1.0)); }

/* From space: move a ray's origin to where it enters the top sphere (t_entry km along it). False if it misses
 * the atmosphere. */
bool enter_atmosphere(inout float h, inout float mu, inout float mu_s, float nu, out float t_entry)
{
    t_entry = 0.0;
    if (h <= top_altitude()) return true;
    float r = ground_radius() + h;
    float gap2 = -top_gap2_of(h);                     /* r^2 - Rt^2 > 0 */
    float disc = r * r * mu * mu - gap2;
    if (mu >= 0.0 || disc < 0.0) return false;
    t_entry = gap2 / (-r * mu + sqrt(disc));
    float rt = top_radius();
    mu = clamp((r * mu + t_entry) / rt, -1.0, 1.0);
    mu_s = clamp((r * mu_s + t_entry * nu) / rt, -1.0, 1.0);
    h = top_altitude();
    return true;
}

/* What the march gathers over a piece of a view ray. The in-scattered radiance is split by phase function into
 * two parts that add up to all of it exactly (docs/readme/composite.md, "Layers"):
 *   rayleigh: single scattering by every species with the Rayleigh phase (Rayleigh, and the extra species of a
 *             scene file), plus the multiple-scattering term Psi * sigma_s of those species;
 *   mie:      single scattering by Mie, plus Psi * sigma_s of Mie.
 * (Psi multiplies the total scattering coefficient, which is the sum of the two groups'.) The lit ground's
 * reflection is not part of either: sky_march adds it where the whole ray ends on the ground. */
struct MarchSegment {
    spectrum_t rayleigh, mie;  /* in-scattered radiance of each part, up to the segment's end */
    spectrum_t throughput;     /* transmittance from the camera to the segment's end */
    bool hits_ground;       /* the whole ray (not the segment) ends on the ground */
    float r, mu_s, nu;      /* at the march's origin (the camera, or where a ray from space enters) */
    float t_max;            /* the whole ray's length from that origin (to the ground or the top) */
};

/* The march over the first t_end km of the ray from altitude h_cam along v (sun toward s, local up = +Y); the
 * whole ray for t_end >= its length. The one march of vksky: the sky (sky_march), the LUT passes and aerial
 * perspective to a point (aerial.glsl) all integrate through here. */
MarchSegment march_segment(float h_cam, vec3 v, vec3 s, vec4 march, float distribution, float t_end)
{
    float h = h_cam;
    float mu = v.y;
    float mu_s = s.y;
    float nu = dot(v, s);
    MarchSegment seg;
    seg.rayleigh = spectrum_t(0.0);
    seg.mie = spectrum_t(0.0);
    seg.throughput = spectrum_t(1.0);
    seg.hits_ground = false;
    seg.nu = nu;
    /* Uniform steps from space, the given distribution near the ground, and a smooth hand-over between them
     * over the upper half of the atmosphere (see below). */
    float toward_uniform = smoothstep(0.5 * top_altitude(), top_altitude(), h);
    float t_entry;
    bool enters = enter_atmosphere(h, mu, mu_s, nu, t_entry);
    seg.r = ground_radius() + h;
    seg.mu_s = mu_s;
    seg.t_max = 0.0;
    if (!enters) return seg;

    seg.hits_ground = ray_class_ground(h, mu);
    float t_max = seg.hits_ground ? distance_to_ground(h, mu) : distance_to_top(h, mu);
    seg.t_max = t_max;
    float t_stop = clamp(t_end - t_entry, 0.0, t_max);
    /* Fixed count (min = max) or Hillaire's count growing with the path length. */
    float steps = floor(mix(march.x, march.y, clamp(t_stop / max(march.w, 1e-6), 0.0, 1.0)));
    float r = seg.r;
    float phase_r = rayleigh_phase(nu);
    float phase_m = mie_phase(nu, MIE_G);
    PhaseLegendre mie_k = mie_legendre(MIE_G);
    /* Step boundaries at t_stop (i/N)^p: p = 1 uniform, p = 2 Hillaire's quadratic spacing, which puts short
     * steps near the camera where an upward or horizontal ray meets the dense, thin Mie layer. A ray that
     * enters from space starts in the thinnest air, so it keeps uniform steps. In between, the exponent moves
     * smoothly from p to 1 over the upper half of the atmosphere (no Mie layer near the camera there), so that the
     * march (and the sky-view LUT built by it) changes continuously as a camera climbs out through the top: an
     * exponent that jumps at the top is a 1 % pop in the mean (issue 26). */
    float p = mix(distribution, 1.0, toward_uniform);
    float t_prev = 0.0;
    for (float i = 0.0; i < steps; i += 1.0) {
        float u = (i + 1.0) / steps;
        float t_next = t_stop * (p == 2.0 ? u * u : p == 1.0 ? u : pow(u, p));   /* pow costs exp + log per step */
        float dt = t_next - t_prev;
        float t = t_prev + march.z * dt;
        t_prev = t_next;
        float r_t;
        float h_t = altitude_along(h, mu, t, r_t);
        float mu_s_t = clamp((r * mu_s + t * nu) / r_t, -1.0, 1.0);
        Medium m = sample_medium(h_t);
        spectrum_t step_t = exp(-m.extinction * dt);
        float mu_t;
        float visible = sun_visibility(h_t, mu_s_t, mu_t);
        spectrum_t sun_t = lookup_transmittance(h_t, mu_t);
        MultiScatter ms = MultiScatter(spectrum_t(0.0), 0.0, vec4(0.0), vec4(0.0));
        if (HAS_MULTISCATTER) ms = lookup_multiscatter(h_t, mu_s_t);
        /* The second bounce's anisotropy: the view direction in the sample's frame (v_x toward the sun's azimuth,
         * v_z = mu_v up) and each phase's factor on its part of the Psi term; 1 for the lesson's model. */
        float f_r = 1.0, f_m = 1.0;
        if (HAS_MULTISCATTER && SUN_VISIBILITY != VKSKY_SUN_VISIBILITY_LESSON_FADE) {
            float mu_v = clamp((r * mu + t) / r_t, -1.0, 1.0);
            float sin2s = (1.0 - mu_s_t) * (1.0 + mu_s_t);
            float v_x = sin2s > 1e-8 ? (nu - mu_v * mu_s_t) * inversesqrt(sin2s) : 0.0;
            f_r = ms_phase_factor(ms, v_x, mu_v, RAYLEIGH_LEGENDRE);
            f_m = ms_phase_factor(ms, v_x, mu_v, mie_k);
        }
        /* Single scattering is shadowed by the planet (seed bug 5), the penumbra included; multiple scattering is
         * already integrated over the sphere, shadow included, in the LUT (seed bug 9). */
        spectrum_t sun_single = visible * sun_t;
        spectrum_t weight = atmo.sun.CH * seg.throughput * step_integral(m.extinction, dt, step_t);
        seg.rayleigh += weight * m.rayleigh * (sun_single * phase_r + ms.psi * f_r);
        seg.mie += weight * m.mie * (sun_single * phase_m + ms.psi * f_m);
        seg.throughput *= step_t;
    }
    return seg;
}

/* A lit ground (albedo > 0) where the whole ray ends on it, seen through the ray's transmittance: Lambertian, lit
 * by the sun through the atmosphere and by the sky (the ground-irradiance LUT: the sky's irradiance on the ground
 * per unit sun illuminance, by sun angle). Zero without a lit ground. */
spectrum_t lit_ground(MarchSegment seg)
{
    if (!HAS_GROUND || !seg.hits_ground) return spectrum_t(0.0);
    float mu_s_g = clamp((seg.r * seg.mu_s + seg.t_max * seg.nu) / ground_radius(), -1.0, 1.0);
    float mu_t_g;
    float visible_g = sun_visibility(0.0, mu_s_g, mu_t_g);
    spectrum_t sun_g = lookup_transmittance(0.0, mu_t_g) * visible_g * max(mu_t_g, 0.0);
    return seg.throughput * atmo.sun.CH * (sun_g + GROUND_SKY_IRRADIANCE(mu_s_g)) * atmo.ground.CH / PI;
}

/* The march: in-scattered radiance along the ray (no sun disc) and the ray's transmittance. */
spectrum_t sky_march(float h_cam, vec3 v, vec3 s, vec4 march, float distribution, out spectrum_t throughput,
                     out bool hits_ground)
{
    MarchSegment seg = march_segment(h_cam, v, s, march, distribution, 3.0e38);
    spectrum_t radiance = seg.rayleigh + seg.mie;
    throughput = seg.throughput;
    hits_ground = seg.hits_ground;
    return radiance + lit_ground(seg);
}

/* Sun disc with limb darkening, seen through the ray's transmittance; hidden where the planet is in the way of
 * this very ray. */
/* The disc as drawn, filtered by the texel it is seen through. Point-sampled, a disc a few texels wide gains or
 * loses whole texels as it moves (its power jumps by tens of per cent), and one smaller than a texel (a small or
 * wide-angle image, a render scale below 1) falls between texel centres and vanishes. So the disc is drawn with
 * radius max(true radius, one texel), its edge a linear ramp one texel wide centred on that radius (a texel's
 * coverage of the disc, to first order), and its radiance scaled by (true / drawn radius)^2 so that it keeps the
 * sun's power. With sky_texel_angle 0 it is the hard-edged disc of the true radius. */
float sun_drawn_radius() { return max(SUN_RADIUS, sky_texel_angle); }
float sun_disc_extent_lesson() { return sun_drawn_radius() + 0.5 * sky_texel_angle; }   /* no coverage beyond */

/* The disc that carries the sun's power (--units photometric, atmo.sun_disc.x = 1) must keep it when its pixels are
 * summed, not only in the integral: sampled at one point per pixel, a shape a few texels wide aliases (the lesson's
 * one-texel ramp: up to 15 % by where the disc falls on the pixel grid; with limb darkening's sharp edge, 2 %). So
 * its shape is smooth at the texel's scale: radius R = max(true radius, 1.5 texels), a raised-cosine edge 3 texels
 * wide centred on R, limb darkening over the whole support R + 1.5 texels (so its square-root edge falls where the
 * edge has already gone to zero). Summed over any pixel grid (tried: every phase, sizes 0.1-8 texels per true
 * radius, anisotropic pixels) it keeps the power within 0.3 %; resolved (texels below a tenth of the radius) it is
 * the limb-darkened disc. Its radiance is sun x T / (the shape's integral): the disc holds E T at the camera. */
const float SUN_POWER_RADIUS = 1.5, SUN_POWER_EDGE = 3.0;   /* texels */
/* A texel over 0.5 rad (an image a few pixels across) is taken as 0.5: the support stays under 1.5 rad, well inside
 * the sphere (at such sizes no shape survives one sample per pixel; the disc stays finite and in its place). */
float sun_power_texel() { return min(sky_texel_angle, 0.5); }
float sun_power_radius() { return max(SUN_RADIUS, SUN_POWER_RADIUS * sun_power_texel()); }
float sun_power_support() { return sun_power_radius() + 0.5 * SUN_POWER_EDGE * sun_power_texel(); }
float sun_disc_extent() { return atmo.sun_disc.x > 0.5 ? sun_power_support() : sun_disc_extent_lesson(); }

/* The power disc's shape at angle theta from the sun's centre (1 at the centre, 0 beyond the support). */
float sun_power_shape(float theta, float u)
{
    float R = sun_power_radius(), w = SUN_POWER_EDGE * sun_power_texel(), support = sun_power_support();
    float edge = w > 0.0 ? 0.5 - 0.5 * cos(3.1415927 * clamp((R - theta) / w + 0.5, 0.0, 1.0)) : (theta < R ? 1.0 : 0.0);
    float x = min(theta / support, 1.0);
    return edge * (1.0 - u * (1.0 - sqrt(max(0.0, 1.0 - x * x))));
}

/* Its solid-angle integral, 2 pi times the integral of shape(theta) sin(theta) d theta over the support: with
 * theta = support sin(phi) the limb's square root is cos(phi), smooth, so a midpoint rule of 64 steps is exact to
 * ~1e-5 (no small-angle step). Evaluated only by pixels inside the disc. */
float sun_power_integral(float u)
{
    const int N = 64;
    float support = sun_power_support(), sum = 0.0;
    for (int i = 0; i < N; ++i) {
        float phi = (float(i) + 0.5) * (1.5707963 / float(N));
        float theta = support * sin(phi);
        sum += sun_power_shape(theta, u) * sin(theta) * support * cos(phi);
    }
    return 6.2831853 * sum * (1.5707963 / float(N));
}

spectrum_t sun_disc(vec3 v, vec3 s, spectrum_t throughput, bool hits_ground)
{
    float angle = small_angle(v, s);
    if (!HAS_SUN_DISC || hits_ground || angle >= sun_disc_extent()) return spectrum_t(0.0);
    if (atmo.sun_disc.x > 0.5)
        return atmo.sun.CH * throughput * (sun_power_shape(angle, LIMB_U) / sun_power_integral(LIMB_U));
    /* The lesson's disc (--units relative): drawn with radius max(true radius, one texel), its edge a linear ramp one
     * texel wide, its radiance sun x 10 scaled by (true / drawn radius)^2. */
    float radius = sun_drawn_radius();
    float coverage = sky_texel_angle > 0.0 ? clamp((radius - angle) / sky_texel_angle + 0.5, 0.0, 1.0) : 1.0;
    float x = min(angle / radius, 1.0);
    float limb = 1.0 - LIMB_U * (1.0 - sqrt(max(0.0, 1.0 - x * x)));
    float power_kept = (SUN_RADIUS / radius) * (SUN_RADIUS / radius);   /* solid angles' ratio (small angles) */
    return atmo.sun.CH * 10.0 * throughput * limb * coverage * power_kept;
}

/* The power disc's share above the camera's horizon: the penumbra's visible fraction of the sun (sun_visibility.glsl).
 * Its smooth shape reaches a few texels past the true disc, so on a small image a sun just below the horizon would
 * otherwise light sky pixels above it through their grazing rays. 1 for the lesson's disc (its pixels' own ground
 * test only, as before). */
float sun_disc_visible(float h_cam, vec3 s)
{
    float mu_t;
    return atmo.sun_disc.x > 0.5 ? sun_visibility(h_cam, s.y, mu_t) : 1.0;
}

spectrum_t sky_radiance(float h_cam, vec3 v, vec3 s, vec4 march, float distribution)
{
    spectrum_t throughput;
    bool hits_ground;
    spectrum_t radiance = sky_march(h_cam, v, s, march, distribution, throughput, hits_ground);
    return clamp(radiance + sun_disc(v, s, throughput, hits_ground) * sun_disc_visible(h_cam, s), spectrum_t(0.0),
                 spectrum_t(FP16_MAX));
}

#ifdef VKSKY_SKYVIEW_LOOKUP
/* The fast path (camera inside the atmosphere): one sky-view LUT lookup plus the sun disc, whose transmittance
 * comes from the transmittance LUT. */
spectrum_t sky_radiance_lookup(float h_cam, vec3 v, vec3 s)
{
    vec2 hv = v.xz, hs = s.xz;
    float lv = length(hv), ls = length(hs);
    float cos_azimuth = (lv > 1e-6 && ls > 1e-6) ? dot(hv, hs) / (lv * ls) : 1.0;
    ivec2 size = textureSize(skyview_lut, 0);
    vec2 uv = skyview_uv(h_cam, v.y, cos_azimuth, vec2(size));
    /* The horizon lies between two rows of the LUT (skyview_uv puts it at v = 0.5): a bilinear tap across it would
     * blend ground into sky. A ray of a known class reads only its own half: sky rays no lower than the last sky
     * row's centre, ground rays no higher than the first ground row's (1/N^2 of the horizon's zenith angle away). */
    if (sky_forced_class >= 0) {
        float sky_last = (float(size.y / 2) - 0.5) / float(size.y), ground_first = (float((size.y + 1) / 2) + 0.5) / float(size.y);
        uv.y = sky_forced_class == 1 ? min(uv.y, sky_last) : max(uv.y, ground_first);
    }
    spectrum_t radiance = texture(skyview_lut, uv).CH;
    /* Only pixels inside the sun's disc pay for its transmittance lookup. */
    if (HAS_SUN_DISC && small_angle(v, s) < sun_disc_extent()) {
        bool hits_ground = ray_class_ground(h_cam, v.y);
        spectrum_t throughput = hits_ground ? spectrum_t(0.0) : lookup_transmittance(h_cam, v.y);
        radiance += sun_disc(v, s, throughput, hits_ground) * sun_disc_visible(h_cam, s);
    }
    return clamp(radiance, spectrum_t(0.0), spectrum_t(FP16_MAX));
}
#endif
