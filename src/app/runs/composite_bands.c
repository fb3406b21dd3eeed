/* The composite in bands (composite_bands.h). */
#include "app/runs/composite_bands.h"
#include "app/runs/stage_times.h"
#include "app/runs/stop.h"
#include "io/encode_settings.h"
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const LAYER_NAMES[VKSKY_COMPOSITE_LAYERS] = {"", "sky", "sun_disk", "transmittance", "rayleigh", "mie"};

int composite_band_rows(int width, int height)
{
    const char *env = getenv("VKSKY_COMPOSITE_BAND_ROWS");
    /* 2^18 pixels: at 3840x2160, bands of 64 rows take 10-17 % less CPU than bands of 272 (2^20 pixels), the same
     * bytes: a third of the page faults, 236 MB resident instead of 626 (docs/performance.md "The composite's band
     * size"). Bands of 16 rows cost more: the 3 margin rows either side decode a whole 16-row chunk each, and every
     * band is a submission. 64 rows at least: at 7680x4320 on an H200, bands of 32 rows (2^18 pixels) took 4.5 s
     * wall against 3.7 for 64 and 3.4 for 128 (medians of 3), the margins' chunk decodes and the submissions adding
     * up; 64 rows there cost what main's 2^20-pixel bands did (3.71 s). */
    int rows = env && atoi(env) > 0 ? atoi(env) : (1 << 18) / (width > 0 ? width : 1);
    if (!(env && atoi(env) > 0) && rows < 64) rows = 64;
    /* Whole chunks of the writer: 16 rows (ZIP's, and the bands' floor), or 32 for PIZ and B44 (all powers of 2). */
    int chunk = io_exr_compression_lines(io_encode_settings_get().exr_compression);
    if (chunk < 16) chunk = 16;
    rows = rows < chunk ? chunk : rows / chunk * chunk;
    return rows >= height ? height : rows;
}

int band_reader_init(band_reader *b, const char *beauty_path, const composite_inputs *in, const composite_view *v,
                     int width, int height, int band_rows)
{
    *b = (band_reader){.beauty_path = beauty_path, .in = in, .v = v, .width = width, .height = height,
                       .band_rows = band_rows};
    size_t n = (size_t)width * (size_t)(band_rows + 2 * COMPOSITE_BAND_MARGIN) * 4;
    b->beauty = malloc(n * sizeof(float));
    b->position = malloc(n * sizeof(float));
    if (!b->beauty || !b->position) {
        fprintf(stderr, "vksky: --composite: out of memory for a band of %dx%d pixels\n", width, band_rows);
        band_reader_free(b);
        return 1;
    }
    return 0;
}

void band_reader_free(band_reader *b)
{
    free(b->beauty);
    free(b->position);
    b->beauty = b->position = NULL;
}

int band_reader_read(band_reader *b, int y0)
{
    int core_rows = b->height - y0 < b->band_rows ? b->height - y0 : b->band_rows;
    int first = y0 - COMPOSITE_BAND_MARGIN < 0 ? 0 : y0 - COMPOSITE_BAND_MARGIN;
    int last = y0 + core_rows + COMPOSITE_BAND_MARGIN > b->height ? b->height : y0 + core_rows + COMPOSITE_BAND_MARGIN;
    b->band = (composite_band){.width = b->width, .frame_height = b->height, .first_row = first, .rows = last - first,
                               .core_row = y0, .core_rows = core_rows};
    int rc = composite_read_band(b->beauty_path, b->in, b->width, first, last - first, b->beauty, b->position);
    if (rc) return rc;
    composite_fix_positions(b->beauty, b->position, b->in->has_depth ? b->position : NULL, &b->band, b->v,
                            b->in->position_half, &b->fix);
    size_t core = (size_t)(y0 - first) * (size_t)b->width, end = core + (size_t)core_rows * (size_t)b->width;
    for (size_t i = core; i < end; ++i) {
        const float *p = b->position + 4 * i;
        if (isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]) && b->beauty[4 * i + 3] > 0.0f) ++b->geometry;
        else ++b->sky;
    }
    return 0;
}

