/* Sky radiance of the reference: the view march (graded steps split at the shadow and fade crossings, direct sun
 * transmittance, Psi from the table of psi_table.c), its converged counts, and the image convention's pixel
 * directions. */
#include "reference/ref_internal.h"

#include <math.h>
#include <stddef.h>

/* ---------------------------------------------------------------------------------------------------------- */
/* Sky radiance                                                                                               */

ref_quality ref_quality_converged(void)
{
    /* See tests/test_reference.c for the convergence study behind these counts. */
    ref_quality q = {512, 256, 48, 64, 0};
    return q;
}

/* Camera (altitude, view, sun) -> start point (h, mu, mu_s, nu) of the march; 0 when the ray misses the
 * atmosphere (or the input is unusable). */
static int sky_start(const model_atmosphere *a, double altitude, const double v_in[3], const double s_in[3],
                     double *h, double *mu, double *mus, double *nu, double *t_entry)
{
    *t_entry = 0.0;
    double v[3], s[3];
    double lv = sqrt(v_in[0] * v_in[0] + v_in[1] * v_in[1] + v_in[2] * v_in[2]);
    double ls = sqrt(s_in[0] * s_in[0] + s_in[1] * s_in[1] + s_in[2] * s_in[2]);
    if (!(lv > 0.0) || !(ls > 0.0) || !isfinite(lv) || !isfinite(ls) || isnan(altitude))
        return 0;
    for (int c = 0; c < 3; ++c) {
        v[c] = v_in[c] / lv;
        s[c] = s_in[c] / ls;
    }
    *nu = clampd(v[0] * s[0] + v[1] * s[1] + v[2] * s[2], -1.0, 1.0);
    *mu = clampd(v[1], -1.0, 1.0);
    *mus = clampd(s[1], -1.0, 1.0);
    *h = altitude > 0.0 ? altitude : 0.0;
    double top = atmo_height(a);
    if (*h <= top)
        return 1;
    if (!isfinite(*h) || !(*mu < 0.0))
        return 0;
    /* Above the top: enter at the near intersection with the top sphere, computed about the ray's point of closest
     * approach to the centre so that nothing cancels even for a very distant camera: impact parameter
     * p = r sqrt(1 - mu^2), closest point P_c = r (y - mu v) = r (-mu v.x, (1 - mu)(1 + mu), -mu v.z), the entry
     * point P_e = P_c - sqrt(Rt^2 - p^2) v. There mu_e = -sqrt(Rt^2 - p^2) / Rt and mu_s_e = P_e.s / Rt. */
    double r = a->bottom_radius + *h, Rt = a->top_radius;
    double sin2 = (1.0 - *mu) * (1.0 + *mu);
    double p = r * sqrt(sin2);
    if (!(p < Rt))
        return 0; /* misses (or only grazes) the atmosphere */
    double sq = sqrt((Rt - p) * (Rt + p));
    double pcs = r * (-*mu * v[0] * s[0] + sin2 * s[1] - *mu * v[2] * s[2]);
    *mus = clampd((pcs - sq * *nu) / Rt, -1.0, 1.0);
    *t_entry = -r * *mu - sq; /* the closest point is -r mu along the ray; the entry sq before it */
    *mu = -sq / Rt;
    *h = top;
    return 1;
}

typedef struct sky_ray {
    const model_atmosphere *a;
    double h, r, mu, mus, nu, pr, pm;
    int sun_steps;
    const psi_table *psi;
    double Tv[3];
    double Lr[3], Lm[3]; /* in-scattering by phase: Rayleigh-phase species, Mie (each with its Psi share) */
    double k_rayleigh[MS_ZONAL_LAST], k_mie[MS_ZONAL_LAST]; /* the phases' Legendre coefficients k_1 .. k_6 */
} sky_ray;

/* The factor on a phase's part of the Psi term for a view direction v (v_x toward the sun's azimuth, v_z up,
 * v_y^2 = 1 - v_x^2 - v_z^2) from the second bounce's moments (docs/model.md "The second bounce"): the phase
 * averaged over L2's directions relative to the isotropic 1/(4 pi), with L2 cut to its spherical harmonics of
 * degree <= 2 (the moments) and its zonal part (symmetric about the vertical) to degree 6: 1 + 3 k1 v.m +
 * (15/2) k2 v.Q.v + sum over l = 3..6 of (2l + 1) k_l E[P_l(w_z)] P_l(v_z), k_l the phase's Legendre coefficients
 * (Rayleigh: 0, 1/10 and no higher, exact; Henyey-Greenstein: g^l). Never below 0. */
