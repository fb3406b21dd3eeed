/* The LUTs' parameterisations (texel-centre sub-UV, Bruneton's transmittance mapping, the multi-scattering and
 * sky-view mappings), forward and inverse. Expects geometry.glsl and PI before it. Shared by vksky's shaders
 * (atmosphere.glsl) and a host's (include/vksky_luts.glsl), so both sample the LUTs alike. */
#ifndef VKSKY_LUT_MAPPING_GLSL
#define VKSKY_LUT_MAPPING_GLSL
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

/* The ground-irradiance LUT (a row of texels): the multi-scattering LUT's x <-> mu_s. */
vec2 ground_irradiance_uv(float mu_s, float width)
{
    return vec2(unit_to_sub_uv(multiscatter_x_of_mu_s(mu_s), width), 0.5);
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
#endif
