/* --spectral N on the GPU (spectral_render.h). */
#include "app/runs/spectral_render.h"
#include "app/quality/quality.h"
#include "app/runs/stop.h"
#include "app/runs/tiles.h"
#include "app/runs/sequence_frames.h"
#include "app/scene/light.h"
#include "io/half_float.h"
#include "model/spectrum.h"
#include "reference/metrics.h"
#include "reference/spectral.h"
#include "sky/submit.h"
#include "sky/view_params.h"
#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

static struct {
    int wavelengths;
    bool medium_set;
    spectral_medium medium;
    sequence_render_fn inner;
    bool display;   /* a PNG among the outputs: the sum tone-mapped on the host (spectral_render_tonemap) */
    bool quiet;     /* or a sequence: no auto exposure line per frame, as the GPU meter's */
} job;

static bool ends_with(const char *s, const char *tail);

/* Whether any output is a PNG (the only other format --render writes). */
static bool wants_display(const options *o)
{
    for (int i = 0; i < o->output_count; ++i)
        if (!ends_with(o->outputs[i], ".exr")) return true;
    return false;
}

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
    const char *why = spectral_render_unable(o);
    if (why) {
        fprintf(stderr, "vksky: %s: %s\n", flag, why);
        return 2;
    }
    return 0;
}

const char *spectral_render_unable(const options *o)
{
    if (o->output_count == 0 || o->bench_frames > 0)
        return "on the GPU only with --render FILE (.exr or .png; not the window, not --bench)";
    /* A PNG is the sum tone-mapped on the host (spectral_render_tonemap), which knows a perspective frame's pixels
     * only; an environment map or a banded image writes its bands as they come, before a whole image exists. */
    if (wants_display(o) && tiles_wanted(o))
        return "a .png environment map or banded image: its tone map needs the whole image (write .exr, or one band "
               "of a perspective frame)";
    /* An .exr map or image, in one band or several, goes through include/vksky.h (app/runs/spectral_host.c; several
     * bands through tiles.c's tiles_render_drawn). A sequence draws whole frames: not one in several bands. */
    if (tiles_in_bands(o) && sequence_active(o))
        return "a sequence of images in several bands (over the band budget, VKSKY_TILE_PIXELS / VKSKY_TILE_ROWS): a "
               "spectral sequence draws whole frames (render each frame alone, or RGB)";
    return NULL;
}

void spectral_render_begin(const options *o, sequence_render_fn inner)
{
    job.wavelengths = o->spectral;
    job.medium_set = o->spectral_medium_set;
    job.medium = o->spectral_medium;
    job.inner = inner;
    job.display = wants_display(o);
    job.quiet = o->quiet || sequence_active(o);
}

void spectral_render_plain(sky_renderer *r, const frame_desc *f) { sky_renderer_render(r, f); }

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

bool spectral_render_four_wide(const options *o)
{
    const char *pack = getenv("VKSKY_SPECTRAL_PACK");
    if (o->spectral <= 0 || (pack && !strcmp(pack, "3"))) return false;
    if (o->view.projection != VKSKY_PROJECTION_PERSPECTIVE) return false;   /* a map: the horizon is in it */
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
    /* XYZ -> linear Rec.709 (D65), back into the linear readback the EXR writer takes; alpha: the composite's with
     * three to a pass, 1 with four (the four-wide readback's alpha is the last group's fourth wavelength). The sum
     * is float; the readback is half, in the HDR image's units (light_scale, app/scene/light.h), which keep the
     * sun's disc under half of half's range in every group and so in their sum (its colour is the sun's). */
    float *rgb = job.display ? malloc(pixels * 4 * sizeof *rgb) : NULL;
    for (size_t i = 0; i < pixels; ++i) {
        double in[3] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, out[3];
        spectrum_xyz_to_rec709(in, out);
        for (int k = 0; k < 3; ++k) {
            /* Out of Rec.709's gamut stays negative, as the reference writes it; half's range bounds it. */
            double v = out[k] < -65504.0 ? -65504.0 : out[k] > 65504.0 ? 65504.0 : out[k];
            px[4 * i + k] = io_float_to_half((float)v);
            if (rgb) rgb[4 * i + k] = (float)out[k];
        }
        if (width == 4) px[4 * i + 3] = io_float_to_half(1.0f);
        if (rgb) rgb[4 * i + 3] = 1.0f;
    }
    free(xyz);
    if (job.display) {
        if (!rgb) {
            fprintf(stderr, "vksky: --spectral: out of memory\n");
            exit(1);
        }
        spectral_render_tonemap(r, f->view, rgb, r->readback_display.mapped);
        free(rgb);
    }
    sky_renderer_set_scene(r, &base, sun_radius, &base_features);
}

