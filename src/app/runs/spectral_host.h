/* --spectral N of one image through include/vksky.h (issue 25s): a perspective frame, or an environment map, in one
 * band or several. A renderer per wavelength group, each made with its group's scene (vksky_scene_spectral_group: the spectral
 * reference's packing and weights as API values), every group recorded into one command buffer and submitted once; the
 * readbacks summed on the host into CIE XYZ, then linear Rec.709 into the linear image and, with a PNG, the host's tone
 * map (spectral_render_tonemap_image). No src/sky or src/lib header (tests/layering_test.sh). */
#ifndef VKSKY_APP_SPECTRAL_HOST_H
#define VKSKY_APP_SPECTRAL_HOST_H
#include <volk.h>
#include <vksky.h>
#include "app/cli/options_struct.h"
#include "app/runs/host_ring.h"

/* The image's pixels, the host's own (free them with spectral_image_release). display: NULL without a PNG output. */
typedef struct spectral_image {
    uint16_t *linear;            /* width x height x 4 halfs, the HDR image's units */
    uint8_t *display;            /* width x height x 4 sRGB bytes */
} spectral_image;
void spectral_image_release(spectral_image *img);

/* Renders o's image spectral on ctx (the scene `scene` of o's command line, its groups derived here) with h's command
 * buffer. 0, or 1 (the line printed). */
int spectral_host_render(const options *o, vksky_context *ctx, const vksky_scene *scene, host_commands *h,
                         spectral_image *out);
/* A sequence (or --skip-existing), frame by frame (each frame's groups in one submission), as an RGB sequence writes
 * them (app/runs/sequence.c): files, progress and summary lines. `scene` takes each frame's values. 0, or 1. */
int spectral_host_sequence(const options *o, vksky_context *ctx, vksky_scene *scene, host_commands *h);
/* An .exr or .png image in several bands (tiles_in_bands): a renderer per group of tiles_frame_rows rows, every band's
 * groups in one submission and summed on the encode threads, the bands streamed by app/runs/tiles.c; a PNG's band
 * tone-mapped on the host (an auto-exposed one metered first over every band). 0, or 1. */
int spectral_host_bands(const options *o, vksky_context *ctx, const vksky_scene *scene, host_commands *h);
#endif
