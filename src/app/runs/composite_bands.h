/* The composite in bands (issue 28): any image size through band-sized buffers. The render is read a band of rows at
 * a time (with a few rows either side for the edge repair, app/runs/composite_layers.h), composited on the GPU band by
 * band through one band-sized composite pass (sky/composite.h), and its layers streamed into the output EXR
 * (io/exr_layers.h, io_exr_layers_stream_*): peak memory follows the band, not the image. */
#ifndef VKSKY_APP_COMPOSITE_BANDS_H
#define VKSKY_APP_COMPOSITE_BANDS_H

#include "app/runs/composite_layers.h"
#include "io/exr_layers.h"
#include "sky/composite.h"

/* Rows per band for a width x height composite: about 2^20 pixels (VKSKY_COMPOSITE_BAND_ROWS overrides, for
 * tests), a whole number of the writer's 16-row chunks, the whole image when it is smaller. */
int composite_band_rows(int width, int height);

typedef struct band_reader {
    const char *beauty_path;
    const composite_inputs *in;
    const composite_view *v;
    int width, height, band_rows;
    float *beauty, *position;   /* (band_rows + 2 margins) rows, RGBA */
    composite_band band;        /* the band last read */
} band_reader;

/* 0, or 1 after one line on stderr (out of memory). */
int band_reader_init(band_reader *b, const char *beauty_path, const composite_inputs *in, const composite_view *v,
                     int width, int height, int band_rows);
void band_reader_free(band_reader *b);

/* Reads and fixes the band whose core starts at row y0 (composite_fix_positions; its counts added to *fix). 0, 1
 * or 2 (one line on stderr). */
int band_reader_read(band_reader *b, int y0, composite_fixups *fix);

/* The core rows of the band last read into the composite's upload buffer (beauty rows, then position rows; rows
 * below a short last band: covered and without a position, so that nothing is marched for them). */
void band_reader_upload(const band_reader *b, sky_composite *c);

/* Every band: read, composite (push's band row set per band), and its rows streamed into `out`. 0, 1 or 2 (after
 * one line on stderr; the stream is then aborted). */
int composite_bands_render(band_reader *b, sky_renderer *r, sky_composite *c, CompositePush push, int frames,
                           io_exr_layers_stream *out);

#endif
