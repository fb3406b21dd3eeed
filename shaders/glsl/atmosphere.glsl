/* The atmosphere model of docs/model.md in GLSL: medium, phases, ray geometry in cancellation-free forms,
 * LUT parameterisations. Included by every sky shader. A point is described by its altitude h (km above the
 * ground, never the planet-scale radius minus the ground radius) and the cosine mu of a ray's zenith angle. */
#include "shared.h"

layout(std140, set = 0, binding = VKSKY_BINDING_ATMOSPHERE) uniform AtmosphereUbo { AtmosphereParams atmo; };

/* The scene's variant (see shared.h): species with zero coefficients, multi-scattering, the sun disc and a lit
 * ground cost nothing when absent. */
layout(constant_id = VKSKY_SPEC_RAYLEIGH) const bool HAS_RAYLEIGH = true;
layout(constant_id = VKSKY_SPEC_MIE) const bool HAS_MIE = true;
layout(constant_id = VKSKY_SPEC_OZONE) const bool HAS_OZONE = true;
layout(constant_id = VKSKY_SPEC_MULTISCATTER) const bool HAS_MULTISCATTER = true;
layout(constant_id = VKSKY_SPEC_SUN_DISC) const bool HAS_SUN_DISC = true;
layout(constant_id = VKSKY_SPEC_GROUND) const bool HAS_GROUND = false;
layout(constant_id = VKSKY_SPEC_MIE_PHASE) const int MIE_PHASE = VKSKY_MIE_PHASE_HG;
layout(constant_id = VKSKY_SPEC_RAYLEIGH_PROFILE) const int RAYLEIGH_PROFILE = VKSKY_PROFILE_GENERAL;
layout(constant_id = VKSKY_SPEC_MIE_PROFILE) const int MIE_PROFILE = VKSKY_PROFILE_GENERAL;
layout(constant_id = VKSKY_SPEC_OZONE_PROFILE) const int OZONE_PROFILE = VKSKY_PROFILE_GENERAL;
layout(constant_id = VKSKY_SPEC_EXTRA_SPECIES) const int EXTRA_SPECIES = 0;
layout(constant_id = VKSKY_SPEC_EXTRA0_PROFILE) const int EXTRA0_PROFILE = VKSKY_PROFILE_GENERAL;
layout(constant_id = VKSKY_SPEC_EXTRA1_PROFILE) const int EXTRA1_PROFILE = VKSKY_PROFILE_GENERAL;
layout(constant_id = VKSKY_SPEC_SUN_VISIBILITY) const int SUN_VISIBILITY = VKSKY_SUN_VISIBILITY_PENUMBRA;

const float PI = 3.14159265358979;
/* The multi-scattering LUT clamps its altitude to 10 m (seed bug 1: no sphere-sampled ray may start exactly on
 * the ground). */
const float MULTISCATTER_MIN_ALTITUDE = 0.01;
const float FP16_MAX = 65504.0;

float ground_radius() { return atmo.radii.x; }
float top_radius() { return atmo.radii.y; }
float top_altitude() { return atmo.radii.z; }          /* Rt - Rb, computed in double on the CPU */

/* r^2 - Rb^2 for r = Rb + h, without forming r^2 (~4e7 km^2, where float keeps only ~2.4 km^2). */
float rho2_of(float h) { return h * (2.0 * ground_radius() + h); }
/* Rt^2 - r^2 for r = Rb + h (negative above the top). */
float top_gap2_of(float h) { return (top_altitude() - h) * (top_radius() + ground_radius() + h); }

/* Does a ray from altitude h with zenith cosine mu hit the ground? Inclusive (seed bug 1): a ray that starts on
 * the ground heading down hits it at t = 0. */
bool ray_hits_ground(float h, float mu)
{
    float r = ground_radius() + h;
    return mu < 0.0 && rho2_of(h) <= r * r * mu * mu;
}

