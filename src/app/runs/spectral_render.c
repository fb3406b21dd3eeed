/* --spectral N on the GPU (spectral_render.h). */
#include "app/runs/spectral_render.h"
#include "app/cli/bad_value.h"
#include "app/quality/quality.h"
#include "app/runs/stop.h"
#include "app/runs/tiles.h"
#include "app/runs/sequence_frames.h"
#include "app/scene/light.h"
#include "io/parts.h"
#include "reference/metrics.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

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
    /* A map or image, .exr or .png, in one band or several, goes through include/vksky.h (app/runs/spectral_host.c;
     * several bands through tiles.c's tiles_render_drawn). A PNG is the sum tone-mapped on the host, per pixel; its
     * exposure is given or metered on the host over the whole image (in bands: a first pass over the bands that
     * writes nothing, as the RGB banded meter's). A sequence draws whole frames: not one in several bands. */
    if (tiles_in_bands(o) && sequence_active(o))
        return "a sequence of images in several bands (over the band budget, VKSKY_TILE_PIXELS / VKSKY_TILE_ROWS): a "
               "spectral sequence draws whole frames (render each frame alone, or RGB)";
    return NULL;
}

/* Whether the horizon passes within HORIZON_MARGIN pixels of any pixel of the (perspective) frame: the sign of each
 * pixel centre's elevation sine against the horizon's, over the image grown by the margin on every side. */
#define HORIZON_MARGIN 3
static bool horizon_in_view(const options *o)
{
    view_rays rays = light_view_rays(&o->view, o->width, o->height);
    const double *f = rays.forward, *right = rays.right, *up = rays.up, tx = rays.tx, ty = rays.ty;
    double sin_h = light_horizon_sine(o->view.altitude_km, o->atmosphere.bottom_radius);
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
    /* The four-wide image has no horizon resolve (its alpha is a wavelength) and no bloom (its composite is the sky
     * texel): a frame with the horizon in it keeps three to a pass, whose tone map anti-aliases the horizon per pixel
     * (issue 26), and so does a frame with bloom, whose groups' composites carry it as an RGB frame's does. */
    return !o->view.bloom && !horizon_in_view(o);
}

/* The spectral sum's PNG: tone-mapped on the host, where the sum is (the GPU's tone map saw one group at a time).
 * The same law as the GPU's (metrics_tonemap_srgb8: shaders/glsl/tonemap_ops.glsl's operators and sRGB encode) at
 * the view's exposure; auto exposure as the GPU's meter computes it (sky/meter.c: the log-average of the luminance
 * in cd/m2 floored at 1e-4, over the sky's pixels only when the ground is black; a fisheye's pixels outside its circle
 * not counted); the GPU's dither (+-1 LSB triangular noise, its law: metrics_tonemap_srgb8_dithered). Bloom: what the
 * groups' composites carry (each group's HDR image plus its bloom, as an RGB frame's EXR: a frame with bloom is three
 * to a pass); the meter reads the groups' bloom-free frames, as the GPU's meter reads the HDR image before bloom
 * (app/runs/spectral_host.c). */
void spectral_render_meter_rows(const sky_view *v, int w, int whole_h, int first_row, int rows, bool every_pixel,
                                double bottom_radius, const float *rgb, spectral_meter *m)
{
    double scale = v->ev100 ? v->light_scale : 1.0;
    view_rays rays = light_view_rays(v, w, whole_h);
    const double *f = rays.forward, *right = rays.right, *up = rays.up, tx = rays.tx, ty = rays.ty;
    double sin_h = light_horizon_sine(v->altitude_km, bottom_radius);
    bool map = v->projection != VKSKY_PROJECTION_TYPE_PERSPECTIVE;
    /* Rows in order, pixels in order, one double sum: the whole image's sum, whether it comes in one band or many. */
    for (int r = 0; r < rows; ++r)
        for (int i = 0; i < w; ++i) {
            int j = first_row + r;
            double d[3];
            if (!map) {
                double x = 2.0 * (i + 0.5) / w - 1.0, y = 1.0 - 2.0 * (j + 0.5) / whole_h;
                for (int k = 0; k < 3; ++k) d[k] = f[k] + x * tx * right[k] + y * ty * up[k];
            } else if (!light_map_dir(v->projection, w, whole_h, i + 0.5, j + 0.5, d)) {
                continue;   /* outside a fisheye's circle: no direction, written black, no part of the scene */
            }
            if (!every_pixel && d[1] / sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) < sin_h) continue;
            const float *p = rgb + 4 * ((size_t)r * w + i);
            double lum = (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / scale;
            m->log_sum += log(fmax(lum, 1e-4)), m->count += 1.0;
        }
}

