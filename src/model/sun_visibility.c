/* Sun visibility: the penumbra's geometry and the lesson's fade (see sun_visibility.h; the GLSL twin is
 * shaders/glsl/sun_visibility.glsl, the derivation docs/model.md "Sun visibility"). */
#include "model/sun_visibility.h"

#include <math.h>

#define SV_PI 3.14159265358979323846

static double clamp1(double x) { return x < -1.0 ? -1.0 : (x > 1.0 ? 1.0 : x); }

/* phi - sin(phi) cos(phi) divided by kappa^2, for phi = asin(s) with s = c kappa <= 1: the area of a circle's
 * segment of half-chord c on a circle of curvature kappa (radius 1 / kappa, infinite for kappa = 0). For a small
 * phi the difference cancels, so its series (2/3) phi^3 (1 - phi^2/5 + 2 phi^4/105), next term 1e-3 phi^6 relative,
 * written with phi / kappa = c asin(s) / s, which stays finite as kappa -> 0 (the straight horizon: area 0). */
static double segment_area(double c, double kappa)
{
    double s = c * kappa;
    if (s >= 1.0)
        return 0.5 * SV_PI / (kappa * kappa);
    double phi = asin(s);
    if (phi < 0.05) {
        double ratio = s < 1e-4 ? c * (1.0 + s * s / 6.0) : c * phi / s; /* phi / kappa */
        double p2 = phi * phi;
        return (2.0 / 3.0) * phi * ratio * ratio * (1.0 - p2 / 5.0 + 2.0 * p2 * p2 / 105.0);
    }
    return (phi - s * sqrt((1.0 - s) * (1.0 + s))) / (kappa * kappa);
}

/* Visible fraction of a disc of radius R whose centre is the angular height d above a horizon of curvature kappa
 * (the horizon circle has radius P = 1 / kappa and its centre, the nadir, lies at D = P + d from the sun's centre). */
static double lens_fraction(double d, double kappa, double R)
{
    if (d >= R)
        return 1.0;
    if (d <= -R)
        return 0.0; /* the disc lies inside the horizon circle (below the horizon) */
    double kD = 1.0 + kappa * d; /* kappa D > 0 */
    if (kappa * R > 1.0 && d <= R - 2.0 / kappa) {
        double q = 1.0 / (kappa * R); /* the planet is a disc inside the sun's (a camera very far away) */
        return 1.0 - q * q;
    }
    /* The radical line of the two circles, at distance a_s from the sun's centre toward the nadir:
     * a_s = (D^2 + R^2 - P^2) / (2 D), with D^2 - P^2 = d (2 P + d) formed without cancellation. */
    double as = (d * (2.0 + kappa * d) + kappa * R * R) / (2.0 * kD);
    double x = as / R;
    x = clamp1(x);
    double c = R * sqrt((1.0 - x) * (1.0 + x)); /* half the common chord */
    /* The horizon circle's segment on the sun's side of the line; its centre lies at a_p = D - a_s beyond it. */
    double kap = kD - kappa * as; /* kappa a_p */
    double seg_p = kap >= 0.0 ? segment_area(c, kappa)
                              : (SV_PI - asin(fmin(1.0, c * kappa)) + c * kappa * (-kap)) / (kappa * kappa);
    double disc = SV_PI * R * R;
    if (x > 0.0) /* mostly visible: 1 - hidden, hidden = the sun's segment beyond the line + the planet's */
        return fmax(0.0, 1.0 - (R * R * acos(x) - as * c + seg_p) / disc);
    /* mostly hidden: the visible area directly (no 1 - (almost 1)) */
    return fmax(0.0, fmin(1.0, (R * R * acos(-x) + as * c - seg_p) / disc));
}

/* Sun elevation and horizon dip, both as angles without cancellation (see the header). */
static double height_above_horizon(double rho, double bottom_radius, double mu_s, double *elevation)
{
    *elevation = asin(clamp1(mu_s));
    return *elevation + atan2(rho, bottom_radius);
}

double model_sun_visible_fraction(double rho, double bottom_radius, double mu_s, double sun_radius)
{
    double e, d = height_above_horizon(rho, bottom_radius, mu_s, &e);
    if (!(sun_radius > 0.0))
        return d > 0.0 ? 1.0 : 0.0;
    return lens_fraction(d, rho / bottom_radius, sun_radius);
}

double model_sun_visibility(int kind, double rho, double r, double bottom_radius, double mu_s, double sun_radius,
                            double *mu_transmittance)
{
    *mu_transmittance = mu_s;
    if (kind == MODEL_SUN_VISIBILITY_LESSON_FADE) {
        if (mu_s < 0.0 && rho * rho <= r * r * mu_s * mu_s)
            return 0.0;
        double f = 10.0 * mu_s + 0.5;
        return f < 0.0 ? 0.0 : (f > 1.0 ? 1.0 : f);
    }
    double e, d = height_above_horizon(rho, bottom_radius, mu_s, &e);
    if (!(sun_radius > 0.0))
        return d > 0.0 ? 1.0 : 0.0;
    if (d >= sun_radius)
        return 1.0;
    double f = lens_fraction(d, rho / bottom_radius, sun_radius);
    if (f <= 0.0)
        return 0.0;
    /* The visible part's centroid, above a straight horizon (the curvature moves it by O(R^2)): the unit disc cut at
     * y = a = -d / R = cos(theta) keeps the segment y > a, of area g = theta - sin(theta) cos(theta) and centroid
     * height (2/3) sin^3(theta) / g. theta = 2 asin(sqrt((1 - a) / 2)), 1 - a = (R + d) / R, and g by its series
     * for a small theta (a sliver), so nothing cancels as the disc sinks below the horizon. */
    double theta = 2.0 * asin(sqrt(fmin(1.0, fmax(0.0, 0.5 * (sun_radius + d) / sun_radius))));
    double st = sin(theta), g;
    if (theta < 0.05) {
        double t2 = theta * theta;
        g = (2.0 / 3.0) * theta * t2 * (1.0 - t2 / 5.0 + 2.0 * t2 * t2 / 105.0);
    } else {
        g = theta - st * cos(theta);
    }
    double ybar = g > 0.0 ? (2.0 / 3.0) * st * st * st / g : -cos(theta);
    *mu_transmittance = sin(e + sun_radius * ybar);
    return f;
}