/* The spectral sum's PNG: tone-mapped on the host, where the sum is (the GPU's tone map saw one group at a time).
 * The same law as the GPU's (metrics_tonemap_srgb8: shaders/glsl/tonemap_ops.glsl's operators and sRGB encode) at
 * the view's exposure; auto exposure as the GPU's meter computes it (sky/meter.c: the log-average of the luminance
 * in cd/m2 floored at 1e-4, over the sky's pixels only when the ground is black). No bloom (the spectral path has
 * none) and no dither (the GPU's +-1 LSB triangular noise). */
void spectral_render_tonemap(const sky_renderer *r, const sky_view *v, const float *rgb, void *display)
{
    spectral_render_tonemap_image(v, (int)r->desc.width, (int)r->desc.height, r->variant.ground,
                                  r->medium.bottom_radius, rgb, display);
}

void spectral_render_tonemap_image(const sky_view *v, int w, int h, bool every_pixel, double bottom_radius,
                                   const float *rgb, void *display)
{
    double scale = v->ev100 ? v->light_scale : 1.0, ev = v->exposure_ev;
    if (v->auto_exposure) {
        double f[3], right[3], up[3], log_sum = 0.0, count = 0.0;
        sky_view_basis(v, f, right, up);
        double ty = tan(0.5 * v->fov_deg * 3.14159265358979323846 / 180.0), tx = ty * w / h;
        double sin_h = sky_view_horizon_sine(v->altitude_km, bottom_radius);
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) {
                double x = 2.0 * (i + 0.5) / w - 1.0, y = 1.0 - 2.0 * (j + 0.5) / h, d[3];
                for (int k = 0; k < 3; ++k) d[k] = f[k] + x * tx * right[k] + y * ty * up[k];
                if (!every_pixel && d[1] / sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) < sin_h) continue;
                const float *p = rgb + 4 * ((size_t)j * w + i);
                double lum = (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / scale;
                log_sum += log(fmax(lum, 1e-4)), count += 1.0;
            }
        double average = count > 0.0 ? exp(log_sum / count) : 1e-4;
        sky_view exposed = *v;
        light_expose(&exposed, average);
        ev = exposed.exposure_ev;
        if (!job.quiet)
            fprintf(stderr, "vksky: auto exposure: EV100 %.4f (log-average luminance %.6g %s over %.0f pixels, metered "
                            "on the host: the spectral sum)\n", light_auto_ev100(average), average,
                    v->ev100 ? "cd/m2" : "(relative units)", count);
    }
    /* The tone map's multiplier (sky/view_params.c): photometric 1 / (light_scale 1.2 2^EV100), else 2^EV. */
    double multiplier = v->ev100 ? 1.0 / (v->light_scale * 1.2 * exp2(ev)) : exp2(ev);
    metrics_tonemap_srgb8(rgb, w, h, log2(multiplier), v->tonemap, display);
}

/* The scene classes of the run: a sequence's every frame (all of them, whatever --frame-range renders, so that a
 * split sequence picks what the whole does: sequence_choose_quality's rule), else the view's. */
