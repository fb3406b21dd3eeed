// vksky_luts.glsl: vksky's LUTs sampled in a host's own shaders (VKSKY_OUTPUT_LUTS_ONLY or any output; see
// vksky_get_luts in vksky.h and docs/library.md). The mappings are vksky's own shaders' (vksky/glsl/geometry.glsl and
// lut_mapping.glsl, installed beside this file and included, not copied), so a host samples the LUTs exactly as the
// sky pass does.
//
// Before including it, define (as expressions of the host's uniforms; values from vksky_luts):
//   VKSKY_BOTTOM_RADIUS_KM, VKSKY_TOP_RADIUS_KM   vksky_luts.bottom_radius_km, top_radius_km
//   VKSKY_TRANSMITTANCE_LUT   a sampler2D of vksky_luts.transmittance (+ vksky_luts.sampler)
//   VKSKY_MULTISCATTER_LUT    optional: a sampler2D of vksky_luts.multiscatter
//   VKSKY_SKYVIEW_LUT         optional: a sampler2D of vksky_luts.skyview
// and enable #extension GL_GOOGLE_include_directive. Heights h are km above the ground; mu is the cosine of a
// direction's zenith angle in vksky's frame (+Y up: the host's up); directions toward the sun as vksky_luts.sun_direction.
// Every helper the included files define is renamed vksky_* while they are included, so none collides with the host's
// names.
#ifndef VKSKY_LUTS_GLSL
#define VKSKY_LUTS_GLSL
#define PI VKSKY_PI
#define ground_radius vksky_ground_radius
#define top_radius vksky_top_radius
#define top_altitude vksky_top_altitude
#define rho2_of vksky_rho2_of
#define top_gap2_of vksky_top_gap2_of
#define ray_hits_ground vksky_ray_hits_ground
#define distance_to_ground vksky_distance_to_ground
#define distance_to_top vksky_distance_to_top
#define altitude_along vksky_altitude_along
#define unit_to_sub_uv vksky_unit_to_sub_uv
#define sub_uv_to_unit vksky_sub_uv_to_unit
#define horizon_distance vksky_horizon_distance
#define transmittance_uv vksky_transmittance_uv
#define transmittance_params vksky_transmittance_params
#define multiscatter_x_of_mu_s vksky_multiscatter_x_of_mu_s
#define multiscatter_mu_s_of_x vksky_multiscatter_mu_s_of_x
#define multiscatter_y_of_h vksky_multiscatter_y_of_h
#define multiscatter_h_of_y vksky_multiscatter_h_of_y
#define multiscatter_uv vksky_multiscatter_uv
#define skyview_horizon vksky_skyview_horizon
#define skyview_uv vksky_skyview_uv
#define skyview_params vksky_skyview_params

const float VKSKY_PI = 3.14159265358979;
float vksky_ground_radius() { return VKSKY_BOTTOM_RADIUS_KM; }
float vksky_top_radius() { return VKSKY_TOP_RADIUS_KM; }
float vksky_top_altitude() { return VKSKY_TOP_RADIUS_KM - VKSKY_BOTTOM_RADIUS_KM; }
#include "vksky/glsl/geometry.glsl"
#include "vksky/glsl/lut_mapping.glsl"

// Transmittance from altitude h (km) along zenith cosine mu to the top of the atmosphere (rgb, 0..1).
vec3 vksky_transmittance(float h, float mu)
{
    vec2 size = vec2(textureSize(VKSKY_TRANSMITTANCE_LUT, 0));
    return textureLod(VKSKY_TRANSMITTANCE_LUT, vksky_transmittance_uv(h, mu, size), 0.0).rgb;
}

#ifdef VKSKY_MULTISCATTER_LUT
// Hillaire's Psi_ms (per unit sun illuminance) at altitude h for the sun at zenith cosine mu_s. The LUT holds square
// parts side by side (Psi^(1/4) and moments: shaders/glsl/sky_common.glsl, lookup_multiscatter); this reads the
// first part as vksky's sky pass does.
vec3 vksky_multiscatter(float h, float mu_s)
{
    vec2 size = vec2(textureSize(VKSKY_MULTISCATTER_LUT, 0));
    float part = size.y / size.x;   // 1 / the number of parts
    vec2 uv = vksky_multiscatter_uv(h, mu_s, size * vec2(part, 1.0)) * vec2(part, 1.0);
    vec3 root2 = textureLod(VKSKY_MULTISCATTER_LUT, uv, 0.0).rgb;
    root2 *= root2;
    return root2 * root2;
}
#endif

#ifdef VKSKY_SKYVIEW_LUT
// The sky's radiance seen from the camera's altitude h (the last recorded frame's) along zenith cosine mu, at
// cos_azimuth from the sun's azimuth; the sun disc is not in it.
vec3 vksky_skyview(float h, float mu, float cos_azimuth)
{
    vec2 size = vec2(textureSize(VKSKY_SKYVIEW_LUT, 0));
    return textureLod(VKSKY_SKYVIEW_LUT, vksky_skyview_uv(h, mu, cos_azimuth, size), 0.0).rgb;
}
#endif

// The helpers' plain names go back to the host.
#undef PI
#undef ground_radius
#undef top_radius
#undef top_altitude
#undef rho2_of
#undef top_gap2_of
#undef ray_hits_ground
#undef distance_to_ground
#undef distance_to_top
#undef altitude_along
#undef unit_to_sub_uv
#undef sub_uv_to_unit
#undef horizon_distance
#undef transmittance_uv
#undef transmittance_params
#undef multiscatter_x_of_mu_s
#undef multiscatter_mu_s_of_x
#undef multiscatter_y_of_h
#undef multiscatter_h_of_y
#undef multiscatter_uv
#undef skyview_horizon
#undef skyview_uv
#undef skyview_params
#endif
