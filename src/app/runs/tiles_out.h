/* The files of a banded render or an environment map (app/runs/tiles.c; one band through the API:
 * app/runs/headless_api.c): every --render output opened as a stream before the first row exists (EXR with its sky and
 * environment-map attributes, PNG), rows appended band by band, finished or aborted (no partial file). */
#ifndef VKSKY_APP_RUNS_TILES_OUT_H
#define VKSKY_APP_RUNS_TILES_OUT_H
#include "app/cli/options_struct.h"
#include "io/exr_stream.h"
#include "io/png_stream.h"

typedef struct output {
    bool exr;
    io_exr_stream *exr_stream;
    io_png_stream *png_stream;
} output;

/* Opens every output of `o` (o->width x o->height); 0, or 1 with the line printed (abort_outputs cleans up). */
int open_outputs(const options *o, output *outs);
/* A band's EXR rows: as read back, or in output units (the HDR scale divided out) through `band_f32` (reused). */
int write_exr_rows(const options *o, io_exr_stream *s, const uint16_t *half, int rows, float **band_f32,
                   size_t *band_cap, char *err, size_t err_size);
/* Removes every output still open (their partial files). */
void abort_outputs(const options *o, output *outs);
/* The note for a --render-scale the user gave (not a preset's): bands are rendered at full size. */
void tiles_note_render_scale(const options *o);
#endif