/* Distance to the ground along a ray that hits it (the near root, in the form without cancellation). */
float distance_to_ground(float h, float mu)
{
    float r = ground_radius() + h;
    float rho2 = rho2_of(h);
    return rho2 / max(-r * mu + sqrt(max(0.0, r * r * mu * mu - rho2)), 1e-30);
}

/* Distance to the top of the atmosphere from inside it (h <= top). */
float distance_to_top(float h, float mu)
{
    float r = ground_radius() + h;
    float gap2 = max(0.0, top_gap2_of(h));
    float s = sqrt(max(0.0, r * r * mu * mu + gap2));
    return mu >= 0.0 ? gap2 / max(r * mu + s, 1e-30) : s - r * mu;
}

/* Altitude and sun zenith cosine at distance t along a ray from (h, mu) whose cosine with the sun is nu and whose
 * starting point has sun zenith cosine mu_s. */
float altitude_along(float h, float mu, float t, out float r_t)
{
    float r = ground_radius() + h;
    float num = rho2_of(h) + t * t + 2.0 * r * mu * t;     /* r_t^2 - Rb^2 */
    r_t = sqrt(max(0.0, r * r + t * t + 2.0 * r * mu * t));
    return max(0.0, num / (r_t + ground_radius()));
}

struct Medium {
    vec3 scattering;        /* sigma_s total */
    vec3 extinction;        /* sigma_t total */
    vec3 rayleigh;          /* sigma_s Rayleigh */
    vec3 mie;               /* sigma_s Mie */
};

/* Density of species 0 (Rayleigh), 1 (Mie), 2 (ozone) at altitude h >= 0: a pair of Bruneton density layers
 * {a, b, c, d} = atmo.profiles[2 species + (h < width ? 0 : 1)], clamp(a exp(b h) + c h + d, 0, 1). `kind` (a
 * specialization constant) compiles the general form down for the common profiles. */
float profile_density(int species, int kind, float h)
{
    if (kind == VKSKY_PROFILE_EXPONENTIAL) /* a = 1, b < 0, c = d = 0: in (0, 1] for h >= 0 */
        return exp(atmo.profiles[2 * species].y * h);
    /* Both layers loaded at constant offsets and selected (no dynamic indexing: lavapipe pays for that). */
    vec4 l = h < atmo.profile_widths[species / 4][species % 4] ? atmo.profiles[2 * species] : atmo.profiles[2 * species + 1];
    float e = (kind == VKSKY_PROFILE_GENERAL && l.x != 0.0) ? l.x * exp(l.y * h) : 0.0;
    return clamp(e + l.z * h + l.w, 0.0, 1.0);
}

Medium sample_medium(float h)
{
    h = max(h, 0.0);
    float d_r = HAS_RAYLEIGH ? profile_density(0, RAYLEIGH_PROFILE, h) : 0.0;
    float d_m = HAS_MIE ? profile_density(1, MIE_PROFILE, h) : 0.0;
    float d_o = HAS_OZONE ? profile_density(2, OZONE_PROFILE, h) : 0.0;
    Medium m;
    m.rayleigh = atmo.rayleigh_scattering.rgb * d_r;
    m.mie = atmo.mie_scattering.rgb * d_m;
    vec3 absorption = atmo.mie_absorption.rgb * d_m + atmo.ozone_absorption.rgb * d_o;
    for (int i = 0; i < EXTRA_SPECIES; ++i) { /* extra species scatter with the Rayleigh phase */
        float d_e = profile_density(3 + i, i == 0 ? EXTRA0_PROFILE : EXTRA1_PROFILE, h);
        m.rayleigh += atmo.extra_scattering[i].rgb * d_e;
        absorption += atmo.extra_absorption[i].rgb * d_e;
    }
    m.scattering = m.rayleigh + m.mie;
    m.extinction = m.scattering + absorption;
    return m;
}

float rayleigh_phase(float nu) { return 3.0 / (16.0 * PI) * (1.0 + nu * nu); }

