/* Band rendering and streaming (see tiles.h), as a host of include/vksky.h: each band is a frame of one renderer
 * (vksky_frame_band: its first row in the whole image), recorded into the host's command buffers and read back
 * through the renderer's readback slots, band k+1 rendering while band k is written (app/runs/host_ring.h). No
 * src/sky or src/lib header (tests/layering_test.sh). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "app/runs/tiles.h"
#include "app/runs/tiles_out.h"
#include "app/runs/host_ring.h"
#include "app/scene/light.h"
#include "app/runs/stop.h"
#include "app/runs/stage_times.h"
#include "io/encode_settings.h"
#include "app/runs/progress.h"
#include "io/exr_stream.h"
#include "io/png_stream.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

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
    return o->view.projection != VKSKY_PROJECTION_TYPE_PERSPECTIVE || (long)o->width * o->height > tiles_budget();
}

bool tiles_in_bands(const options *o)
{
    return tiles_wanted(o) && tiles_band_rows(o->width, o->height, tiles_budget()) < o->height;
}

/* A banded render draws each band with one more row above and below it (the image's own edges excepted: the tone
 * map clamps its taps there, vksky_frame_band), so the tone map's horizon coverage (hdr_upsample.glsl), which reads a
 * pixel's neighbours, sees the same neighbours as in one whole image: no seam at a band's edge. The band's own rows
 * start `pad` rows into what was read back. */
int tiles_band_pad(const options *o) { return tiles_in_bands(o) ? 1 : 0; }

int tiles_frame_rows(const options *o)
{
    return tiles_band_rows(o->width, o->height, tiles_budget()) + 2 * tiles_band_pad(o);
}

void tiles_begin_notes(const options *o)
{
    long budget = tiles_budget();
    int band = tiles_band_rows(o->width, o->height, budget), bands = (o->height + band - 1) / band;
    /* Bloom gathers light from a neighbourhood that crosses band borders: seamless only untiled, so a tiled render
     * leaves it out (and environment maps never have it: options_projection.c). */
    if (bands > 1 && o->view.bloom)
        fprintf(stderr, "vksky: note: bloom is off in a render of %d bands (an image over VKSKY_TILE_PIXELS=%ld "
                        "pixels); render at most %ld pixels for bloom\n", bands, budget, budget);
    tiles_note_render_scale(o);
}

/* What writing a band needs: the outputs and the progress line. */
typedef struct bands_state {
    const options *o;
    output *outs;
    progress *prog;
    int stopped_line;   /* a stop ended the line of a terminal's progress */
    float *band_f32;    /* a band in output units (write_exr_rows), reused; only the writing thread touches it */
    size_t band_cap;    /* its size in pixels */
    int pad;            /* rows rendered above (and below) each band (tiles_band_pad) */
} bands_state;

/* A band's own rows: `pad` rows into what was read back. */
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

/* The band that starts at row y: the whole image's view and projection, the band's first row (its pad row above). */
static host_view band_view(const bands_state *st, const host_view *whole, int y)
{
    host_view v = *whole;
    v.band = true, v.first_row = y - st->pad;
    return v;
}

/* The RGB renderer's band (tiles_draw_fn): its frame, read back in slot 0. */
typedef struct renderer_draw {
    vksky_renderer *r;
    host_commands *h;
    FILE *trace;
} renderer_draw;

static int draw_renderer(void *user, const host_view *v, frame_ring_pixels *out)
{
    renderer_draw *d = user;
    vksky_readback px;
    if (host_commands_render(d->h, d->r, v, d->trace, NULL) ||
        vksky_renderer_get_readback_slot(d->r, 0, &px) != VKSKY_SUCCESS)
        return 1;
    *out = (frame_ring_pixels){px.linear_rgba16f, px.display_rgba8};
    return 0;
}

static int bands_serial(bands_state *st, tiles_draw_fn draw, void *user, const host_view *whole, int band)
{
    int height = st->o->height, status = 0;
    for (int y = 0; y < height && status == 0; y += band) {
        host_view v = band_view(st, whole, y);
        frame_ring_pixels pixels;
        if (draw(user, &v, &pixels)) return 1;
        status = write_band(st, &pixels, y, height - y < band ? height - y : band);
    }
    return status;
}

typedef struct band_job {
    int y, rows;
} band_job;

/* host_ring_consume_fn: a band's rows, on the ring's thread, in band order. */
static int consume_band(void *user, const frame_ring_pixels *px, void *job)
{
    const band_job *j = job;
    return write_band(user, px, j->y, j->rows);
}

static int bands_ring(bands_state *st, vksky_context *ctx, vksky_renderer *r, const host_view *whole, int band,
                      int slots, FILE *trace)
{
    host_ring ring;
    /* One consumer: a band's rows go into streams that take them in order. */
    if (host_ring_create(&ring, ctx, r, slots, 1, consume_band, NULL, st, trace)) return 1;
    int height = st->o->height, status = 0;
    for (int y = 0; y < height && status == 0 && !stop_requested(); y += band) {
        band_job *j = malloc(sizeof *j);
        if (!j) {
            status = 1;
            break;
        }
        stage_mark t0 = stage_mark_now();
        *j = (band_job){y, height - y < band ? height - y : band};
        /* The band's first row goes into this band's command buffer (a push constant). */
        host_view v = band_view(st, whole, y);
        status = host_ring_submit(&ring, &v, j);
        stage_add_since(STAGE_PRODUCE, t0);
    }
    int consumed = host_ring_finish(&ring);
    if (status == 0) status = consumed;
    return status || stop_requested() ? 1 : 0;
}

