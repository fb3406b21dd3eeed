/* Ray geometry on the planet in cancellation-free forms (docs/model.md): altitudes h in km above the ground, zenith
 * cosines mu. Expects ground_radius(), top_radius() and top_altitude() (Rt - Rb, from double) defined before it:
 * atmosphere.glsl takes them from the uniform block, include/vksky_luts.glsl from the host's values. */
#ifndef VKSKY_GEOMETRY_GLSL
#define VKSKY_GEOMETRY_GLSL
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
#endif
