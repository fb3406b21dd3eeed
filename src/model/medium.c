/* The medium's definition: Hillaire's Earth and the density profiles (see medium.h). */
#include "model/medium.h"

#include <math.h>
#include <string.h>

/* ---------------------------------------------------------------------------------------------------------- */
/* Medium                                                                                                     */

void model_atmosphere_earth(model_atmosphere *o)
{
    memset(o, 0, sizeof *o);
    o->bottom_radius = 6360.0;
    o->top_radius = 6460.0;
    o->rayleigh_scattering[0] = 5.802e-3;
    o->rayleigh_scattering[1] = 13.558e-3;
    o->rayleigh_scattering[2] = 33.1e-3;
    o->rayleigh_density = model_profile_exponential(8.0);
    for (int c = 0; c < 3; ++c) {
        o->mie_scattering[c] = 3.996e-3;
        o->mie_absorption[c] = 0.444e-3;
        o->sun_illuminance[c] = 20.0;
    }
    o->mie_density = model_profile_exponential(1.2);
    o->mie_g = 0.8;
    o->ozone_absorption[0] = 0.650e-3;
    o->ozone_absorption[1] = 1.881e-3;
    o->ozone_absorption[2] = 0.085e-3;
    o->ozone_density = model_profile_tent(25.0, 15.0);
    o->sun_angular_radius = MODEL_SUN_ANGULAR_RADIUS_DEFAULT;
    o->sun_visibility = MODEL_SUN_VISIBILITY_PENUMBRA;
}

model_density_profile model_profile_exponential(double scale_height)
{
    model_density_layer l = {.width = 0.0, .exp_term = 1.0, .exp_scale = -1.0 / scale_height};
    return (model_density_profile){{l, l}};
}

model_density_profile model_profile_tent(double center, double half_width)
{
    /* Rising to 1 at the centre, falling to 0 at center +- half_width (Bruneton's ozone layers). */
    model_density_layer rise = {.width = center, .linear_term = 1.0 / half_width,
                              .constant_term = 1.0 - center / half_width};
    model_density_layer fall = {.width = 0.0, .linear_term = -1.0 / half_width,
                              .constant_term = 1.0 + center / half_width};
    return (model_density_profile){{rise, fall}};
}

bool model_profile_as_exponential(const model_density_profile *p, double *scale_height)
{
    const model_density_layer *a = &p->layers[0], *b = &p->layers[1];
    bool same = a->exp_term == b->exp_term && a->exp_scale == b->exp_scale && a->linear_term == b->linear_term &&
                a->constant_term == b->constant_term;
    if (!same || a->exp_term != 1.0 || a->exp_scale >= 0.0 || a->linear_term != 0.0 || a->constant_term != 0.0)
        return false;
    *scale_height = -1.0 / a->exp_scale;
    return true;
}

bool model_profile_as_tent(const model_density_profile *p, double *center, double *half_width)
{
    const model_density_layer *a = &p->layers[0], *b = &p->layers[1];
    if (a->exp_term != 0.0 || b->exp_term != 0.0 || a->linear_term <= 0.0 || b->linear_term != -a->linear_term)
        return false;
    double c = a->width, w = 1.0 / a->linear_term;
    if (fabs(a->constant_term - (1.0 - c / w)) > 1e-12 || fabs(b->constant_term - (1.0 + c / w)) > 1e-12)
        return false;
    *center = c, *half_width = w;
    return true;
}

/* One layer's unclamped value at h (the exponent capped as in model_density). */
static double layer_value(const model_density_layer *l, double h)
{
    double e = l->exp_scale * h;
    return (l->exp_term != 0.0 ? l->exp_term * exp(e < 700.0 ? e : 700.0) : 0.0) + l->linear_term * h + l->constant_term;
}

/* Max of one layer over [lo, hi]: a e^(b h) + c h + d has at most one stationary point, where a b e^(b h) = -c. */
static double layer_max(const model_density_layer *l, double lo, double hi)
{
    double m = fmax(layer_value(l, lo), layer_value(l, hi));
    if (l->exp_term != 0.0 && l->exp_scale != 0.0) {
        double q = -l->linear_term / (l->exp_term * l->exp_scale);
        if (q > 0.0) {
            double hs = log(q) / l->exp_scale;
            if (hs > lo && hs < hi)
                m = fmax(m, layer_value(l, hs));
        }
    }
    return m;
}

double model_density(const model_density_profile *p, double h)
{
    /* Below the ground (reached only by below-horizon transmittance rays, which the model integrates through the
     * planet) the medium is held at its ground value, as the GPU's sample_medium() does. */
    if (h < 0.0)
        h = 0.0;
    /* Layer 0 below its width, layer 1 above; the clamp to [0, 1] is Bruneton's. */
    double d = layer_value(h < p->layers[0].width ? &p->layers[0] : &p->layers[1], h);
    return d < 0.0 ? 0.0 : d > 1.0 ? 1.0 : d;
}

double model_density_max(const model_density_profile *p, double hmin, double hmax)
{
    hmin = hmin > 0.0 ? hmin : 0.0; /* below the ground the medium is held at its ground value (model_density) */
    hmax = hmax > hmin ? hmax : hmin;
    double w = p->layers[0].width, m = 0.0;
    if (hmin < w)
        m = layer_max(&p->layers[0], hmin, hmax < w ? hmax : w); /* layer 0's limit at w bounds it from above */
    if (hmax >= w)
        m = fmax(m, layer_max(&p->layers[1], hmin > w ? hmin : w, hmax));
    return m < 0.0 ? 0.0 : m > 1.0 ? 1.0 : m;
}

