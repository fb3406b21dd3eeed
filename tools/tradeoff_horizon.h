/* The horizon-band error of tools/tradeoff (issue 26): a configuration's frame against the per-pixel march (the
 * ultra preset: 128 steps, render scale 1) of the same view, over the pixels within 2 pixels of the analytic
 * horizon (its elevation -atan(sqrt(h (2R + h)) / R), in double), the sun's disc and 3 px around it left out. The mean error of the
 * whole frame cannot see a few wrong rows; this can. Header-only, included by tools/tradeoff.c. */
#ifndef VKSKY_TOOLS_TRADEOFF_HORIZON_H
#define VKSKY_TOOLS_TRADEOFF_HORIZON_H
#include "app/quality/quality.h"
#include "io/half_float.h"
#include "reference/ref_atmosphere.h"
#include "sky/submit.h"
#include <math.h>
#include <stdlib.h>

typedef struct horizon_error { double max, mean; } horizon_error;

/* A configuration's frame of a scene at w x h (bloom off): luminance per pixel (malloc'd). */
static float *horizon_frame(gpu_context *ctx, const quality_config *q, const quality_scene *s, int w, int h,
                            const model_atmosphere *a, double sun_radius)
{
    sky_view v = sky_view_default();
    v.altitude_km = s->altitude_km, v.sun_elevation_deg = s->sun_elevation_deg, v.sun_azimuth_deg = 0.0;
    v.yaw_deg = s->yaw_deg, v.pitch_deg = s->pitch_deg, v.fov_deg = s->fov_deg, v.exposure_ev = s->exposure_ev;
    v.bloom = false;
    sky_renderer_desc desc = {.width = (uint32_t)w, .height = (uint32_t)h, .readback = true,
                              .display_format = VK_FORMAT_R8G8B8A8_SRGB, .lut = sky_lut_quality_default()};
    int bloom_mips = 5;
    quality_apply(q, &v, &desc.lut, &desc.render_scale, &bloom_mips, &desc.bloom_quarter);
    v.bloom = false;
    sky_renderer r;
    sky_renderer_create(&r, ctx, &desc);
    sky_renderer_set_atmosphere(&r, a, sun_radius);
    frame_desc f = {.view = &v};
    sky_renderer_render(&r, &f);
    float *lum = malloc(sizeof(float) * (size_t)w * h);
    const uint16_t *half = r.readback_linear.mapped;
    for (size_t i = 0; i < (size_t)w * h; ++i)
        lum[i] = (float)(0.2126 * io_half_to_float(half[4 * i]) + 0.7152 * io_half_to_float(half[4 * i + 1]) +
                         0.0722 * io_half_to_float(half[4 * i + 2]));
    sky_renderer_destroy(&r);
    return lum;
}

/* Relative luminance error of `lum` against the march `ref` over the horizon band: the pixels whose centre's
 * elevation is within 2 of the column's pixel heights of the horizon, not within 4 sun radii + 3 px of the sun. Floored at
 * 5 % of the band's brightest reference pixel: the error as a share of the sky beside the horizon where the pixel is
 * darker (a ground a thousandth of the sky changes by tens of per cent a pixel, invisibly; issue 26 measured the
 * rows at the horizon so). */
static horizon_error horizon_band_error(const float *lum, const float *ref, const quality_scene *s, int w, int h,
                                        const model_atmosphere *a, double sun_radius)
{
    const double deg = 3.14159265358979323846 / 180.0;
    double R = a->bottom_radius, alt = s->altitude_km;
    double e_h = -atan(sqrt(alt * (2.0 * R + alt)) / R), sun[3];
    ref_dir(0.0, s->sun_elevation_deg * deg, sun);
    unsigned char *band = calloc((size_t)w * h, 1);
    double peak = 0.0;
    for (int y = 0; y + 1 < h; ++y)
        for (int x = 0; x < w; ++x) {
            double d0[3], d1[3];
            ref_pixel_dir(x, y, w, h, s->yaw_deg * deg, s->pitch_deg * deg, s->fov_deg * deg, d0);
            ref_pixel_dir(x, y + 1, w, h, s->yaw_deg * deg, s->pitch_deg * deg, s->fov_deg * deg, d1);
            double el = asin(d0[1]), step = fabs(asin(d1[1]) - el);
            /* The sun's disc and its aureole's first pixels (the sun's error, not the horizon's). */
            bool near_sun = d0[0] * sun[0] + d0[1] * sun[1] + d0[2] * sun[2] > cos(4.0 * sun_radius + 3.0 * step);
            if (fabs(el - e_h) < 2.0 * step && !near_sun) {
                band[(size_t)y * w + x] = 1;
                peak = fmax(peak, ref[(size_t)y * w + x]);
            }
        }
    horizon_error e = {0.0, 0.0};
    size_t count = 0;
    for (size_t i = 0; i < (size_t)w * h; ++i) {
        if (!band[i]) continue;
        double err = fabs(lum[i] - ref[i]) / fmax(ref[i], 0.05 * peak);
        e.max = fmax(e.max, err), e.mean += err, ++count;
    }
    e.mean = count ? e.mean / (double)count : 0.0;
    free(band);
    return e;
}
#endif
