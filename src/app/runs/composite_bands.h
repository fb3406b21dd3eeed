/* The composite in bands (issue 28): any image size through band-sized buffers. The render is read a band of rows at
 * a time (with a few rows either side for the edge repair, app/runs/composite_layers.h), composited on the GPU band by
 * band through one band-sized composite pass of include/vksky.h (vksky_composite_*), and its layers streamed into the
 * output EXR (io/exr_layers.h, io_exr_layers_stream_*): peak memory follows the band, not the image. A host of the
 * API: no src/sky or src/lib header (tests/layering_test.sh). */
#ifndef VKSKY_APP_COMPOSITE_BANDS_H
#define VKSKY_APP_COMPOSITE_BANDS_H

#include "app/runs/composite_layers.h"
#include "app/runs/host_ring.h"
#include "io/exr_layers.h"
#include <vksky.h>
#include <stdio.h>

/* Rows per band for a width x height composite: about 2^18 pixels (VKSKY_COMPOSITE_BAND_ROWS overrides, for
 * tests), a whole number of the writer's chunks (16 rows, 32 for PIZ and B44: --exr-compression), the whole image
 * when it is smaller. */
int composite_band_rows(int width, int height);

typedef struct band_reader {
    const char *beauty_path;
    const composite_inputs *in;
    const composite_view *v;
    int width, height, band_rows;
    float *beauty, *position;   /* (band_rows + 2 margins) rows, RGBA */
    composite_band band;        /* the band last read */
    /* Summed over the bands read (their core rows): the edge repairs and the film's checks, the pixels with and
     * without geometry (a finite position and alpha > 0). The inputs are read once, as they are composited. */
    composite_fixups fix;
    size_t geometry, sky;
} band_reader;

/* 0, or 1 after one line on stderr (out of memory). */
int band_reader_init(band_reader *b, const char *beauty_path, const composite_inputs *in, const composite_view *v,
                     int width, int height, int band_rows);
void band_reader_free(band_reader *b);

/* Reads and fixes the band whose core starts at row y0 (composite_fix_positions; its counts added to b's). 0, 1
 * or 2 (one line on stderr). */
int band_reader_read(band_reader *b, int y0);

/* The common mistakes, from the counts so far: an opaque film (most pixels alpha 1 with no position: decided as soon as
 * the count reaches it, so a run stops at the band that shows it) and, once every band was read (`whole`), no geometry
 * at all. 0, or 2 after one line on stderr; the caller aborts its output (nothing at the output path). */
int band_reader_verdict(const band_reader *b, bool whole);

/* The core rows of the band last read into `in` (vksky_composite_inputs: `rows` beauty rows, then `rows` position
 * rows; rows below a short last band: covered and without a position, so that nothing is marched for them). */
void band_reader_upload(const band_reader *b, float *in, int rows);

/* The composite's frames of one band, from inputs already in `slot`: VKSKY_FRAMES frames recorded back to back into
 * h's command buffer (the LUTs rebuilt in each after the first; with h->async each frame its own pair of submissions,
 * the LUTs on the compute queue), submitted and waited for. *wall_ms (may be NULL): submit to fence. 0, or 1. */
int composite_submit(host_commands *h, vksky_renderer *r, vksky_composite *c, const vksky_composite_frame *f,
                     int frames, FILE *trace, double *wall_ms);

/* Every band: read, composited, and its rows streamed into `out`. slots 1: one band at a time through h[0] (frames:
 * VKSKY_FRAMES, --async-luts as h[0] says). slots 2 (c made with two slots, one frame a band, no --async-luts): a ring
 * of two, band k + 1's GPU work while band k's layers are encoded (h[k % 2]; composite.band_done, composite.slot_free:
 * docs/synchronization.md, "The composite's bands"). 0, 1 or 2 (after one line on stderr; the stream is then
 * aborted). */
int composite_bands_render(band_reader *b, host_commands h[2], int slots, vksky_renderer *r, vksky_composite *c,
                           int frames, FILE *trace, io_exr_layers_stream *out);

/* --bench N with --composite: per-pass GPU medians of N composite frames of slot 0's inputs after warm-up (the LUTs
 * are not in them: built once by the first frame), one line per pass like the sky's benchmark, on stdout. */
/* --timings: the start (the device, renderer and pipelines) and the bands' stages (stage_times.h: read, check and
 * upload + submit, the GPU waits, the stream's writes) since stage_begin. */
typedef struct composite_start_times {
    double setup_wall_ms;
} composite_start_times;
void composite_timings_report(FILE *out, const band_reader *b, const composite_start_times *t);

void composite_bench(host_commands *h, vksky_renderer *r, vksky_composite *c, bool volume, uint32_t width,
                     uint32_t rows, int frames, FILE *trace);

#endif