double spectral_render_exposure(const sky_view *v, const spectral_meter *m, int bands, bool quiet)
{
    if (!v->auto_exposure) return v->exposure_ev;
    double average = m->count > 0.0 ? exp(m->log_sum / m->count) : 1e-4;
    sky_view exposed = *v;
    light_expose(&exposed, average);
    if (!quiet)
        fprintf(stderr, "vksky: auto exposure: EV100 %.4f (log-average luminance %.6g %s over %.0f pixels, metered "
                        "on the host: the spectral sum%s)\n", light_auto_ev100(average), average,
                v->ev100 ? "cd/m2" : "(relative units)", m->count, bands > 1 ? " in bands" : "");
    return exposed.exposure_ev;
}

typedef struct tonemap_job {
    const sky_view *v;
    double ev;   /* log2 of the multiplier */
    int w, first_row;
    const float *rgb;
    unsigned char *display;
} tonemap_job;

static void tonemap_part(void *user, size_t part, size_t begin, size_t end)
{
    (void)part;
    const tonemap_job *j = user;
    size_t at = begin * (size_t)j->w;
    metrics_tonemap_srgb8_dithered(j->rgb + 4 * at, j->w, (int)(end - begin), j->ev, j->v->tonemap, !j->v->no_dither, 0,
                                   j->first_row + (int)begin, j->display + 4 * at);
}

void spectral_render_tonemap_rows(const sky_view *v, double exposure_ev, int w, int rows, int first_row,
                                  const float *rgb, void *display)
{
    /* The tone map's multiplier (sky/view_params.c): photometric 1 / (light_scale 1.2 2^EV100), else 2^EV. The
     * dither seeded by the whole image's pixel positions, as the GPU's (TonemapPush.dither: the band's offset). Rows
     * over the encode threads (--threads): every pixel's arithmetic is its own, so the bytes are the one loop's (a
     * 1080p PNG's tone map was ~70 ms of one core on the H200 host). */
    double multiplier = v->ev100 ? 1.0 / (v->light_scale * 1.2 * exp2(exposure_ev)) : exp2(exposure_ev);
    tonemap_job job = {v, log2(multiplier), w, first_row, rgb, display};
    size_t min_rows = (size_t)(65536 / (w > 0 ? w : 1)) + 1;   /* parts of at least 64 Ki pixels */
    io_parts_run((size_t)rows, min_rows, tonemap_part, &job);
}

/* The scene classes of the run: a sequence's every frame (all of them, whatever --frame-range renders, so that a
 * split sequence picks what the whole does: sequence_choose_quality's rule), else the view's. */
static unsigned run_classes(const options *o)
{
    if (!sequence_active(o)) return o->quality_classes;
    unsigned classes = 0;
    int count = o->frame_count > 0 ? o->frame_count : 1, bad = 0;
    /* A bad frame is refused later by sequence_check, with its one line: not printed here a first time. The frames'
     * lines go to this thread's report stream (app/cli/bad_value.h), pointed at nothing for the loop, not the
     * process's stderr. */
    FILE *null = fopen("/dev/null", "w");
    if (null) options_report_to(null);
    for (int i = 0; i < count && !bad; ++i) {
        options f;
        bad = sequence_frame_options(o, i, &f);
        if (!bad) classes |= quality_class_bit(f.view.altitude_km, f.view.sun_elevation_deg);
    }
    if (null) options_report_to(NULL), fclose(null);
    return bad ? 0 : classes;
}

