/* Sun visibility at a point of the atmosphere (docs/model.md "Sun visibility"): how much of the sun's disc the
 * planet leaves visible, and the direction whose transmittance stands for the visible part.
 *
 * Two models, chosen per scene ("sun_visibility" / --sun-visibility):
 *  - penumbra (default): the fraction of the sun's disc (angular radius R) above the planet's horizon seen from the
 *    point. Exact geometry, no tuning constant: a smooth penumbra of angular width 2R around the earth's shadow.
 *  - lesson-fade: Hillaire's binary earth shadow times the horizon fade saturate(10 mu_s + 0.5), kept so that the
 *    seed's model can still be rendered and compared.
 * shaders/glsl/sun_visibility.glsl is the same formula in GLSL; keep them in step.
 *
 * Numerics: everything is an angle formed without cancellation. The horizon dip is delta = atan2(rho, Rb) (rho =
 * sqrt(h (2 Rb + h)), never r - Rb), the sun's elevation asin(mu_s), and the sun centre's angular height above the
 * horizon d = elevation + delta, so 1 mm (delta ~ 6e-7 rad) and 36 000 km both keep full relative precision.
 * The horizon is a small circle of angular radius alpha = pi/2 - delta around the nadir, whose geodesic curvature
 * is cot(alpha) = tan(delta) = rho / Rb: the visible fraction is the plane lens of the sun's disc (radius R) and a
 * circle of that curvature (radius Rb / rho, a straight line on the ground), a form whose error against the
 * spherical overlap is O(R^2) relative (tests/test_sun_visibility.c measures it). */
#ifndef VKSKY_MODEL_SUN_VISIBILITY_H
#define VKSKY_MODEL_SUN_VISIBILITY_H

#ifdef __cplusplus
extern "C" {
#endif

/* Values of model_atmosphere.sun_visibility (and of the shaders' specialization constant). */
#define MODEL_SUN_VISIBILITY_PENUMBRA 0
#define MODEL_SUN_VISIBILITY_LESSON_FADE 1

/* The default angular radius of the sun's disc: 0.265 degrees, in radians. */
#define MODEL_SUN_ANGULAR_RADIUS_DEFAULT (0.265 * 3.14159265358979323846 / 180.0)

/* The fraction (0..1) of a disc of angular radius sun_radius (rad, >= 0) centred at sun zenith cosine mu_s that lies
 * above the horizon seen from a point with rho = sqrt(r^2 - Rb^2) = sqrt(h (2 Rb + h)) on a planet of radius
 * bottom_radius. sun_radius = 0: the binary shadow of a point sun (0 when the sun is on or below the horizon, the
 * inclusive ground test). */
double model_sun_visible_fraction(double rho, double bottom_radius, double mu_s, double sun_radius);

/* Sun visibility of model `kind` (MODEL_SUN_VISIBILITY_*) at a point with rho, radius r = Rb + h and sun zenith cosine
 * mu_s. *mu_transmittance: the zenith cosine at which to read the sun's transmittance: mu_s for the lesson's model;
 * for the penumbra, the direction of the centroid of the visible part of the disc (mu_s itself when the whole disc
 * is up), which always lies above the horizon, so that the transmittance of the sliver of sun still visible is that
 * of air it really crosses, not of a ray through the planet. */
double model_sun_visibility(int kind, double rho, double r, double bottom_radius, double mu_s, double sun_radius,
                            double *mu_transmittance);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_MODEL_SUN_VISIBILITY_H */