double ms_phase_factor(const double mom[MS_MOMENTS], double vx, double vz, const double k[MS_ZONAL_LAST])
{
    double vy2 = fmax(0.0, (1.0 - vz) * (1.0 + vz) - vx * vx);
    /* v.Q.v with Q_xx - Q_yy = D, Q_xx + Q_yy = -Q_zz */
    double vqv = 0.5 * mom[MS_D] * (vx * vx - vy2) + 0.5 * mom[MS_QZZ] * (3.0 * vz * vz - 1.0) +
                 2.0 * mom[MS_QXZ] * vx * vz;
    double f = 1.0 + 3.0 * k[0] * (vx * mom[MS_MX] + vz * mom[MS_MZ]) + 7.5 * k[1] * vqv;
    double pl[MS_ZONAL_LAST + 1];
    legendre_upto(vz, MS_ZONAL_LAST, pl);
    for (int l = MS_ZONAL_FIRST; l <= MS_ZONAL_LAST; ++l)
        f += (2 * l + 1) * k[l - 1] * mom[MS_Z3 + l - MS_ZONAL_FIRST] * pl[l];
    return fmax(0.0, f);
}

/* One midpoint step [t - dt/2, t + dt/2] of the view march (per-step analytic integration). */
static void sky_step(sky_ray *s, double t, double dt)
{
    const model_atmosphere *a = s->a;
    double rt, ht;
    medium m;
    if (!(dt > 0.0))
        return;
    ray_point(a, s->h, s->r, s->mu, t, &rt, &ht);
    ht = clampd(ht, 0.0, atmo_height(a));
    double mst = rt > 0.0 ? clampd((s->r * s->mus + t * s->nu) / rt, -1.0, 1.0) : s->mus;
    medium_at(a, ht, &m);
    double mut;
    double vis = sun_visibility_at(a, rho2_of(a, ht), rt, mst, &mut);
    double Ts[3] = {0.0, 0.0, 0.0}, ps[3] = {0.0, 0.0, 0.0};
    if (vis > 0.0) {
        double tau[3];
        optical_depth(a, ht, mut, s->sun_steps, tau);
        for (int c = 0; c < 3; ++c)
            Ts[c] = exp(-tau[c]);
    }
    double fr = 1.0, fm = 1.0; /* the second bounce's anisotropy on the Rayleigh and Mie parts of the Psi term */
    if (s->psi) {
        double mom[MS_MOMENTS];
        psi_table_eval(s->psi, a, ht, mst, ps, mom);
        if (rt > 0.0) {
            /* the view direction in the sample's frame: v_z = mu_v, v_x toward the sun's azimuth, v_y across */
            double muv = clampd((s->r * s->mu + t) / rt, -1.0, 1.0), sin2s = (1.0 - mst) * (1.0 + mst);
            double vx = sin2s > 1e-12 ? (s->nu - muv * mst) / sqrt(sin2s) : 0.0;
            fr = ms_phase_factor(mom, vx, muv, s->k_rayleigh);
            fm = ms_phase_factor(mom, vx, muv, s->k_mie);
        }
    }
    /* Psi multiplies the total scattering coefficient, sr + sm: each group takes its own share, so the two parts
     * add up to the whole source (each with its phase's anisotropy factor). */
    for (int c = 0; c < 3; ++c) {
        double w = a->sun_illuminance[c] * s->Tv[c] * step_integral(m.ext[c], dt);
        s->Lr[c] += w * m.sr[c] * (vis * Ts[c] * s->pr + ps[c] * fr);
        s->Lm[c] += w * m.sm[c] * (vis * Ts[c] * s->pm + ps[c] * fm);
        s->Tv[c] *= exp(-m.ext[c] * dt);
    }
}

/* March from (h, mu) with the sun at mu_s and nu = dot(view, sun) over the first `limit` km of the ray (all of
 * it when longer): view_steps steps graded toward the lowest point, a step that contains a crossing of the
 * earth's shadow or a kink of the horizon fade split there (ray_cuts), direct sun transmittance, Psi from the
 * table. */
