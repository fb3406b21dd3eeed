/* Directions and LUT mappings: ref_dir, the Bruneton transmittance-LUT mapping (h, mu) <-> (x_mu, x_r) <-> uv
 * with the texel-centre sub-UV, and the Ms LUT's texel parameters (docs/model.md). */
#include "reference/ref_internal.h"

#include <math.h>

void ref_dir(double az, double el, double out[3])
{
    out[0] = cos(el) * cos(az);
    out[1] = sin(el);
    out[2] = cos(el) * sin(az);
}

/* Texel-centre sub-UV: uv = 0.5/N + x (N - 1)/N and its inverse; x clamped to [0, 1]. */
static double x_from_uv(double uv, int n)
{
    if (n < 2)
        return clampd(uv, 0.0, 1.0);
    return clampd((uv - 0.5 / n) * n / (n - 1.0), 0.0, 1.0);
}

static double uv_from_x(double x, int n)
{
    if (n < 2)
        return clampd(x, 0.0, 1.0);
    return 0.5 / n + clampd(x, 0.0, 1.0) * (n - 1.0) / n;
}

void bruneton_x(const model_atmosphere *a, double h, double mu, double *x_mu, double *x_r)
{
    double H = bruneton_H(a);
    h = clampd(h, 0.0, atmo_height(a));
    double rho = sqrt(rho2_of(a, h));
    double d = dist_to_top(a, h, clampd(mu, -1.0, 1.0));
    double d_min = atmo_height(a) - h, d_max = rho + H;
    *x_mu = clampd(d_max > d_min ? (d - d_min) / (d_max - d_min) : 0.0, 0.0, 1.0);
    *x_r = clampd(rho / H, 0.0, 1.0);
}

void bruneton_params(const model_atmosphere *a, double x_mu, double x_r, double *h_out, double *mu_out)
{
    double Rb = a->bottom_radius, H = bruneton_H(a);
    double rho = H * x_r;
    double h = rho * rho / (sqrt(rho * rho + Rb * Rb) + Rb);
    if (h > atmo_height(a))
        h = atmo_height(a);
    double r = Rb + h;
    double d_min = atmo_height(a) - h, d_max = rho + H;
    double d = d_min + x_mu * (d_max - d_min);
    double c = (atmo_height(a) - h) * (a->top_radius + r); /* H^2 - rho^2 = Rt^2 - r^2, without cancellation */
    *h_out = h;
    *mu_out = d == 0.0 ? 1.0 : clampd((c - d * d) / (2.0 * r * d), -1.0, 1.0);
}

void ref_transmittance_uv_to_params(const model_atmosphere *a, double u, double v, int width, int height,
                                    double *altitude, double *mu)
{
    bruneton_params(a, x_from_uv(u, width), x_from_uv(v, height), altitude, mu);
}

void ref_transmittance_params_to_uv(const model_atmosphere *a, double altitude, double mu, int width, int height,
                                    double *u, double *v)
{
    double x_mu, x_r;
    bruneton_x(a, altitude, mu, &x_mu, &x_r);
    *u = uv_from_x(x_mu, width);
    *v = uv_from_x(x_r, height);
}

void ref_multiscatter_texel_params(const model_atmosphere *a, int i, int j, int width, int height, double *altitude,
                                   double *mu_s)
{
    double xu = x_from_uv((i + 0.5) / width, width);
    double xv = x_from_uv((j + 0.5) / height, height);
    /* x = 0.5 + 0.5 sign(mu_s) sqrt(|mu_s|): texels crowd at the terminator (docs/model.md). */
    double y = 2.0 * xu - 1.0;
    *mu_s = y < 0.0 ? -y * y : y * y;
    *altitude = xv * xv * atmo_height(a); /* y = sqrt(h / top): texels crowd near the ground */
}
