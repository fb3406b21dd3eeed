/* Band rendering and streaming (see tiles.h). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "app/tiles.h"
#include "app/stop.h"
#include "app/options.h"
#include "app/options_projection.h"
#include "app/progress.h"
#include "io/exr_stream.h"
#include "io/png_stream.h"
#include "sky/projection.h"
#include "sky/submit.h"
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* Vulkan guarantees 4096; every device vksky runs on has 16384 (lavapipe, NVIDIA, AMD, Intel). */
#define TILES_MAX_ROWS 16384

long tiles_budget(void)
{
    const char *env = getenv("VKSKY_TILE_PIXELS");
    long v = env ? atol(env) : 0;
    return v > 0 ? v : 8L << 20;
}

int tiles_band_rows(int width, int height, long budget)
{
    long rows = budget / width;
    rows -= rows % 16;
    if (rows < 16) rows = 16;
    if (rows > TILES_MAX_ROWS) rows = TILES_MAX_ROWS;
    return rows >= height ? height : (int)rows;
}

bool tiles_wanted(const options *o)
{
    return o->view.projection != SKY_PROJECTION_PERSPECTIVE || (long)o->width * o->height > tiles_budget();
}

typedef struct output {
    bool exr;
    io_exr_stream *exr_stream;
    io_png_stream *png_stream;
} output;

static bool is_exr(const char *path)
{
    size_t n = strlen(path);
    return n > 4 && strcasecmp(path + n - 4, ".exr") == 0;
}

static int open_outputs(const options *o, output *outs)
{
    char err[512];
    double sun[3];
    projection_dir_from_angles(o->view.sun_azimuth_deg, o->view.sun_elevation_deg, sun);
    double at_camera[3];
    options_sun_at_camera(o, at_camera);
    int p = o->view.projection;
    io_exr_sky_attrs attrs = {
        .envmap = p == SKY_PROJECTION_EQUIRECT ? IO_ENVMAP_LATLONG : p == SKY_PROJECTION_CUBEMAP ? IO_ENVMAP_CUBE : IO_ENVMAP_NONE,
        .projection = options_projection_name(p), .has_sun = true,
        .sun_direction = {(float)sun[0], (float)sun[1], (float)sun[2]},
        .sun_illuminance = {(float)o->atmosphere.sun_illuminance[0], (float)o->atmosphere.sun_illuminance[1],
                            (float)o->atmosphere.sun_illuminance[2]},
        .sun_at_camera = {(float)at_camera[0], (float)at_camera[1], (float)at_camera[2]}};
    for (int i = 0; i < o->output_count; ++i) {
        outs[i].exr = is_exr(o->outputs[i]);
        if (outs[i].exr) outs[i].exr_stream = io_exr_stream_open(o->outputs[i], o->width, o->height, &attrs, err, sizeof err);
        else outs[i].png_stream = io_png_stream_open(o->outputs[i], o->width, o->height, err, sizeof err);
        if (!outs[i].exr_stream && !outs[i].png_stream) {
            fprintf(stderr, "vksky: %s\n", err);
            return 1;
        }
    }
    return 0;
}

static void abort_outputs(const options *o, output *outs)
{
    for (int i = 0; i < o->output_count; ++i) {
        io_exr_stream_abort(outs[i].exr_stream);
        io_png_stream_abort(outs[i].png_stream);
        outs[i] = (output){0};
    }
}

int tiles_render(const options *o, gpu_context *ctx)
{
    long budget = tiles_budget();
    int width = o->width, height = o->height;
    int band = tiles_band_rows(width, height, budget);
    int bands = (height + band - 1) / band;
    sky_view view = o->view;
    /* Bloom gathers light from a neighbourhood that crosses band borders: seamless only untiled, so a tiled render
     * leaves it out (and environment maps never have it: options_projection.c). */
    if (bands > 1 && view.bloom) {
        fprintf(stderr, "vksky: note: bloom is off in a render of %d bands (an image over VKSKY_TILE_PIXELS=%ld "
                        "pixels); render at most %ld pixels for bloom\n", bands, budget, budget);
        view.bloom = false;
    }
    bool scale_given = false;   /* a note for the user's --render-scale, not for a preset's (--quality auto's) */
    for (int i = 1; i < o->argc; ++i)
        if (!strncmp(o->argv[i], "--render-scale", 14) && (o->argv[i][14] == '\0' || o->argv[i][14] == '='))
            scale_given = true;
    if (o->render_scale != 1.0 && scale_given && !o->quiet)
        fprintf(stderr, "vksky: note: --render-scale %g ignored: banded renders are rendered at full size\n", o->render_scale);
    view.whole_width = width, view.whole_height = height;

    output outs[OPTIONS_MAX_OUTPUTS] = {0};
    if (open_outputs(o, outs) != 0) {
        abort_outputs(o, outs);
        return 1;
    }
    sky_renderer r;
    sky_features features = options_features(o);
    sky_renderer_desc rdesc = {.width = (uint32_t)width, .height = (uint32_t)band, .bloom = view.bloom,
                               .readback = true, .display_format = VK_FORMAT_R8G8B8A8_SRGB, .render_scale = 1.0,
                               .lut = o->lut, .bloom_mips = (uint32_t)o->bloom_mips, .atmosphere = &o->atmosphere,
                               .sun_angular_radius_rad = options_sun_radius_rad(o), .features = &features};
    sky_renderer_create(&r, ctx, &rdesc);
    if (o->trace_passes) r.pass_trace = stdout;

    char what[300];
    snprintf(what, sizeof what, "rendering %s (%dx%d, %d bands)", o->output_count ? o->outputs[0] : "", width, height, bands);
    progress prog;
    progress_begin(&prog, stderr, o->quiet || bands < 2, what, height);
    int status = 0;
    char err[512];
    for (int y = 0; y < height && status == 0; y += band) {
        view.tile_x = 0, view.tile_y = y;
        frame_desc f = {.view = &view};
        sky_renderer_render(&r, &f);
        int rows = height - y < band ? height - y : band;
        for (int i = 0; i < o->output_count && status == 0; ++i) {
            int rc = outs[i].exr ? io_exr_stream_rows(outs[i].exr_stream, r.readback_linear.mapped, rows, err, sizeof err)
                                 : io_png_stream_rows(outs[i].png_stream, r.readback_display.mapped, rows, err, sizeof err);
            if (rc != 0) {
                outs[i] = (output){0};   /* the stream aborted itself */
                fprintf(stderr, "vksky: %s\n", err);
                status = 1;
            }
        }
        progress_update(&prog, y + rows);
        /* Ctrl-C or a TERM (app/stop.c): the band loop stops at the next band and removes the partial files;
         * the caller's stop_status says so and exits 130 / 143. */
        if (stop_requested() && status == 0) {
            if (prog.terminal) fputc('\n', stderr);
            status = 1;
        }
    }
    for (int i = 0; i < o->output_count && status == 0; ++i) {
        int rc = outs[i].exr ? io_exr_stream_finish(outs[i].exr_stream, err, sizeof err)
                             : io_png_stream_finish(outs[i].png_stream, err, sizeof err);
        outs[i] = (output){0};
        if (rc != 0) fprintf(stderr, "vksky: %s\n", err), status = 1;
    }
    if (status == 0) progress_end(&prog);
    abort_outputs(o, outs);
    sky_renderer_destroy(&r);
    return status;
}