/* Legendre polynomials P_3 .. P_6 of x (the multi-scattering LUT's zonal moments, docs/model.md). */
vec4 legendre_3456(float x)
{
    float x2 = x * x;
    float p2 = 1.5 * x2 - 0.5;
    float p3 = (2.5 * x2 - 1.5) * x;
    float p4 = (7.0 * x * p3 - 3.0 * p2) / 4.0;
    float p5 = (9.0 * x * p4 - 4.0 * p3) / 5.0;
    float p6 = (11.0 * x * p5 - 5.0 * p4) / 6.0;
    return vec4(p3, p4, p5, p6);
}

/* Cornette-Shanks: Henyey-Greenstein with a Rayleigh-like (1 + nu^2) factor, normalised. */
float cornette_shanks_phase(float nu, float g)
{
    float g2 = g * g;
    float denom = max(1.0 + g2 - 2.0 * g * nu, 1e-8);
    return 3.0 / (8.0 * PI) * (1.0 - g2) * (1.0 + nu * nu) / ((2.0 + g2) * denom * sqrt(denom));
}

float henyey_greenstein_phase(float nu, float g);
float mie_phase(float nu, float g)
{
    return MIE_PHASE == VKSKY_MIE_PHASE_CORNETTE_SHANKS ? cornette_shanks_phase(nu, g) : henyey_greenstein_phase(nu, g);
}

float henyey_greenstein_phase(float nu, float g)
{
    float g2 = g * g;
    float denom = max(1.0 + g2 - 2.0 * g * nu, 1e-8);
    return (1.0 - g2) / (4.0 * PI * denom * sqrt(denom));
}

/* (1 - exp(-sigma dt)) / sigma, the exact integral of exp(-sigma s) over one step, given the step's
 * transmittance exp(-sigma dt) (computed once by the caller); -> dt as sigma -> 0. */
vec3 step_integral(vec3 sigma, float dt, vec3 step_transmittance)
{
    vec3 x = sigma * dt;
    vec3 exact = (1.0 - step_transmittance) / max(sigma, vec3(1e-30));
    return mix(exact, vec3(dt) * (1.0 - 0.5 * x), lessThan(x, vec3(1e-4)));
}

#include "sun_visibility.glsl"

/* Texel-centre sub-UV: unit x in [0,1] <-> texture coordinate; exact inverses, texel k sits at x = k/(n-1). */
float unit_to_sub_uv(float x, float n) { return 0.5 / n + x * (n - 1.0) / n; }
float sub_uv_to_unit(float u, float n) { return (u - 0.5 / n) * n / (n - 1.0); }

/* Bruneton's transmittance parameterisation, forward: (h, mu) -> uv. The distance d is always to the top of the
 * atmosphere, never clipped to the ground (seed bug 6), so forward and inverse are exact inverses. */
/* Distance to the top along the horizon-tangent ray from the ground: sqrt(Rt^2 - Rb^2). */
float horizon_distance() { return sqrt(top_altitude() * (top_radius() + ground_radius())); }

vec2 transmittance_uv(float h, float mu, vec2 size)
{
    float H = horizon_distance();
    float rho = sqrt(rho2_of(h));
    float d = distance_to_top(h, mu);
    float d_min = top_altitude() - h;
    float d_max = rho + H;
    float x_mu = (d - d_min) / max(d_max - d_min, 1e-30);
    float x_r = rho / H;
    return vec2(unit_to_sub_uv(clamp(x_mu, 0.0, 1.0), size.x), unit_to_sub_uv(clamp(x_r, 0.0, 1.0), size.y));
}

/* Inverse: uv -> (h, mu). */
void transmittance_params(vec2 uv, vec2 size, out float h, out float mu)
{
    float x_mu = sub_uv_to_unit(uv.x, size.x);
    float x_r = sub_uv_to_unit(uv.y, size.y);
    float H = horizon_distance();
    float rho = H * x_r;
    h = rho * rho / (sqrt(rho * rho + ground_radius() * ground_radius()) + ground_radius());
    float r = ground_radius() + h;
    float d_min = top_altitude() - h;
    float d_max = rho + H;
    float d = d_min + x_mu * (d_max - d_min);
    /* (H^2 - rho^2 - d^2) / (2 r d) with H^2 - rho^2 = Rt^2 - r^2 = d_min (Rt + r). */
    mu = d <= 0.0 ? 1.0 : clamp((d_min * (top_radius() + r) - d * d) / (2.0 * r * d), -1.0, 1.0);
}