static unsigned run_classes(const options *o)
{
    if (!sequence_active(o)) return o->quality_classes;
    unsigned classes = 0;
    int count = o->frame_count > 0 ? o->frame_count : 1, bad = 0;
    /* A bad frame is refused later by sequence_check, with its one line: not printed here a first time. */
    fflush(stderr);
    int saved = dup(STDERR_FILENO), null = open("/dev/null", O_WRONLY);
    if (saved >= 0 && null >= 0) dup2(null, STDERR_FILENO);
    for (int i = 0; i < count && !bad; ++i) {
        options f;
        bad = sequence_frame_options(o, i, &f);
        if (!bad) classes |= quality_class_bit(f.view.altitude_km, f.view.sun_elevation_deg);
    }
    fflush(stderr);
    if (saved >= 0 && null >= 0) dup2(saved, STDERR_FILENO);
    if (saved >= 0) close(saved);
    if (null >= 0) close(null);
    return bad ? 0 : classes;
}

int spectral_auto(options *o, const char *impossible)
{
    if (!o->quality_auto || o->spectral || o->max_color_error > 0.0 || o->reference) return 0;
    for (int i = 1; i < o->argc; ++i)   /* --spectral 0 given: RGB asked for */
        if (!strcmp(o->argv[i], "--spectral") || !strncmp(o->argv[i], "--spectral=", 11)) return 0;
    /* The window is interactive: it stays RGB (a spectral frame is a pass per group of four wavelengths). */
    if (o->output_count == 0 && o->bench_frames == 0) return 0;
    /* A sequence gets one choice for the run, from the worst of its frames' classes: its frames share one colour
     * setting as they share one quality preset (no jump in colour from one frame to the next). */
    unsigned classes = run_classes(o);
    double rgb = 0.0, measured;
    for (int c = 0; c < QUALITY_SCENE_COUNT; ++c)
        if (classes & (1u << c)) rgb = fmax(rgb, quality_color_error(0, c));
    /* Noon and afternoon (RGB within 2.4) stay RGB: their colour is off by less than the keep threshold, and the
     * fewest wavelengths within the budget there (8) would double the frame's cost for it. */
    if (rgb <= SPECTRAL_AUTO_RGB_KEEP) return 0;
    char names[96];
    quality_class_names(classes, names, sizeof names);
    /* A sequence keeps RGB under auto: a spectral frame is a pass per wavelength group. With the sum on the encode
     * threads and the write beside the next frame (app/runs/spectral_host.c), a 720p sunset sequence of 24 wavelengths
     * ran at 22-28 frames/s on an H100 against 45-48 in RGB; with the groups summed on the GPU (32j, one readback a
     * frame) a 960x540 frame still costs ~4x an RGB frame's CPU on lavapipe (0.52 s against 0.12: the groups' passes),
     * so issue 27's throughput stays the default's until the H100's figure (tools/throughput_bench.sh SPECTRAL=1)
     * says otherwise (docs/spectral.md, "The sum on the GPU"). --spectral N asks for it. */
    const char *why = impossible               ? impossible
                      : o->bench_frames > 0    ? "--bench (it times RGB frames)"
                      : sequence_active(o)     ? "a sequence at a sequence's speed (a frame would take a pass per "
                                                 "wavelength group, summed on the GPU: ~4x an RGB frame's CPU on "
                                                 "lavapipe; ask with --spectral N)"
                                               : spectral_render_unable(o);
    if (why) {   /* RGB kept where the spectral path cannot render: said, not silent */
        printf("vksky: --quality auto: RGB's colour on the '%s' scene is within CIEDE2000 %.2f of the spectrum's, "
               "over %g, but this run stays RGB: the spectral path cannot render %s\n", names, rgb,
               SPECTRAL_AUTO_RGB_KEEP, why);
        return 0;
    }
    int n = spectral_pick(SPECTRAL_AUTO_BUDGET, classes, &measured);
    if (n <= 0) return 0;
    o->spectral = n;
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
