/* Renders in bands (issue 13): environment maps, and images larger than a tile budget, are rendered a band of rows
 * at a time and streamed into their files, so that memory stays bounded whatever the image size. A band's pixels
 * get the directions they have in the whole image (sky_view's tile offset), so the bands put together equal the
 * untiled frame (tests/envmap_test.sh checks it). */
#ifndef VKSKY_APP_TILES_H
#define VKSKY_APP_TILES_H
#include "app/cli/options_struct.h"
#include "gpu/context.h"
#include "sky/frame.h"

/* Pixels a band may hold: VKSKY_TILE_PIXELS, else 8 Mpixel (about 300 MB of images and readback buffers). */
long tiles_budget(void);
/* Rows per band for a width x height image (a multiple of 16, the EXR ZIP chunk, unless the image is smaller). */
int tiles_band_rows(int width, int height, long budget);
/* Whether this render goes through the band renderer: an environment-map projection, or more pixels than a band. */
bool tiles_wanted(const options *o);
/* Whether it takes more than one band (else one frame of the whole image: through the API, app/runs/headless_api.c). */
bool tiles_in_bands(const options *o);
/* Renders every band and streams each output; 0, or 1 (runtime failure, message printed, no partial file), or
 * 1 when SIGINT/SIGTERM stopped it (between bands; the partial files removed; the caller's stop_status exits
 * 130 / 143). */
int tiles_render(const options *o, gpu_context *ctx);
/* The same with each band's frame drawn by `frame` (NULL: sky_renderer_render; --spectral: spectral_render_frame,
 * armed by the caller), in the serial band loop. */
typedef void (*tiles_frame_fn)(sky_renderer *r, const frame_desc *f);
int tiles_render_with(const options *o, gpu_context *ctx, tiles_frame_fn frame);
#endif
