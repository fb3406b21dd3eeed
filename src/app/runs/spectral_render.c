/* --spectral N on the GPU (spectral_render.h). */
#include "app/runs/spectral_render.h"
#include "app/quality/quality.h"
#include "app/runs/stop.h"
#include "app/runs/tiles.h"
#include "io/half_float.h"
#include "model/spectrum.h"
#include "reference/spectral.h"
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

/* The ground's albedo at the group's wavelengths: the RGB law (680, 550, 440 nm, linear between), as the spectral
 * reference's irradiance takes it. */
static void group_albedo(const sky_features *base, const double nm[3], double out[3])
{
    spectral_law law = {.kind = SPECTRAL_LAW_RGB};
    memcpy(law.rgb, base->ground_albedo, sizeof law.rgb);
    for (int c = 0; c < 3; ++c) out[c] = spectral_law_eval(&law, nm[c]);
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
    int n = job.wavelengths, groups = (n + 2) / 3;
    uint16_t *px = r->readback_linear.mapped;
    for (int g = 0; g < groups && !stop_requested(); ++g) {
        model_atmosphere a;
        int idx[3];
        int real = ref_spectral_group(&s, g, &a, idx);
        double nm[3], m[3][3];   /* m[c]: channel c's XYZ per unit of the group's image */
        for (int c = 0; c < 3; ++c) {
            nm[c] = ref_spectral_nm(n, idx[c]);
            a.sun_illuminance[c] = sun_y;
            ref_spectral_weights(n, idx[c], m[c]);
            for (int k = 0; k < 3; ++k) m[c][k] = c < real ? m[c][k] / toa : 0.0;
        }
        sky_features feat = base_features;
        group_albedo(&base_features, nm, feat.ground_albedo);
        sky_renderer_set_scene(r, &a, sun_radius, &feat);
        job.inner(r, f);
        for (size_t i = 0; i < pixels; ++i) {
            const uint16_t *p = px + 4 * i;
            float v[3] = {io_half_to_float(p[0]), io_half_to_float(p[1]), io_half_to_float(p[2])};
            for (int k = 0; k < 3; ++k)
                xyz[3 * i + k] += (float)(m[0][k] * v[0] + m[1][k] * v[1] + m[2][k] * v[2]);
        }
    }
    /* XYZ -> linear Rec.709 (D65), back into the linear readback the EXR writer takes (alpha as rendered). */
    for (size_t i = 0; i < pixels; ++i) {
        double in[3] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, rgb[3];
        spectrum_xyz_to_rec709(in, rgb);
        for (int k = 0; k < 3; ++k) {
            /* Out of Rec.709's gamut stays negative, as the reference writes it; half's range bounds it. */
            double v = rgb[k] < -65504.0 ? -65504.0 : rgb[k] > 65504.0 ? 65504.0 : rgb[k];
            px[4 * i + k] = io_float_to_half((float)v);
        }
    }
    free(xyz);
    sky_renderer_set_scene(r, &base, sun_radius, &base_features);
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
