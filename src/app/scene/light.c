/* Physical light: units, the sun's scale, EXR pixels and auto exposure (see light.h; docs/units.md). */
#include "app/scene/light.h"
#include "io/half_float.h"
#include "model/spectrum.h"
#include "reference/ref_atmosphere.h"
#include "reference/spectral.h"
#include "sky/projection.h"
#include "sky/view_params.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define HALF_MAX 65504.0

void light_sun(const options *o, double out[3])
{
    const double *given = o->atmosphere.sun_illuminance;
    if (o->units == OPTIONS_UNITS_RELATIVE) {
        for (int c = 0; c < 3; ++c) out[c] = given[c];
        return;
    }
    double toa[3];
    spectrum_solar_rec709_toa(toa);
    for (int c = 0; c < 3; ++c) out[c] = toa[c] * given[c] / LIGHT_RELATIVE_SUN;
}

double light_scale(const options *o)
{
    if (o->units == OPTIONS_UNITS_RELATIVE) return 1.0;
    double e[3];
    light_sun(o, e);
    double brightest = fmax(e[0], fmax(e[1], e[2]));
    if (!(brightest > 0.0)) return 1.0;
    /* The sky is far below the sun's illuminance: the lesson's scale (the sun at 20) keeps the dark end of twilight
     * out of half's subnormals, as precise as --units relative. */
    double scale = exp2(floor(log2(LIGHT_RELATIVE_SUN / brightest)));
    if (!o->sun_disc) return scale;
    /* The disc's peak radiance is E T / (Omega (1 - u/3)) (limb darkening 1 - u (1 - cos) integrates to 1 - u/3 of
     * a flat disc); keep it below half of half's largest value. T: the transmittance toward the sun, or toward the
     * horizon when the sun is below it (its penumbra's rim still shows there). A low sun, dimmed by the air, leaves
     * the lesson's scale; a high one takes it down by up to four stops (the twilight sky is then dark anyway). */
    const model_atmosphere *a = &o->atmosphere;
    double h = o->view.altitude_km, rc = a->bottom_radius + h;
    double horizon = -sqrt(fmax(0.0, 1.0 - (a->bottom_radius / rc) * (a->bottom_radius / rc)));
    double mu = fmax(sin(o->view.sun_elevation_deg * 3.14159265358979323846 / 180.0), horizon + 1e-6), t[3];
    ref_transmittance(a, h, mu, 2000, t);
    double peak = fmax(e[0] * t[0], fmax(e[1] * t[1], e[2] * t[2]));
    double r = o->sun_angular_radius_deg * 3.14159265358979323846 / 180.0;
    double omega = 2.0 * 3.14159265358979323846 * (1.0 - cos(r));
    double fit = 0.5 * HALF_MAX * omega * (1.0 - o->limb_darkening / 3.0);
    return peak > 0.0 ? fmin(scale, exp2(floor(log2(fit / peak)))) : scale;
}

static void light_sun_at_camera_spectral(const options *o, bool visible, const double e[3], double out[3]);

void light_sun_at_camera(const options *o, double out[3])
{
    const model_atmosphere *a = &o->atmosphere;
    double h = o->view.altitude_km, r = a->bottom_radius + h;
    double mu = sin(o->view.sun_elevation_deg * 3.14159265358979323846 / 180.0);
    /* Below the camera's geometric horizon the planet is in the way. */
    double horizon = -sqrt(fmax(0.0, 1.0 - (a->bottom_radius / r) * (a->bottom_radius / r)));
    double t[3] = {0, 0, 0}, e[3];
    light_sun(o, e);
    if (o->spectral > 0) {   /* --spectral N: the sun's spectrum through the medium per wavelength, as rendered */
        light_sun_at_camera_spectral(o, mu >= horizon, e, out);
        return;
    }
    if (mu >= horizon) ref_transmittance(a, h, mu, 2000, t);
    for (int i = 0; i < 3; ++i) out[i] = e[i] * t[i];
}

/* The spectral path's sun at the camera (app/runs/spectral_render.c, the spectral reference): each of the N bins'
 * weights (683 times the solar spectrum times the CIE functions over the bin) times the medium's transmittance at
 * the bin's centre, summed to XYZ, scaled to the configured sun's luminance over the spectrum's own illuminance,
 * then linear Rec.709: what the spectral image's disc integrates to. */
static void light_sun_at_camera_spectral(const options *o, bool visible, const double e[3], double out[3])
{
    const model_atmosphere *a = &o->atmosphere;
    double mu = sin(o->view.sun_elevation_deg * 3.14159265358979323846 / 180.0), xyz[3] = {0, 0, 0};
    spectral_medium medium;
    if (o->spectral_medium_set) medium = o->spectral_medium;
    else spectral_medium_from_rgb(a, &medium);
    int n = o->spectral;
    for (int g = 0; visible && 3 * g < n; ++g) {
        double nm[3], sun[3] = {1, 1, 1}, t[3];
        for (int c = 0; c < 3; ++c) nm[c] = ref_spectral_nm(n, 3 * g + c < n ? 3 * g + c : n - 1);
        model_atmosphere packed;
        spectral_medium_pack(&medium, a, nm, sun, &packed);
        ref_transmittance(&packed, o->view.altitude_km, mu, 2000, t);
        for (int c = 0; c < 3 && 3 * g + c < n; ++c) {
            double w[3];
            ref_spectral_weights(n, 3 * g + c, w);
            for (int k = 0; k < 3; ++k) xyz[k] += w[k] * t[c];
        }
    }
    double y_sun = 0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2], k = y_sun / spectrum_solar_illuminance_toa();
    for (int i = 0; i < 3; ++i) xyz[i] *= k;
    spectrum_xyz_to_rec709(xyz, out);
}

