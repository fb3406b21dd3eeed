/* Sun visibility at a point (docs/model.md "Sun visibility"): the GLSL twin of src/model/sun_visibility.c — the
 * same formulas, keep them in step. Included by atmosphere.glsl (needs ground_radius(), rho2_of(), ray_hits_ground(),
 * atmo.sun.w = the sun's angular radius and the SUN_VISIBILITY specialization constant).
 *
 * Penumbra: the fraction of the sun's disc above the horizon, from angles formed without cancellation (the horizon dip
 * atan(rho, Rb), the sun's elevation asin(mu_s)); the horizon is a circle of curvature rho / Rb (a straight line on
 * the ground). Lesson fade: the binary earth shadow times saturate(10 mu_s + 0.5). */

/* phi - sin(phi) cos(phi) over kappa^2 for phi = asin(c kappa): a segment of a circle of curvature kappa; the series
 * where it would cancel (see the C twin). */
float sv_segment_area(float c, float kappa)
{
    float s = c * kappa;
    if (s >= 1.0) return 0.5 * PI / (kappa * kappa);
    float phi = asin(s);
    if (phi < 0.05) {
        float ratio = s < 1e-3 ? c * (1.0 + s * s / 6.0) : c * phi / s;
        float p2 = phi * phi;
        return (2.0 / 3.0) * phi * ratio * ratio * (1.0 - p2 / 5.0 + 2.0 * p2 * p2 / 105.0);
    }
    return (phi - s * sqrt((1.0 - s) * (1.0 + s))) / (kappa * kappa);
}

/* Visible fraction of a disc of radius R whose centre is d above a horizon of curvature kappa. */
float sv_lens_fraction(float d, float kappa, float R)
{
    if (d >= R) return 1.0;
    if (d <= -R) return 0.0;
    float kD = 1.0 + kappa * d;
    if (kappa * R > 1.0 && d <= R - 2.0 / kappa) {
        float q = 1.0 / (kappa * R);
        return 1.0 - q * q;
    }
    float as = (d * (2.0 + kappa * d) + kappa * R * R) / (2.0 * kD);
    float x = clamp(as / R, -1.0, 1.0);
    float c = R * sqrt((1.0 - x) * (1.0 + x));
    float kap = kD - kappa * as;
    float seg_p = kap >= 0.0 ? sv_segment_area(c, kappa)
                             : (PI - asin(min(1.0, c * kappa)) + c * kappa * (-kap)) / (kappa * kappa);
    float disc = PI * R * R;
    if (x > 0.0) return max(0.0, 1.0 - (R * R * acos(x) - as * c + seg_p) / disc);
    return clamp((R * R * acos(-x) + as * c - seg_p) / disc, 0.0, 1.0);
}

/* Sun visibility of the scene's model at altitude h with sun zenith cosine mu_s; mu_t: where to read the sun's
 * transmittance (mu_s, or for the penumbra the centroid of the visible part of the disc, always above the horizon). */
float sun_visibility(float h, float mu_s, out float mu_t)
{
    mu_t = mu_s;
    if (SUN_VISIBILITY == VKSKY_SUN_VISIBILITY_LESSON_FADE) {
        float lit = ray_hits_ground(h, mu_s) ? 0.0 : 1.0;
        return lit * clamp(mu_s * 10.0 + 0.5, 0.0, 1.0);
    }
    float R = SUN_RADIUS;
    if (mu_s >= R && R > 0.0) return 1.0;   /* asin(mu_s) >= mu_s: the whole disc is up, no trigonometry */
    float rho = sqrt(rho2_of(h));
    if (mu_s + rho / ground_radius() <= -R) return 0.0;   /* asin(mu_s) <= mu_s, atan(rho, Rb) <= rho / Rb: all hidden */
    float elevation = asin(clamp(mu_s, -1.0, 1.0));
    float d = elevation + atan(rho, ground_radius());
    if (!(R > 0.0)) return d > 0.0 ? 1.0 : 0.0;
    if (d >= R) return 1.0;
    float f = sv_lens_fraction(d, rho / ground_radius(), R);
    if (f <= 0.0) return 0.0;
    /* Centroid of the visible segment (a straight horizon): theta = 2 asin(sqrt((R + d) / 2R)), area g, height
     * (2/3) sin^3 / g, the series for a thin sliver. */
    float theta = 2.0 * asin(sqrt(clamp(0.5 * (R + d) / R, 0.0, 1.0)));
    float st = sin(theta);
    float t2 = theta * theta;
    float g = theta < 0.05 ? (2.0 / 3.0) * theta * t2 * (1.0 - t2 / 5.0 + 2.0 * t2 * t2 / 105.0) : theta - st * cos(theta);
    float ybar = g > 0.0 ? (2.0 / 3.0) * st * st * st / g : -cos(theta);
    mu_t = sin(elevation + R * ybar);
    return f;
}
