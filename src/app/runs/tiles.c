/* Band rendering and streaming (see tiles.h). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "app/runs/tiles.h"
#include "app/runs/tiles_out.h"
#include "app/scene/render_values.h"
#include "app/runs/exr_header.h"
#include "app/runs/frame_ring.h"
#include "app/scene/light.h"
#include "app/runs/stop.h"
#include "app/runs/stage_times.h"
#include "io/encode_settings.h"
#include "app/cli/options.h"
#include "app/cli/options_projection.h"
#include "app/runs/progress.h"
#include "io/exr_stream.h"
#include "io/png_stream.h"
#include "sky/meter.h"
#include "sky/projection.h"
#include "sky/submit.h"
#include <math.h>
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
    /* VKSKY_TILE_ROWS=N (tests): bands of exactly N rows, whatever the budget (tests/band_rows_test.sh). */
    const char *exact = getenv("VKSKY_TILE_ROWS");
    if (exact && atoi(exact) > 0) return atoi(exact) >= height ? height : atoi(exact);
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

bool tiles_in_bands(const options *o)
{
    return tiles_wanted(o) && tiles_band_rows(o->width, o->height, tiles_budget()) < o->height;
}

/* What writing a band needs: the outputs and the progress line. */
typedef struct bands_state {
    const options *o;
    output *outs;
    progress *prog;
    int stopped_line;   /* a stop ended the line of a terminal's progress */
    float *band_f32;    /* a band in output units (write_exr_rows), reused; only the writing thread touches it */
    size_t band_cap;    /* its size in pixels */
    int pad;            /* rows rendered above (and below) each band: the tone map's horizon taps (band_pad) */
    tiles_frame_fn frame;   /* a band's frame (NULL: sky_renderer_render) */
} bands_state;

/* A banded render draws each band with one more row above and below it (the image's own edges excepted: the tone
 * map clamps its taps there, view.whole_height), so the tone map's horizon coverage (hdr_upsample.glsl), which
 * reads a pixel's neighbours, sees the same neighbours as in one whole image: no seam at a band's edge. The band's
 * own rows start `pad` rows into what was read back. */
static frame_ring_pixels band_rows(const bands_state *st, const frame_ring_pixels *px)
{
    size_t skip = (size_t)st->pad * (size_t)st->o->width * 4;
    return (frame_ring_pixels){px->linear + skip, px->display + skip};
}

/* A band's rows (y .. y + rows) into every output, in order. 0, or 1 with the message printed. */
static int write_band(bands_state *st, const frame_ring_pixels *rendered, int y, int rows)
{
    char err[512];
    frame_ring_pixels own = band_rows(st, rendered);
    const frame_ring_pixels *px = &own;
    for (int i = 0; i < st->o->output_count; ++i) {
        output *out = &st->outs[i];
        stage_mark t0 = stage_mark_now();
        int rc = out->exr ? write_exr_rows(st->o, out->exr_stream, px->linear, rows, &st->band_f32, &st->band_cap, err,
                                           sizeof err)
                          : io_png_stream_rows(out->png_stream, px->display, rows, err, sizeof err);
        if (!out->exr) stage_add_since(STAGE_WRITE, t0);
        if (rc != 0) {
            *out = (output){0};   /* the stream aborted itself */
            fprintf(stderr, "vksky: %s\n", err);
            return 1;
        }
    }
    progress_update(st->prog, y + rows);
    /* Ctrl-C or a TERM (app/runs/stop.c): the band loop stops at the next band and removes the partial files; the
     * caller's stop_status says so and exits 130 / 143. */
    if (stop_requested()) {
        if (st->prog->terminal && !st->stopped_line++) fputc('\n', stderr);
        return 1;
    }
    return 0;
}

static int bands_serial(bands_state *st, sky_renderer *r, sky_view *view, int band)
{
    int height = st->o->height, status = 0;
    for (int y = 0; y < height && status == 0; y += band) {
        view->tile_x = 0, view->tile_y = y - st->pad;
        frame_desc f = {.view = view};
        if (st->frame) st->frame(r, &f);   /* --spectral: a pass per wavelength group, summed (EXR only) */
        else sky_renderer_render(r, &f);
        frame_ring_pixels px = {r->readback_linear.mapped, r->readback_display.mapped};
        status = write_band(st, &px, y, height - y < band ? height - y : band);
    }
    return status;
}

typedef struct band_job {
    int y, rows;
} band_job;

/* frame_ring_consume_fn: a band's rows, on the ring's thread, in band order. */
static int consume_band(void *user, const frame_ring_pixels *px, void *job)
{
    const band_job *j = job;
    return write_band(user, px, j->y, j->rows);
}

static int bands_ring(bands_state *st, sky_renderer *r, sky_view *view, int band, int slots)
{
    frame_ring ring;
    /* One consumer: a band's rows go into streams that take them in order. */
    if (frame_ring_create(&ring, r, slots, 1, consume_band, NULL, st, st->o->trace_barriers ? stdout : NULL)) return 1;
    int height = st->o->height, status = 0;
    for (int y = 0; y < height && status == 0 && !stop_requested(); y += band) {
        band_job *j = malloc(sizeof *j);
        if (!j) {
            status = 1;
            break;
        }
        stage_mark t0 = stage_mark_now();
        *j = (band_job){y, height - y < band ? height - y : band};
        /* The band's offset is a push constant, recorded into this band's command buffer. */
        view->tile_x = 0, view->tile_y = y - st->pad;
        frame_desc f = {.view = view};
        status = frame_ring_submit(&ring, &f, j);
        stage_add_since(STAGE_PRODUCE, t0);
    }
    int consumed = frame_ring_finish(&ring);
    if (status == 0) status = consumed;
    return status || stop_requested() ? 1 : 0;
}