/* Auto exposure of a banded image, metered on the GPU (vksky_auto_exposure): a first pass over the bands that writes
 * nothing, each band's frame metering only its own rows (not the rows it shares with its neighbours); the host adds the
 * bands' sums of logs (count ln L per band), so the log-average is the whole image's, as one frame's meter would count
 * it. The exposure, or NAN (vksky's message printed). */
static double tiles_auto_exposure(const bands_state *st, vksky_renderer *r, host_commands *h, const host_view *whole,
                                  int band, FILE *trace)
{
    int height = st->o->height;
    double log_sum = 0.0, count = 0.0;
    for (int y = 0; y < height && !stop_requested(); y += band) {
        host_view v = band_view(st, whole, y);
        v.auto_exposure = true;
        v.meter_first_row = (uint32_t)st->pad, v.meter_rows = (uint32_t)(height - y < band ? height - y : band);
        vksky_exposure m;
        if (host_commands_render(h, r, &v, trace, NULL) || vksky_renderer_get_exposure(r, 0, &m) != VKSKY_SUCCESS)
            return NAN;
        if (m.pixel_count > 0.0) log_sum += m.pixel_count * log(m.log_average), count += m.pixel_count;
    }
    sky_view v = st->o->view;
    double average = count > 0.0 ? exp(log_sum / count) : 1e-4;
    light_expose(&v, average);
    if (!st->o->quiet)
        fprintf(stderr, "vksky: auto exposure: EV100 %.4f (log-average luminance %.6g %s over %.0f pixels, metered on "
                        "the GPU in %d band%s)\n", light_auto_ev100(average), average,
                v.ev100 ? "cd/m2" : "(relative units)", count, (height + band - 1) / band, band < height ? "s" : "");
    return v.exposure_ev;
}

/* tiles_render's body: r (the RGB renderer, pipelined where it pays) or draw (serial). */
static int render_bands(const options *o, vksky_context *ctx, vksky_renderer *r, host_commands *h, FILE *trace,
                        tiles_draw_fn draw, void *user)
{
    int width = o->width, height = o->height;
    int band = tiles_band_rows(width, height, tiles_budget());
    int bands = (height + band - 1) / band;
    /* Pipelined (app/runs/host_ring.h): band k+1 renders while band k is written. The bands keep their height (a
     * cube or perspective band's pixels depend on it by up to an fp16 ulp, and the files must equal the serial
     * loop's); each slot past the first adds one band's readback buffers (12 bytes a pixel). */
    int slots = bands > 1 && r ? host_ring_slots_wanted() : 0;
    renderer_draw own = {r, h, trace};
    if (!draw) draw = draw_renderer, user = &own;

    output outs[OPTIONS_MAX_OUTPUTS] = {0};
    if (open_outputs(o, outs) != 0) {
        abort_outputs(o, outs);
        return 1;
    }
    char what[300];
    snprintf(what, sizeof what, "rendering %s (%dx%d, %d bands)", o->output_count ? o->outputs[0] : "", width, height, bands);
    progress prog;
    progress_begin(&prog, stderr, o->quiet || bands < 2, what, height);
    bands_state st = {o, outs, &prog, 0, NULL, 0, tiles_band_pad(o)};
    /* The whole image's view (a perspective band's rays from yaw, pitch and fov) and projection. */
    host_view whole = {.yaw_deg = o->view.yaw_deg, .pitch_deg = o->view.pitch_deg, .fov_deg = o->view.fov_deg,
                       .exposure = o->view.exposure_ev, .projection = (vksky_projection)o->view.projection,
                       .whole_width = (uint32_t)width, .whole_height = (uint32_t)height};
    int status = 0;
    if (r && light_auto_exposure_wanted(o)) {
        whole.exposure = tiles_auto_exposure(&st, r, h, &whole, band, trace);
        if (isnan(whole.exposure)) status = 1;
    }
    stage_begin();
    if (status == 0)
        status = slots >= 2 ? bands_ring(&st, ctx, r, &whole, band, slots, trace)
                            : bands_serial(&st, draw, user, &whole, band);
    /* A LUT cache miss: the LUTs the first band computed, into the cache for the next start (every band is done). */
    if (status == 0 && r && vksky_renderer_store_luts(r) != VKSKY_SUCCESS) status = 1;
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
    return status;
}

int tiles_render(const options *o, vksky_context *ctx, vksky_renderer *r, host_commands *h, FILE *trace)
{
    return render_bands(o, ctx, r, h, trace, NULL, NULL);
}

int tiles_render_drawn(const options *o, tiles_draw_fn draw, void *user)
{
    return render_bands(o, NULL, NULL, NULL, NULL, draw, user);
}