int spectral_auto(options *o, const char *impossible)
{
    if (!o->quality_auto || o->spectral || o->max_color_error > 0.0 || o->reference) return 0;
    for (int i = 1; i < o->argc; ++i)   /* --spectral 0 given: RGB asked for */
        if (!strcmp(o->argv[i], "--spectral") || !strncmp(o->argv[i], "--spectral=", 11)) return 0;
    /* A sequence gets one choice for the run, from the worst of its frames' classes: its frames share one colour
     * setting as they share one quality preset (no jump in colour from one frame to the next). */
    unsigned classes = run_classes(o);
    double rgb = 0.0, measured;
    for (int c = 0; c < QUALITY_SCENE_COUNT; ++c)
        if (classes & (1u << c)) rgb = fmax(rgb, quality_color_error(0, c));
    /* RGB kept where its colour is within the budget; on a CPU device also at noon and in the afternoon (RGB within
     * 2.4, under SPECTRAL_AUTO_RGB_KEEP_CPU), where 8 or 16 wavelengths cost a 1080p still 2.0-3.4x RGB's time. */
    double keep = o->quality_cpu_device ? SPECTRAL_AUTO_RGB_KEEP_CPU : SPECTRAL_AUTO_BUDGET;
    if (rgb <= keep) return 0;
    char names[96];
    quality_class_names(classes, names, sizeof names);
    /* A sequence keeps RGB under auto: a spectral frame is a pass per wavelength group. With the sum on the encode
     * threads and the write beside the next frame (app/runs/spectral_host.c), a 720p sunset sequence of 24 wavelengths
     * ran at 22-28 frames/s on an H100 against 45-48 in RGB; with the groups summed on the GPU (32j, one readback a
     * frame) a 960x540 frame still costs ~4x an RGB frame's CPU on lavapipe (0.52 s against 0.12: the groups' passes),
     * so issue 27's throughput stays the default's until the H100's figure (tools/throughput_bench.sh SPECTRAL=1)
     * says otherwise (docs/spectral.md, "The sum on the GPU"). --spectral N asks for it. */
    bool window = o->output_count == 0 && o->bench_frames == 0;
    const char *why = impossible               ? impossible
                      : window                 ? "the interactive window (a frame would take a pass per group of "
                                                 "four wavelengths)"
                      : o->bench_frames > 0    ? "--bench (it times RGB frames)"
                      : sequence_active(o)     ? "a sequence at a sequence's speed (a frame would take a pass per "
                                                 "wavelength group, summed on the GPU: ~4x an RGB frame's CPU on "
                                                 "lavapipe; ask with --spectral N)"
                                               : spectral_render_unable(o);
    if (why) {   /* RGB kept where the spectral path cannot render: said, not silent */
        printf("vksky: --quality auto: RGB's colour on the '%s' scene is within CIEDE2000 %.2f of the spectrum's, "
               "over %g, but this run stays RGB: the spectral path cannot render %s\n", names, rgb, keep, why);
        return 0;
    }
    int n = spectral_pick(SPECTRAL_AUTO_BUDGET, classes, &measured);
    if (n <= 0) return 0;
    o->spectral = n;
    printf("vksky: --quality auto: RGB's colour on the '%s' scene is within CIEDE2000 %.2f of the spectrum's, over %g: "
           "picked --spectral %d (measured worst CIEDE2000 %.2f, budget %g; --spectral 0 keeps RGB)\n",
           names, rgb, keep, n, measured, SPECTRAL_AUTO_BUDGET);
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
