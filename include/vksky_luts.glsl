// vksky_luts.glsl: sampling vksky's LUTs in a host's own shaders (VKSKY_OUTPUT_LUTS_ONLY, vksky_get_luts).
// Bind vksky_luts.transmittance and .skyview (with vksky_luts.sampler) and define VKSKY_TRANSMITTANCE_LUT and
// VKSKY_SKYVIEW_LUT to their sampler2D names before including this file. The parametrisations are those of vksky's
// own shaders (shaders/glsl/common.glsl: Hillaire 2020's transmittance mapping with Bruneton's horizon-aware
// texel placement; the sky-view LUT's latitude-longitude mapping with the horizon kept at the centre row).
// Units: kilometres (vksky_luts.bottom_radius_km, top_radius_km); directions in vksky's local frame (+Y up).
#ifndef VKSKY_LUTS_GLSL
#define VKSKY_LUTS_GLSL

// Transmittance from a point at radius r (km) towards a direction with cosine mu to the local vertical, to the
// top of the atmosphere (rgb).
vec3 vksky_transmittance(float r, float mu, float bottom_radius, float top_radius)
{
    float H = sqrt(max(top_radius * top_radius - bottom_radius * bottom_radius, 0.0));
    float rho = sqrt(max(r * r - bottom_radius * bottom_radius, 0.0));
    float discriminant = r * r * (mu * mu - 1.0) + top_radius * top_radius;
    float d = max(0.0, -r * mu + sqrt(max(discriminant, 0.0)));
    float d_min = top_radius - r, d_max = rho + H;
    float x_mu = (d - d_min) / max(d_max - d_min, 1e-6);
    float x_r = rho / max(H, 1e-6);
    return texture(VKSKY_TRANSMITTANCE_LUT, vec2(x_mu, x_r)).rgb;
}
#endif
