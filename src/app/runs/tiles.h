/* Renders in bands (issue 13): environment maps, and images larger than a tile budget, are rendered a band of rows
 * at a time and streamed into their files, so that memory stays bounded whatever the image size. A band's pixels
 * get the directions they have in the whole image (sky_view's tile offset), so the bands put together equal the
 * untiled frame (tests/envmap_test.sh checks it). */
#ifndef VKSKY_APP_TILES_H
#define VKSKY_APP_TILES_H
#include "app/cli/options_struct.h"
#include "app/runs/host_ring.h"
#include <stdio.h>

/* Pixels a band may hold: VKSKY_TILE_PIXELS, else 8 Mpixel (about 300 MB of images and readback buffers). */
long tiles_budget(void);
/* Rows per band for a width x height image (a multiple of 16, the EXR ZIP chunk, unless the image is smaller). */
int tiles_band_rows(int width, int height, long budget);
/* Whether this render goes through the band renderer: an environment-map projection, or more pixels than a band. */
bool tiles_wanted(const options *o);
/* Whether it takes more than one band (else one frame of the whole image: through the API, app/runs/headless_api.c). */
bool tiles_in_bands(const options *o);
/* The rows of the renderer a render in bands draws with: a band and the pad rows above and below it. */
int tiles_band_pad(const options *o);   /* the pad rows above (and below) each band: 1 in several bands, else 0 */
int tiles_frame_rows(const options *o);
/* The notes a render in bands or an environment map prints before its renderer is made: bloom left out of a render in
 * several bands, a --render-scale ignored. */
void tiles_begin_notes(const options *o);
/* Renders every band through include/vksky.h with r (made by app/runs/headless_api.c for o's scene at full size, the
 * width of the image and tiles_frame_rows rows, no bloom) and streams each output; h: the host's command buffer and
 * fence for the serial loop and auto exposure's metering pass; trace: --trace-barriers's stream (NULL: none). 0, or 1
 * (runtime failure, message printed, no partial file), or 1 when SIGINT/SIGTERM stopped it (between bands; the
 * partial files removed; the caller's stop_status exits 130 / 143). */
int tiles_render(const options *o, vksky_context *ctx, vksky_renderer *r, host_commands *h, FILE *trace);

/* The same bands drawn by someone else (app/runs/spectral_host.c: the wavelength groups summed): `draw` fills *out
 * with the band of view v (v->first_row, tiles_frame_rows(o) rows read back, pad rows included) and returns 0, or 1
 * with its message printed; its pixels stay valid until the next call. One band at a time, written in order; no
 * auto exposure here (a .png's display rows come tone-mapped from `draw`, which meters them itself). 0, or 1. */
typedef int (*tiles_draw_fn)(void *user, const host_view *v, frame_ring_pixels *out);
int tiles_render_drawn(const options *o, tiles_draw_fn draw, void *user);
#endif
