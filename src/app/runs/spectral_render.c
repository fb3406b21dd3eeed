/* --spectral N on the GPU (spectral_render.h). */
#include "app/runs/spectral_render.h"
#include "app/quality/quality.h"
#include "app/runs/stop.h"
#include "app/runs/tiles.h"
#include "io/half_float.h"
#include "model/spectrum.h"
#include "reference/spectral.h"
#include "sky/view_params.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static struct {
    int wavelengths;
    bool medium_set;
    spectral_medium medium;
    sequence_render_fn inner;
} job;

static bool ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), m = strlen(tail);
    return n >= m && strcasecmp(s + n - m, tail) == 0;
}

int spectral_render_check(const options *o, const char *flag)
{
    if (!o->spectral) return 0;
    if (o->spectral % 4 || o->spectral > SPECTRAL_GPU_MAX) {
        fprintf(stderr, "vksky: %s: %d wavelengths on the GPU; expected 0 (RGB) or a multiple of 4 from 4 to %d "
                        "(3 to 120 with --reference)\n", flag, o->spectral, SPECTRAL_GPU_MAX);
        return 2;
    }
    if (o->output_count == 0 || o->bench_frames > 0) {
        fprintf(stderr, "vksky: %s: on the GPU only with --render FILE.exr (not the window, not --bench)\n", flag);
        return 2;
    }
    for (int i = 0; i < o->output_count; ++i)
        if (!ends_with(o->outputs[i], ".exr")) {
            fprintf(stderr, "vksky: %s: '%s': on the GPU only .exr (scene-linear) outputs are accepted\n", flag,
                    o->outputs[i]);
            return 2;
        }
    if (tiles_wanted(o)) {
        fprintf(stderr, "vksky: %s: not with an environment map (--projection) or an image over the band budget\n",
                flag);
        return 2;
    }
    return 0;
}

void spectral_render_begin(const options *o, sequence_render_fn inner)
{
    job.wavelengths = o->spectral;
    job.medium_set = o->spectral_medium_set;
    job.medium = o->spectral_medium;
    job.inner = inner;
}

/* Whether the horizon passes within HORIZON_MARGIN pixels of any pixel of the (perspective) frame: the sign of each
 * pixel centre's elevation sine against the horizon's, over the image grown by the margin on every side. */
#define HORIZON_MARGIN 3
static bool horizon_in_view(const options *o)
{
    double f[3], right[3], up[3];
    sky_view_basis(&o->view, f, right, up);
    double ty = tan(0.5 * o->view.fov_deg * 3.14159265358979323846 / 180.0), tx = ty * o->width / o->height;
    double sin_h = sky_view_horizon_sine(o->view.altitude_km, o->atmosphere.bottom_radius);
    bool above = false, below = false;
    for (int j = -HORIZON_MARGIN; j < o->height + HORIZON_MARGIN; ++j)
        for (int i = -HORIZON_MARGIN; i < o->width + HORIZON_MARGIN; ++i) {
            double x = 2.0 * (i + 0.5) / o->width - 1.0, y = 1.0 - 2.0 * (j + 0.5) / o->height, d[3];
            for (int k = 0; k < 3; ++k) d[k] = f[k] + x * tx * right[k] + y * ty * up[k];
            double s = d[1] / sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (s >= sin_h) above = true;
            else below = true;
            if (above && below) return true;
        }
    return false;
}

/* Whether the sun's disc reaches into the (perspective) frame: above the horizon, its direction within the image
 * grown by 4 pixels and the sun's radius (the power disc's support reaches 3 texels past the true disc). */
static bool sun_in_view(const options *o)
{
    double f[3], right[3], up[3], s[3];
    const double deg = 3.14159265358979323846 / 180.0;
    sky_view_basis(&o->view, f, right, up);
    double ty = tan(0.5 * o->view.fov_deg * deg), tx = ty * o->width / o->height;
    double el = o->view.sun_elevation_deg * deg, az = o->view.sun_azimuth_deg * deg;
    s[0] = cos(el) * cos(az), s[1] = sin(el), s[2] = cos(el) * sin(az);
    /* Wholly below the horizon: the planet hides it (the power disc's share above the horizon is its penumbra's). */
    double horizon = asin(sky_view_horizon_sine(o->view.altitude_km, o->atmosphere.bottom_radius));
    if (el + o->sun_angular_radius_deg * deg < horizon) return false;
    double z = s[0] * f[0] + s[1] * f[1] + s[2] * f[2];
    if (z <= 0.0) return false;
    double x = (s[0] * right[0] + s[1] * right[1] + s[2] * right[2]) / (z * tx);
    double y = (s[0] * up[0] + s[1] * up[1] + s[2] * up[2]) / (z * ty);
    double r = tan(o->sun_angular_radius_deg * deg) / ty;   /* the disc's radius, in y's units */
    return fabs(x) <= 1.0 + 8.0 / o->width + r * o->height / o->width && fabs(y) <= 1.0 + 8.0 / o->height + r;
}