int band_reader_verdict(const band_reader *b, bool whole)
{
    size_t n = (size_t)b->width * (size_t)b->height, opaque = b->fix.opaque;
    if (opaque >= 16 && opaque * 100 >= n) {
        fprintf(stderr, "vksky: --composite: %s: the film is opaque: %zu pixels (%.0f %%) have alpha 1 and no "
                        "position (a background, not geometry): render with a transparent film (Blender: Render "
                        "Properties > Film > Transparent) so that the sky can go behind\n",
                b->beauty_path, opaque, 100.0 * (double)opaque / (double)n);
        return 2;
    }
    if (whole && b->geometry == 0) {
        fprintf(stderr, "vksky: --composite: %s: the %s pass has no finite pixel with alpha > 0: nothing to "
                        "apply the atmosphere to (is it the world-position pass?)\n",
                b->in->has_depth ? b->in->depth_path : b->in->position_path, b->in->has_depth ? "depth" : "position");
        return 2;
    }
    return 0;
}

void band_reader_upload(const band_reader *b, float *in, int rows)
{
    const composite_band *band = &b->band;
    size_t row = (size_t)b->width * 4, core = (size_t)(band->core_row - band->first_row) * row;
    size_t used = (size_t)band->core_rows * row, all = (size_t)rows * row;
    memcpy(in, b->beauty + core, used * sizeof(float));
    memcpy(in + all, b->position + core, used * sizeof(float));
    for (size_t i = used; i < all; i += 4) {
        in[i] = in[i + 1] = in[i + 2] = 0.0f, in[i + 3] = 1.0f;
        in[all + i] = in[all + i + 1] = in[all + i + 2] = NAN, in[all + i + 3] = 1.0f;
    }
}

/* A band's frame for host_commands_submit: the composite frame with the LUTs forced and following as it says. */
typedef struct band_frames {
    vksky_composite *c;
    const vksky_composite_frame *f;
} band_frames;

static int record_band(void *user, VkCommandBuffer cmd, bool force_luts, bool follows_frame)
{
    const band_frames *b = user;
    vksky_composite_frame fk = *b->f;
    fk.force_luts = force_luts, fk.follows_frame = follows_frame;
    return vksky_composite_record(b->c, cmd, &fk) == VKSKY_SUCCESS ? 0 : 1;
}

/* Frames first .. first + count - 1 of the band into h's command buffer (frame k > 0 rebuilds the LUTs), submitted
 * (after the LUT passes on the compute queue, with h->async) and waited for unless the ring waits (wait_fence). */
static int submit_frames(host_commands *h, vksky_renderer *r, vksky_composite *c, const vksky_composite_frame *f,
                         int first, int count, FILE *trace, double *wall_ms, bool wait_fence)
{
    band_frames frames = {c, f};
    host_submission s = {.luts = &r, .luts_count = 1, .force_luts = f->force_luts, .record = record_band,
                         .user = &frames, .trace = trace, .wall_ms = wall_ms, .no_wait = !wait_fence,
                         .what = "the composite"};
    return host_commands_submit(h, &s, first, count);
}

int composite_submit(host_commands *h, vksky_renderer *r, vksky_composite *c, const vksky_composite_frame *f,
                     int frames, FILE *trace, double *wall_ms)
{
    int n = frames < 1 ? 1 : frames > 16 ? 16 : frames;
    if (h->async) {   /* each frame its own pair of submissions, checked across queues by synchronization validation */
        for (int k = 0; k < n; ++k)
            if (submit_frames(h, r, c, f, k, 1, trace, wall_ms, true)) return 1;
        return 0;
    }
    return submit_frames(h, r, c, f, 0, n, trace, wall_ms, true);
}