static void sky_march(const model_atmosphere *a, double h, double mu, double mus, double nu, double limit,
                      int view_steps, int sun_steps, const psi_table *psi, ref_aerial *out)
{
    sky_ray s = {a, h, a->bottom_radius + h, mu, mus, nu, phase_rayleigh(nu), phase_hg(a->mie_g, nu),
                 sun_steps, psi, {1.0, 1.0, 1.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.1}, {0.0}};
    for (int l = 1; l <= MS_ZONAL_LAST; ++l)
        s.k_mie[l - 1] = pow(a->mie_g, l); /* Henyey-Greenstein */
    double tend, cuts[MAX_CUTS];
    int ground = hit_ground(a, h, mu, &tend);
    if (!ground)
        tend = dist_to_top(a, h, mu);
    if (limit < tend) { /* the segment ends in the air: grade it as a ray that does not reach the ground */
        tend = limit > 0.0 ? limit : 0.0;
        ground = 0;
    }
    if (tend > 0.0) {
        int ncut = ray_cuts(a, h, mu, mus, nu, tend, cuts), ic = 0;
        for (int k = 0; k < view_steps; ++k) {
            double t, dt;
            ray_step(a, h, mu, tend, ground, 1, view_steps, k, &t, &dt);
            double t0 = t - 0.5 * dt, t1 = t + 0.5 * dt;
            while (ic < ncut && cuts[ic] <= t0)
                ++ic;
            while (ic < ncut && cuts[ic] < t1) {
                sky_step(&s, 0.5 * (t0 + cuts[ic]), cuts[ic] - t0);
                t0 = cuts[ic++];
            }
            sky_step(&s, 0.5 * (t0 + t1), t1 - t0);
        }
    }
    for (int c = 0; c < 3; ++c) {
        out->rayleigh[c] = (s.Lr[c] > 0.0 && isfinite(s.Lr[c])) ? s.Lr[c] : 0.0;
        out->mie[c] = (s.Lm[c] > 0.0 && isfinite(s.Lm[c])) ? s.Lm[c] : 0.0;
        out->transmittance[c] = s.Tv[c];
    }
}

static ref_quality quality_at_least_1(ref_quality q)
{
    if (q.view_steps < 1)
        q.view_steps = 1;
    if (q.sun_steps < 1)
        q.sun_steps = 1;
    if (q.ms_sqrt_dirs < 2)
        q.ms_sqrt_dirs = 2;
    if (q.ms_steps < 1)
        q.ms_steps = 1;
    return q;
}

void ref_sky_radiance(const model_atmosphere *a, double altitude, const double view_dir[3], const double sun_dir[3],
                      ref_quality q, double out_rgb[3])
{
    double h, mu, mus, nu, t_entry;
    out_rgb[0] = out_rgb[1] = out_rgb[2] = 0.0;
    q = quality_at_least_1(q);
    if (!sky_start(a, altitude, view_dir, sun_dir, &h, &mu, &mus, &nu, &t_entry))
        return;
    const psi_table *psi = q.ms_off ? NULL : psi_cache_get(a, q.ms_sqrt_dirs, q.ms_steps);
    ref_aerial seg;
    sky_march(a, h, mu, mus, nu, INFINITY, q.view_steps, q.sun_steps, psi, &seg);
    for (int c = 0; c < 3; ++c)
        out_rgb[c] = seg.rayleigh[c] + seg.mie[c];
}

void ref_radiance_to_point(const model_atmosphere *a, double altitude, const double view_dir[3],
                           const double sun_dir[3], double distance, ref_quality q, ref_aerial *out)
{
    double h, mu, mus, nu, t_entry;
    *out = (ref_aerial){{1.0, 1.0, 1.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    q = quality_at_least_1(q);
    if (!(distance > 0.0) || !sky_start(a, altitude, view_dir, sun_dir, &h, &mu, &mus, &nu, &t_entry))
        return;
    if (!(distance > t_entry))
        return; /* the point lies in the empty space before the atmosphere */
    const psi_table *psi = q.ms_off ? NULL : psi_cache_get(a, q.ms_sqrt_dirs, q.ms_steps);
    sky_march(a, h, mu, mus, nu, distance - t_entry, q.view_steps, q.sun_steps, psi, out);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Image convention                                                                                           */

void ref_pixel_dir(int x, int y, int width, int height, double yaw_rad, double pitch_rad, double fov_y_rad,
                   double out[3])
{
    double f[3], rgt[3], up[3];
    ref_dir(yaw_rad, pitch_rad, f);
    /* right = normalize(cross(forward, +Y)) = normalize(-f.z, 0, f.x); dir(yaw + 90 deg, 0) when degenerate. */
    double rl = sqrt(f[2] * f[2] + f[0] * f[0]);
    if (rl > 1e-12) {
        rgt[0] = -f[2] / rl;
        rgt[1] = 0.0;
        rgt[2] = f[0] / rl;
    } else {
        ref_dir(yaw_rad + 0.5 * REF_PI, 0.0, rgt);
    }
    /* up = cross(right, forward) */
    up[0] = rgt[1] * f[2] - rgt[2] * f[1];
    up[1] = rgt[2] * f[0] - rgt[0] * f[2];
    up[2] = rgt[0] * f[1] - rgt[1] * f[0];
    double ndc_x = 2.0 * (x + 0.5) / width - 1.0;
    double ndc_y = 1.0 - 2.0 * (y + 0.5) / height;
    double th = tan(0.5 * fov_y_rad), aspect = (double)width / height;
    double d[3], len = 0.0;
    for (int c = 0; c < 3; ++c) {
        d[c] = f[c] + ndc_x * th * aspect * rgt[c] + ndc_y * th * up[c];
        len += d[c] * d[c];
    }
    len = sqrt(len);
    for (int c = 0; c < 3; ++c)
        out[c] = d[c] / len;
}