void light_render_atmosphere(const options *o, model_atmosphere *out)
{
    *out = o->atmosphere;
    double e[3], s = light_scale(o);
    light_sun(o, e);
    for (int c = 0; c < 3; ++c) out->sun_illuminance[c] = e[c] * s;
}

void light_finish(options *o)
{
    bool photometric = o->units == OPTIONS_UNITS_PHOTOMETRIC;
    o->exposure_stops = o->view.exposure_ev;
    o->view.ev100 = photometric;
    if (photometric && o->exposure_given) o->view.exposure_ev = o->exposure_ev100;
    o->view.light_scale = light_scale(o);
}

void light_set_sun_lux(options *o, double lux)
{
    /* The lesson's 20 is the real sun in either unit system, so lux means the same whichever --units comes later. */
    double per_lux = LIGHT_RELATIVE_SUN / spectrum_solar_illuminance_toa();
    for (int c = 0; c < 3; ++c) o->atmosphere.sun_illuminance[c] = lux * per_lux;
}

float *light_exr_pixels(const options *o, const uint16_t *rgba_half, size_t pixels, bool *store_float)
{
    float *out = malloc(pixels * 4 * sizeof(float));
    if (out) light_exr_pixels_into(o, rgba_half, pixels, out, store_float);   /* light_pixels.c */
    return out;
}

bool light_stream_float(const options *o)
{
    if (o->exr_type != OPTIONS_EXR_AUTO) return o->exr_type == OPTIONS_EXR_FLOAT;
    if (o->units == OPTIONS_UNITS_RELATIVE || !o->sun_disc) return false;
    double c[3];
    light_sun_at_camera(o, c);
    return c[0] > 0.0 || c[1] > 0.0 || c[2] > 0.0;
}

const char *light_units_text(const options *o)
{
    return o->units == OPTIONS_UNITS_RELATIVE ? "relative (the lesson's scale: the sun 20,20,20; no physical unit)"
                                              : "cd/m2 (linear Rec.709, D65; Y = 0.2126 R + 0.7152 G + 0.0722 B is luminance)";
}

const char *light_sun_units_text(const options *o)
{
    return o->units == OPTIONS_UNITS_RELATIVE ? "relative" : "lx (linear Rec.709 whose Y is illuminance)";
}

void light_sky_attrs(const options *o, io_exr_sky_attrs *a)
{
    double d[3], e[3], c[3];
    projection_dir_from_angles(o->view.sun_azimuth_deg, o->view.sun_elevation_deg, d);
    light_sun(o, e);
    light_sun_at_camera(o, c);
    a->has_sun = true;
    for (int i = 0; i < 3; ++i)
        a->sun_direction[i] = (float)d[i], a->sun_illuminance[i] = (float)e[i], a->sun_at_camera[i] = (float)c[i];
    a->units = light_units_text(o);
    a->sun_units = light_sun_units_text(o);
    a->white_luminance = o->units == OPTIONS_UNITS_PHOTOMETRIC ? 1.0f : 0.0f;
}

static ref_quality meter_quality(void)
{
    return (ref_quality){.view_steps = 64, .sun_steps = 32, .ms_sqrt_dirs = 16, .ms_steps = 16};
}

view_rays light_view_rays(const sky_view *v, int width, int height)
{
    view_rays rays;
    sky_view_basis(v, rays.forward, rays.right, rays.up);
    rays.ty = tan(0.5 * v->fov_deg * 3.14159265358979323846 / 180.0), rays.tx = rays.ty * width / height;
    return rays;
}

bool light_map_dir(int projection, int width, int height, double x, double y, double dir[3])
{
    return projection_dir((sky_projection)projection, width, height, x, y, dir);
}

double light_horizon_sine(double altitude_km, double ground_radius_km)
{
    return sky_view_horizon_sine(altitude_km, ground_radius_km);
}

double light_meter_pixel(const options *o, const sky_view *v, int width, int height, double x, double y)
{
    double d[3], sun[3], rgb[3];
    view_rays rays = light_view_rays(v, width, height);
    const double *f = rays.forward, *r = rays.right, *u = rays.up, tx = rays.tx, ty = rays.ty;
    double nx = 2.0 * x / width - 1.0, ny = 1.0 - 2.0 * y / height;
    for (int i = 0; i < 3; ++i) d[i] = f[i] + nx * tx * r[i] + ny * ty * u[i];
    projection_dir_from_angles(v->sun_azimuth_deg, v->sun_elevation_deg, sun);
    model_atmosphere a = o->atmosphere;
    light_sun(o, a.sun_illuminance);
    ref_sky_radiance(&a, v->altitude_km, d, sun, meter_quality(), rgb);
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

double light_auto_ev100(double log_average_cd_m2) { return log2(log_average_cd_m2 * 100.0 / 12.5); }

bool light_auto_exposure_wanted(const options *o)
{
    bool png = false;
    for (int i = 0; i < o->output_count; ++i) {
        size_t n = strlen(o->outputs[i]);
        png = png || (n > 4 && strcasecmp(o->outputs[i] + n - 4, ".png") == 0);
    }
    return png && (o->auto_exposure || (o->units == OPTIONS_UNITS_PHOTOMETRIC && !o->exposure_given));
}

void light_expose(sky_view *v, double log_average)
{
    double ev100 = light_auto_ev100(log_average);
    /* exposure_ev and the clamp keep the --exposure flag's range (-20..20) in relative units; EV100 may go past it
     * (a sun-lit snowfield is EV100 16, the disc itself 30): the window's keys clamp, this does not. */
    v->exposure_ev = v->ev100 ? ev100 : -log2(1.2) - ev100;
}
