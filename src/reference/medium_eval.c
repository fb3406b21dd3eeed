/* The medium at a point and what is integrated from it alone: sigma_s and sigma_t (medium_at, the one definition
 * the reference uses, extra species included), the optical depth to the top and ref_transmittance. */
#include "reference/ref_internal.h"

#include <math.h>

void medium_at(const model_atmosphere *a, double h, medium *m)
{
    double rr = model_density(&a->rayleigh_density, h);
    double rm = model_density(&a->mie_density, h);
    double ro = model_density(&a->ozone_density, h);
    for (int c = 0; c < 3; ++c) {
        m->sr[c] = rr * a->rayleigh_scattering[c];
        m->sm[c] = rm * a->mie_scattering[c];
        m->ext[c] = rm * a->mie_absorption[c] + ro * a->ozone_absorption[c];
    }
    for (int i = 0; i < a->extra_count; ++i) {
        double re = model_density(&a->extra[i].density, h);
        for (int c = 0; c < 3; ++c) {
            m->sr[c] += re * a->extra[i].scattering[c];
            m->ext[c] += re * a->extra[i].absorption[c];
        }
    }
    for (int c = 0; c < 3; ++c) {
        m->scat[c] = m->sr[c] + m->sm[c];
        m->ext[c] += m->scat[c];
    }
}

void optical_depth(const model_atmosphere *a, double h, double mu, int steps, double tau[3])
{
    double d = dist_to_top(a, h, mu);
    double r = a->bottom_radius + h;
    double dt = d / steps;
    double sum[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < steps; ++k) {
        double rt, ht;
        medium m;
        ray_point(a, h, r, mu, (k + 0.5) * dt, &rt, &ht);
        medium_at(a, ht, &m); /* the one definition of sigma_t, extra species included */
        for (int c = 0; c < 3; ++c)
            sum[c] += m.ext[c];
    }
    for (int c = 0; c < 3; ++c)
        tau[c] = dt * sum[c];
}

void ref_transmittance(const model_atmosphere *a, double altitude, double mu, int steps, double out[3])
{
    double tau[3];
    if (steps < 1)
        steps = 1;
    optical_depth(a, clampd(altitude, 0.0, atmo_height(a)), clampd(mu, -1.0, 1.0), steps, tau);
    for (int c = 0; c < 3; ++c)
        out[c] = exp(-tau[c]);
}