bool spectral_render_four_wide(const options *o)
{
    const char *pack = getenv("VKSKY_SPECTRAL_PACK");
    if (o->spectral <= 0 || (pack && !strcmp(pack, "3"))) return false;
    if (pack && !strcmp(pack, "4")) return true;
    /* The four-wide image has no horizon resolve (its alpha is a wavelength): a frame with the horizon in it keeps
     * three to a pass, whose tone map anti-aliases the horizon per pixel (issue 26). */
    return !horizon_in_view(o);
}

/* The ground's albedo at a wavelength: the RGB law (680, 550, 440 nm, linear between), as the spectral reference's
 * irradiance takes it. */
static double albedo_at(const sky_features *base, double nm)
{
    spectral_law law = {.kind = SPECTRAL_LAW_RGB};
    memcpy(law.rgb, base->ground_albedo, sizeof law.rgb);
    return spectral_law_eval(&law, nm);
}

/* Group g of `width` (3 or 4) wavelengths: the first three as the channels of a model_atmosphere (the reference's
 * packing, ref_spectral_group's for width 3), the fourth (width 4) as sky_fourth, each channel's sun the configured
 * sun's luminance `sun_y`. idx: the bins, a group past the last bin repeats it (weight 0). Returns the real ones. */
static int pack_group(const ref_spectral *s, int g, int width, const model_atmosphere *base, double sun_y,
                      const sky_features *base_features, model_atmosphere *a, sky_features *feat, int idx[4])
{
    int n = s->wavelengths, real = 0;
    double nm[4], sun[3] = {sun_y, sun_y, sun_y};
    for (int c = 0; c < width; ++c) {
        int i = width * g + c;
        if (i < n) ++real;
        else i = n - 1;
        idx[c] = i;
        nm[c] = ref_spectral_nm(n, i);
    }
    spectral_medium_pack(&s->medium, base, nm, sun, a);
    *feat = *base_features;
    for (int c = 0; c < 3; ++c) feat->ground_albedo[c] = albedo_at(base_features, nm[c]);
    if (width == 4) {
        spectral_coefficients k;
        spectral_medium_eval(&s->medium, nm[3], &k);
        sky_fourth *w = &feat->fourth;
        *w = (sky_fourth){.rayleigh_scattering = k.rayleigh_scattering, .mie_scattering = k.mie_scattering,
                          .mie_absorption = k.mie_absorption, .ozone_absorption = k.ozone_absorption,
                          .sun_illuminance = sun_y, .ground_albedo = albedo_at(base_features, nm[3])};
        for (int e = 0; e < VKSKY_MAX_EXTRA && e < MODEL_MAX_EXTRA_SPECIES; ++e)
            w->extra_scattering[e] = k.extra_scattering[e], w->extra_absorption[e] = k.extra_absorption[e];
    }
    return real;
}