/* Multi-scattering LUT x <-> mu_s. Psi changes fastest across the terminator (mu_s near 0, where the earth
 * shadow sweeps over the atmosphere) and slowly elsewhere, so x = 0.5 + 0.5 sign(mu_s) sqrt(|mu_s|) puts half the
 * texels within |mu_s| < 0.25 (Hillaire's linear x = (mu_s + 1)/2 costs ~10 % at sunset with 32 texels). */
float multiscatter_x_of_mu_s(float mu_s) { return 0.5 + 0.5 * sign(mu_s) * sqrt(abs(mu_s)); }
float multiscatter_mu_s_of_x(float x)
{
    float y = 2.0 * x - 1.0;
    return sign(y) * y * y;
}

/* Multi-scattering LUT y <-> altitude: h = y^2 top. Psi changes fastest near the ground (the densest air, thin
 * aerosol layers, optically thick media), so the texels crowd there (32 texels: the first 0.1 km apart, 6.5 km
 * at the top; a linear mapping spends 3.2 km on every texel). */
float multiscatter_y_of_h(float h) { return sqrt(clamp(h / top_altitude(), 0.0, 1.0)); }
float multiscatter_h_of_y(float y) { return y * y * top_altitude(); }

vec2 multiscatter_uv(float h, float mu_s, vec2 size)
{
    return vec2(unit_to_sub_uv(clamp(multiscatter_x_of_mu_s(mu_s), 0.0, 1.0), size.x),
                unit_to_sub_uv(multiscatter_y_of_h(h), size.y));
}

/* Hillaire's sky-view LUT parameterisation, with the exact texel-centre sub-UV. x: azimuth from the sun,
 * u = sqrt((1 - cos)/2), dense toward the sun. y: view zenith angle, the horizon at v = 0.5, quadratic on both
 * sides so texels crowd at the horizon. beta is the angle between the horizon and the nadir at altitude h. */
void skyview_horizon(float h, out float zenith_horizon_angle, out float beta)
{
    float r = ground_radius() + h;
    beta = acos(clamp(sqrt(rho2_of(h)) / r, 0.0, 1.0));
    zenith_horizon_angle = PI - beta;
}

vec2 skyview_uv(float h, float mu, float cos_azimuth, vec2 size)
{
    float zha, beta;
    skyview_horizon(h, zha, beta);
    float theta = acos(clamp(mu, -1.0, 1.0));
    float y;
    if (theta < zha) {
        y = 0.5 * (1.0 - sqrt(max(0.0, 1.0 - theta / zha)));
    } else {
        y = 0.5 + 0.5 * sqrt(clamp((theta - zha) / max(beta, 1e-6), 0.0, 1.0));
    }
    float x = sqrt(clamp(0.5 - 0.5 * cos_azimuth, 0.0, 1.0));
    return vec2(unit_to_sub_uv(x, size.x), unit_to_sub_uv(y, size.y));
}

void skyview_params(vec2 uv, float h, vec2 size, out float mu, out float cos_azimuth)
{
    float zha, beta;
    skyview_horizon(h, zha, beta);
    float x = clamp(sub_uv_to_unit(uv.x, size.x), 0.0, 1.0);
    float y = clamp(sub_uv_to_unit(uv.y, size.y), 0.0, 1.0);
    float theta;
    if (y < 0.5) {
        float c = 1.0 - 2.0 * y;
        theta = zha * (1.0 - c * c);
    } else {
        float c = 2.0 * y - 1.0;
        theta = zha + beta * c * c;
    }
    mu = cos(theta);
    cos_azimuth = 1.0 - 2.0 * x * x;
}
