/* The atmosphere model of docs/model.md in GLSL: medium, phases, ray geometry in cancellation-free forms,
 * LUT parameterisations. Included by every sky shader. A point is described by its altitude h (km above the
 * ground, never the planet-scale radius minus the ground radius) and the cosine mu of a ray's zenith angle. */
#include "shared.h"

/* The channels' type: three wavelengths (RGB, or the three of a --spectral group), or with SPECTRAL4 four (the
 * four-wide spectral build: every coefficient's .w is the fourth wavelength's, the scalars that .w held in RGB live
 * in atmo.scalars4; docs/spectral.md "Four to a texel"). The RGB build preprocesses to exactly its former text. */
#ifdef SPECTRAL4
#define spectrum_t vec4
#define CH rgba
#define SPECTRUM_TO_VEC4(c, w) (c)
#define MIE_G atmo.scalars4.x
#define SUN_RADIUS atmo.scalars4.y
#define LIMB_U atmo.scalars4.z
#else
#define spectrum_t vec3
#define CH rgb
#define SPECTRUM_TO_VEC4(c, w) vec4(c, w)
#define MIE_G atmo.mie_absorption.w
#define SUN_RADIUS atmo.sun.w
#define LIMB_U atmo.ground.w
#endif

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

#include "geometry.glsl"

struct Medium {
    spectrum_t scattering;  /* sigma_s total */
    spectrum_t extinction;  /* sigma_t total */
    spectrum_t rayleigh;    /* sigma_s Rayleigh */
    spectrum_t mie;         /* sigma_s Mie */
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
    m.rayleigh = atmo.rayleigh_scattering.CH * d_r;
    m.mie = atmo.mie_scattering.CH * d_m;
    spectrum_t absorption = atmo.mie_absorption.CH * d_m + atmo.ozone_absorption.CH * d_o;
    for (int i = 0; i < EXTRA_SPECIES; ++i) { /* extra species scatter with the Rayleigh phase */
        float d_e = profile_density(3 + i, i == 0 ? EXTRA0_PROFILE : EXTRA1_PROFILE, h);
        m.rayleigh += atmo.extra_scattering[i].CH * d_e;
        absorption += atmo.extra_absorption[i].CH * d_e;
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
spectrum_t step_integral(spectrum_t sigma, float dt, spectrum_t step_transmittance)
{
    spectrum_t x = sigma * dt;
    spectrum_t exact = (1.0 - step_transmittance) / max(sigma, spectrum_t(1e-30));
    return mix(exact, spectrum_t(dt) * (1.0 - 0.5 * x), lessThan(x, spectrum_t(1e-4)));
}

#include "sun_visibility.glsl"

#include "lut_mapping.glsl"