void spectral_render_frame(sky_renderer *r, const frame_desc *f)
{
    const model_atmosphere base = r->medium;
    const sky_features base_features = r->features;
    const double sun_radius = r->sun_angular_radius;
    ref_spectral s;
    ref_spectral_init(&s, &base, job.wavelengths);
    if (job.medium_set) s.medium = job.medium;
    /* Each channel's sun is the configured sun's luminance, so that a group's image has the magnitudes of today's
     * RGB image (half floats keep their precision at twilight); the sum then divides it out again with the
     * spectrum's own illuminance: the sun at the top of the atmosphere comes out as the solar spectrum's colour
     * with the configured sun's luminance (the spectral reference's sun_scale, app/runs/reference_run.c). */
    const double *e = base.sun_illuminance;
    double sun_y = 0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2];
    double toa = spectrum_solar_illuminance_toa();
    size_t pixels = (size_t)r->desc.width * r->desc.height;
    float *xyz = calloc(pixels * 3, sizeof *xyz);
    if (!xyz) {
        fprintf(stderr, "vksky: --spectral: out of memory\n");
        exit(1);
    }
    /* Four wavelengths a pass in the four-wide build (its composite holds them in RGBA), else three. */
    int width = r->desc.spectral4 ? 4 : 3;
    int n = job.wavelengths, groups = (n + width - 1) / width;
    uint16_t *px = r->readback_linear.mapped;
    for (int g = 0; g < groups && !stop_requested(); ++g) {
        model_atmosphere a;
        sky_features feat;
        int idx[4];
        int real = pack_group(&s, g, width, &base, sun_y, &base_features, &a, &feat, idx);
        double m[4][3];   /* m[c]: channel c's XYZ per unit of the group's image */
        for (int c = 0; c < width; ++c) {
            ref_spectral_weights(n, idx[c], m[c]);
            for (int k = 0; k < 3; ++k) m[c][k] = c < real ? m[c][k] / toa : 0.0;
        }
        sky_renderer_set_scene(r, &a, sun_radius, &feat);
        job.inner(r, f);
        for (size_t i = 0; i < pixels; ++i) {
            const uint16_t *p = px + 4 * i;
            for (int c = 0; c < width; ++c) {
                float v = io_half_to_float(p[c]);
                for (int k = 0; k < 3; ++k) xyz[3 * i + k] += (float)(m[c][k] * v);
            }
        }
    }
    /* XYZ -> linear Rec.709 (D65), back into the linear readback the EXR writer takes; alpha 1, the composite's (the
     * four-wide readback's alpha is the last group's fourth wavelength). */
    for (size_t i = 0; i < pixels; ++i) {
        double in[3] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, rgb[3];
        spectrum_xyz_to_rec709(in, rgb);
        for (int k = 0; k < 3; ++k) {
            /* Out of Rec.709's gamut stays negative, as the reference writes it; half's range bounds it. */
            double v = rgb[k] < -65504.0 ? -65504.0 : rgb[k] > 65504.0 ? 65504.0 : rgb[k];
            px[4 * i + k] = io_float_to_half((float)v);
        }
        px[4 * i + 3] = io_float_to_half(1.0f);
    }
    free(xyz);
    sky_renderer_set_scene(r, &base, sun_radius, &base_features);
}

int spectral_auto(options *o, bool possible)
{
    if (!o->quality_auto || o->spectral || o->max_color_error > 0.0 || o->reference || !possible) return 0;
    for (int i = 1; i < o->argc; ++i)   /* --spectral 0 given: RGB asked for */
        if (!strcmp(o->argv[i], "--spectral") || !strncmp(o->argv[i], "--spectral=", 11)) return 0;
    /* A still frame only: a sequence keeps its pipelined RGB frames (spectral runs serially, a pass per group). Not
     * with the sun's disc in the frame: it carries the sun's power at radiances past half floats' range (an EXR
     * written as float, docs/units.md), and the spectral sum is read back in half floats. */
    if (o->output_count == 0 || o->bench_frames > 0 || tiles_wanted(o) || sequence_active(o)) return 0;
    if (o->sun_disc && sun_in_view(o)) return 0;
    for (int i = 0; i < o->output_count; ++i)
        if (!ends_with(o->outputs[i], ".exr")) return 0;
    unsigned classes = o->quality_classes;
    double rgb = 0.0, measured;
    for (int c = 0; c < QUALITY_SCENE_COUNT; ++c)
        if (classes & (1u << c)) rgb = fmax(rgb, quality_color_error(0, c));
    /* Noon and afternoon (RGB within 2.4) stay RGB: their colour is off by less than the keep threshold, and the
     * fewest wavelengths within the budget there (8) would double the frame's cost for it. */
    if (rgb <= SPECTRAL_AUTO_RGB_KEEP) return 0;
    int n = spectral_pick(SPECTRAL_AUTO_BUDGET, classes, &measured);
    if (n <= 0) return 0;
    o->spectral = n;
    char names[96];
    quality_class_names(classes, names, sizeof names);
    printf("vksky: --quality auto: RGB's colour on the '%s' scene is within CIEDE2000 %.2f of the spectrum's, over %g: "
           "picked --spectral %d (measured worst CIEDE2000 %.2f, budget %g; --spectral 0 keeps RGB)\n",
           names, rgb, SPECTRAL_AUTO_RGB_KEEP, n, measured, SPECTRAL_AUTO_BUDGET);
    return n;
}

/* The measured colour table lives with the other measured tables (app/quality/quality_color_table.h). */
int spectral_pick(double max_de, unsigned classes, double *measured)
{
    int settings[16], count = quality_color_settings(settings, 16);
    double best = INFINITY;
    for (int k = 0; k < count; ++k) {
        if (settings[k] > SPECTRAL_GPU_MAX) continue;
        double worst = 0.0;
        for (int c = 0; c < QUALITY_SCENE_COUNT; ++c)
            if (classes & (1u << c)) worst = fmax(worst, quality_color_error(settings[k], c));
        if (worst <= max_de) {
            *measured = worst;
            return settings[k];
        }
        if (worst < best) best = worst;
    }
    *measured = best;
    return -1;
}