/* Auto exposure of a banded image, metered on the GPU (sky/meter.h): a first pass over the bands that writes nothing,
 * each band's frame metering only its own rows (not the rows it shares with its neighbours); the host adds the bands'
 * sums of logs (count ln L per band), so the log-average is the whole image's, as one frame's meter would count it. */
static double tiles_auto_exposure(const bands_state *st, sky_renderer *r, sky_view *view, int band, int height)
{
    sky_view v = *view;
    v.auto_exposure = true, v.auto_exposure_ease = 0.0;
    double log_sum = 0.0, count = 0.0;
    for (int y = 0; y < height && !stop_requested(); y += band) {
        v.tile_x = 0, v.tile_y = y - st->pad;
        int rows = height - y < band ? height - y : band;
        frame_desc f = {.view = &v, .meter_first_row = (uint32_t)st->pad, .meter_rows = (uint32_t)rows};
        sky_renderer_render(r, &f);
        meter_result m = meter_read(r->ctx, &r->meter, 0);
        if (m.count > 0.0f) log_sum += (double)m.count * log((double)m.log_average), count += m.count;
    }
    v = *view;
    light_expose(&v, count > 0.0 ? exp(log_sum / count) : 1e-4);
    if (!st->o->quiet)
        fprintf(stderr, "vksky: auto exposure: EV100 %.4f (log-average luminance %.6g %s over %.0f pixels, metered on "
                        "the GPU in %d band%s)\n", light_auto_ev100(count > 0.0 ? exp(log_sum / count) : 1e-4),
                count > 0.0 ? exp(log_sum / count) : 1e-4, v.ev100 ? "cd/m2" : "(relative units)", count,
                (height + band - 1) / band, band < height ? "s" : "");
    return v.exposure_ev;
}

int tiles_render(const options *o, gpu_context *ctx) { return tiles_render_with(o, ctx, NULL); }

int tiles_render_with(const options *o, gpu_context *ctx, tiles_frame_fn frame)
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
    tiles_note_render_scale(o);
    view.whole_width = width, view.whole_height = height;
    /* Pipelined (app/runs/frame_ring.h): band k+1 renders while band k is written. The bands keep their height (a
     * cube or perspective band's pixels depend on it by up to an fp16 ulp, and the files must equal the serial
     * loop's); each slot past the first adds one band's readback buffers (12 bytes a pixel). */
    int slots = bands > 1 && !frame ? frame_ring_slots_wanted() : 0;   /* a frame of the caller's: the serial loop */

    output outs[OPTIONS_MAX_OUTPUTS] = {0};
    if (open_outputs(o, outs) != 0) {
        abort_outputs(o, outs);
        return 1;
    }
    sky_renderer r;
    render_scene scene;
    render_scene_of(o, &scene);
    render_quality quality = render_quality_of(o);
    quality.render_scale = 1.0;   /* bands are drawn at full size (a band's rows are its own) */
    int pad = bands > 1 ? 1 : 0;   /* band_rows */
    sky_renderer_desc rdesc = render_desc(&quality, &scene);
    rdesc.width = (uint32_t)width, rdesc.height = (uint32_t)(band + 2 * pad), rdesc.bloom = view.bloom;
    rdesc.readback = true, rdesc.display_format = VK_FORMAT_R8G8B8A8_SRGB;
    sky_renderer_create(&r, ctx, &rdesc);
    if (o->trace_passes) gpu_barrier_trace_passes(stdout);

    char what[300];
    snprintf(what, sizeof what, "rendering %s (%dx%d, %d bands)", o->output_count ? o->outputs[0] : "", width, height, bands);
    progress prog;
    progress_begin(&prog, stderr, o->quiet || bands < 2, what, height);
    bands_state st = {o, outs, &prog, 0, NULL, 0, pad, frame};
    if (light_auto_exposure_wanted(o)) view.exposure_ev = tiles_auto_exposure(&st, &r, &view, band, height);
    stage_begin();
    int status = slots >= 2 ? bands_ring(&st, &r, &view, band, slots) : bands_serial(&st, &r, &view, band);
    char err[512];
    stage_mark t0 = stage_mark_now();
    for (int i = 0; i < o->output_count && status == 0; ++i) {
        int rc = outs[i].exr ? io_exr_stream_finish(outs[i].exr_stream, err, sizeof err)
                             : io_png_stream_finish(outs[i].png_stream, err, sizeof err);
        outs[i] = (output){0};
        if (rc != 0) fprintf(stderr, "vksky: %s\n", err), status = 1;
    }
    stage_add_since(STAGE_WRITE, t0);
    if (o->timings && status == 0) stage_report(stderr, "banded render", bands, "band", 1, io_encode_threads_all());
    if (status == 0) progress_end(&prog);
    free(st.band_f32);
    abort_outputs(o, outs);
    sky_renderer_destroy(&r);
    return status;
}
