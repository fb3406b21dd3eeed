/* The composite in bands (composite_bands.h). */
#include "app/runs/composite_bands.h"
#include "app/runs/stop.h"
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const LAYER_NAMES[VKSKY_AOV_COUNT] = {"", "sky", "sun_disk", "transmittance", "rayleigh", "mie"};

int composite_band_rows(int width, int height)
{
    const char *env = getenv("VKSKY_COMPOSITE_BAND_ROWS");
    int rows = env && atoi(env) > 0 ? atoi(env) : (1 << 20) / (width > 0 ? width : 1);
    rows = rows < 16 ? 16 : rows / 16 * 16;   /* whole chunks of the ZIP writer (16 rows) */
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

int band_reader_read(band_reader *b, int y0, composite_fixups *fix)
{
    int core_rows = b->height - y0 < b->band_rows ? b->height - y0 : b->band_rows;
    int first = y0 - COMPOSITE_BAND_MARGIN < 0 ? 0 : y0 - COMPOSITE_BAND_MARGIN;
    int last = y0 + core_rows + COMPOSITE_BAND_MARGIN > b->height ? b->height : y0 + core_rows + COMPOSITE_BAND_MARGIN;
    b->band = (composite_band){.width = b->width, .frame_height = b->height, .first_row = first, .rows = last - first,
                               .core_row = y0, .core_rows = core_rows};
    int rc = composite_read_band(b->beauty_path, b->in, b->width, first, last - first, b->beauty, b->position);
    if (rc) return rc;
    composite_fix_positions(b->beauty, b->position, b->in->has_depth ? b->position : NULL, &b->band, b->v,
                            b->in->position_half, fix);
    return 0;
}

void band_reader_upload(const band_reader *b, sky_composite *c)
{
    const composite_band *band = &b->band;
    size_t row = (size_t)b->width * 4, core = (size_t)(band->core_row - band->first_row) * row;
    size_t used = (size_t)band->core_rows * row, all = (size_t)c->height * row;
    float *in = sky_composite_inputs(c);
    memcpy(in, b->beauty + core, used * sizeof(float));
    memcpy(in + all, b->position + core, used * sizeof(float));
    for (size_t i = used; i < all; i += 4) {
        in[i] = in[i + 1] = in[i + 2] = 0.0f, in[i + 3] = 1.0f;
        in[all + i] = in[all + i + 1] = in[all + i + 2] = NAN, in[all + i + 3] = 1.0f;
    }
    /* Each sky tile (shared.h) none of whose pixels shows sky (alpha >= 1: the shader's own test), marked in its
     * first pixel's position w, so that the shader need not read the tile's alphas to skip its sky rays. */
    const int tile = VKSKY_COMPOSITE_TILE, w = b->width, rows = (int)c->height;
    for (int ty = 0; ty < rows; ty += tile)
        for (int tx = 0; tx < w; tx += tile) {
            bool sky = false;
            for (int y = ty; y < ty + tile && y < rows && !sky; ++y)
                for (int x = tx; x < tx + tile && x < w && !sky; ++x) sky = !(in[((size_t)y * w + x) * 4 + 3] >= 1.0f);
            in[all + ((size_t)ty * w + tx) * 4 + 3] = sky ? 1.0f : (float)VKSKY_COMPOSITE_TILE_NO_SKY;
        }
}

int composite_bands_render(band_reader *b, sky_renderer *r, sky_composite *c, CompositePush push, int frames,
                           io_exr_layers_stream *out)
{
    char err[600];
    composite_fixups ignored = {0};   /* counted by the first pass */
    for (int y0 = 0; y0 < b->height; y0 += b->band_rows) {
        int rc = band_reader_read(b, y0, &ignored);
        if (rc) {
            io_exr_layers_stream_abort(out);
            return rc;
        }
        band_reader_upload(b, c);
        push.right.w = (float)y0;   /* the band's first row (shared.h) */
        sky_composite_render(r, c, &push, frames);
        io_exr_band_layer layers[VKSKY_AOV_COUNT];
        for (int k = 0; k < VKSKY_AOV_COUNT; ++k)
            layers[k] = (io_exr_band_layer){LAYER_NAMES[k], k == 0 ? 4 : 3, 4, sky_composite_layer(c, k)};
        if (io_exr_layers_stream_rows(out, layers, b->band.core_rows, err, sizeof err) != 0) {
            fprintf(stderr, "vksky: --render: %s\n", err);
            return 1;
        }
        if (stop_requested()) {   /* SIGINT/SIGTERM: no file at the output path */
            io_exr_layers_stream_abort(out);
            return 1;
        }
    }
    return 0;
}