static int stream_band(vksky_composite *c, uint32_t slot, int core_rows, io_exr_layers_stream *out)
{
    char err[600];
    io_exr_band_layer layers[VKSKY_COMPOSITE_LAYERS];
    for (uint32_t k = 0; k < VKSKY_COMPOSITE_LAYERS; ++k)
        layers[k] = (io_exr_band_layer){LAYER_NAMES[k], k == 0 ? 4 : 3, 4, vksky_composite_layer(c, slot, k)};
    if (io_exr_layers_stream_rows(out, layers, core_rows, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: --render: %s\n", err);
        return 1;
    }
    return 0;
}

/* composite.band_done: the host waits for band `band`'s fence before it reads the slot's layers (GPU -> host, RAW:
 * the copy's writes, made visible to the host by aovs.to_host). Traced; VKSKY_DROP_BARRIER=composite.band_done
 * leaves it (and the fence's reset) out: the layers are read while the band may still be in flight, and the slot's
 * next submission finds its fence signalled, which validation reports (tests/composite_ring_test.sh). */
static int band_done(host_commands *h, int band, uint32_t slot, FILE *trace, const char *drop, bool *waited)
{
    if (trace) fprintf(trace, "sync composite.band_done band=%d slot=%u (GPU -> host: the band's layers)\n", band, slot);
    *waited = !(drop && !strcmp(drop, "composite.band_done"));
    if (!*waited) return 0;
    VkResult vr = vkWaitForFences(h->device, 1, &h->fence, VK_TRUE, UINT64_MAX);
    if (vr == VK_SUCCESS) vr = vkResetFences(h->device, 1, &h->fence);
    if (vr != VK_SUCCESS) fprintf(stderr, "vksky: the composite's band %d failed (VkResult %d)\n", band, (int)vr);
    return vr == VK_SUCCESS ? 0 : 1;
}

/* Two slots (composite_bands.h): band k is read and submitted into slot k % 2, then band k - 1's layers are waited for
 * (composite.band_done) and encoded while the GPU composites band k. Slot k % 2 is the host's again when band k - 2's
 * layers are encoded (composite.slot_free: a hand-over, traced; the wait that makes it safe is band k - 2's
 * band_done). The rows reach the stream in order, so the file is the one-slot loop's, byte for byte. */
static int render_ring(band_reader *b, host_commands h[2], vksky_composite *c, FILE *trace,
                       io_exr_layers_stream *out)
{
    const char *drop = getenv("VKSKY_DROP_BARRIER");
    int bands = (b->height + b->band_rows - 1) / b->band_rows, core_rows[2] = {0, 0}, rc = 0, submitted = 0;
    bool waited[2] = {true, true};
    for (int k = 0; k <= bands && rc == 0; ++k) {
        if (k < bands) {
            uint32_t s = (uint32_t)k % 2;
            int y0 = k * b->band_rows;
            stage_mark t0 = stage_mark_now();   /* --timings: read, upload, record and submit */
            if ((rc = band_reader_read(b, y0)) != 0 || (rc = band_reader_verdict(b, false)) != 0) break;
            if (trace && k >= 2)
                fprintf(trace, "sync composite.slot_free band=%d slot=%u (band %d's layers encoded)\n", k, s, k - 2);
            /* Only where band_done was dropped: the command buffer must not be pending when it is reset (its fence is
             * left signalled: the drop stays visible to validation, the driver safe). */
            if (k >= 2 && !waited[s]) vkWaitForFences(h[s].device, 1, &h[s].fence, VK_TRUE, UINT64_MAX);
            band_reader_upload(b, vksky_composite_inputs(c, s), b->band_rows);
            core_rows[s] = b->band.core_rows;
            vksky_composite_frame f = {.slot = s, .first_row = y0};
            if ((rc = submit_frames(&h[s], NULL, c, &f, 0, 1, trace, NULL, false)) != 0) break;
            stage_add_since(STAGE_PRODUCE, t0);
            submitted = k + 1;
        }
        if (k >= 1) {
            uint32_t s = (uint32_t)(k - 1) % 2;
            stage_mark t0 = stage_mark_now();
            rc = band_done(&h[s], k - 1, s, trace, drop, &waited[s]);
            stage_add_since(STAGE_GPU_WAIT, t0);
            t0 = stage_mark_now();
            if (rc == 0) rc = stream_band(c, s, core_rows[s], out);
            stage_add_since(STAGE_WRITE, t0);
            if (rc == 0 && stop_requested()) rc = 1;   /* SIGINT/SIGTERM: no file at the output path */
        }
    }
    if (submitted > 0) vkQueueWaitIdle(h[0].queue);   /* nothing of a failed run left in flight */
    if (rc == 0) rc = band_reader_verdict(b, true);
    if (rc) io_exr_layers_stream_abort(out);
    return rc;
}

int composite_bands_render(band_reader *b, host_commands h[2], int slots, vksky_renderer *r, vksky_composite *c,
                           int frames, FILE *trace, io_exr_layers_stream *out)
{
    if (slots == 2) return render_ring(b, h, c, trace, out);
    for (int y0 = 0; y0 < b->height; y0 += b->band_rows) {
        stage_mark t0 = stage_mark_now();   /* --timings: one band at a time, its GPU wait inside the submit */
        int rc = band_reader_read(b, y0);
        if (rc == 0) rc = band_reader_verdict(b, false);
        if (rc) {
            io_exr_layers_stream_abort(out);
            return rc;
        }
        band_reader_upload(b, vksky_composite_inputs(c, 0), b->band_rows);
        vksky_composite_frame f = {.slot = 0, .first_row = y0};   /* the band's first row of the whole image */
        if (composite_submit(&h[0], r, c, &f, frames, trace, NULL) != 0) {
            io_exr_layers_stream_abort(out);
            return 1;
        }
        stage_add_since(STAGE_PRODUCE, t0);
        t0 = stage_mark_now();
        if (stream_band(c, 0, b->band.core_rows, out) != 0) return 1;
        stage_add_since(STAGE_WRITE, t0);
        if (stop_requested()) {   /* SIGINT/SIGTERM: no file at the output path */
            io_exr_layers_stream_abort(out);
            return 1;
        }
    }
    int rc = band_reader_verdict(b, true);   /* no geometry at all: known once every band was read */
    if (rc) io_exr_layers_stream_abort(out);
    return rc;
}

void composite_timings_report(FILE *out, const band_reader *b, const composite_start_times *t)
{
    fprintf(out, "vksky: timings of the composite's start (ms): the device, renderer and pipelines %.1f wall\n",
            t->setup_wall_ms);
    int bands = (b->height + b->band_rows - 1) / b->band_rows;
    fprintf(out, "vksky: the composite's bands: produce = the inputs' rows read, fixed, checked and uploaded, recorded "
                 "and submitted; gpu wait = composite.band_done (the LUTs, on the first band, included); write = the layers "
                 "streamed (compressed on the encode threads)\n");
    stage_report(out, "composite", bands, "band", 1, io_encode_threads_all());
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void composite_bench(host_commands *h, vksky_renderer *r, vksky_composite *c, bool volume, uint32_t width,
                     uint32_t rows, int frames, FILE *trace)
{
    enum { PASSES = 4 };
    static const char *const names[PASSES] = {"ap_volume", "composite_upload", "composite", "composite_readback"};
    double *ms = calloc((size_t)frames * (PASSES + 1), sizeof *ms);
    if (!ms) return;
    double *wall = ms + (size_t)frames * PASSES;   /* submit -> fence (lavapipe's timestamps miss compute work) */
    bool timed = true;
    vksky_composite_frame f = {.slot = 0};
    for (int i = 0; i < 3; ++i) composite_submit(h, r, c, &f, 1, trace, NULL);   /* warm-up: LUTs, compiles */
    for (int i = 0; i < frames; ++i) {
        composite_submit(h, r, c, &f, 1, trace, &wall[i]);
        vksky_pass_timing read[64];
        uint32_t count = 0;
        timed = vksky_renderer_get_timings(r, read, 64, &count) == VKSKY_SUCCESS;
        for (uint32_t k = 0; k < count && k < 64; ++k)
            for (int p = 0; p < PASSES; ++p)
                if (!strcmp(read[k].name, names[p])) ms[p * frames + i] = read[k].gpu_ms;
    }
    for (int p = volume ? 0 : 1; p < PASSES && timed; ++p) {
        qsort(ms + p * frames, (size_t)frames, sizeof *ms, compare_double);
        printf("pass %s gpu_ms %.4f (%ux%u)\n", names[p], ms[p * frames + frames / 2], width, rows);
    }
    qsort(wall, (size_t)frames, sizeof *wall, compare_double);
    printf("composite frame wall_ms %.3f (submit to fence, median of %d; %s)\n", wall[frames / 2], frames,
           volume ? "volume" : "march");
    free(ms);
}
