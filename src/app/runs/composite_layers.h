/* The composite's inputs (issue 28): which layers of a render are the beauty, the position and the depth, chosen
 * so that the choice cannot be wrong silently (one view layer for all of them; never a compositor output unless
 * named; several view layers and no --view-layer: exit 2 listing them), read into the composite's RGBA rows, and
 * made fit for compositing (depth -> position; anti-aliased edge pixels without a position take their nearest
 * covered neighbour's; an opaque film and overflowed half positions detected). */
#ifndef VKSKY_APP_COMPOSITE_LAYERS_H
#define VKSKY_APP_COMPOSITE_LAYERS_H

#include "app/cli/options_composite.h"
#include "io/exr_read.h"
#include <volk.h>
#include <vksky.h>
#include <stdbool.h>
#include <stddef.h>

/* The render's world, camera and sun: include/vksky.h's (vksky_composite_view). */
typedef vksky_composite_view composite_view;

typedef struct layer_pick {
    char prefix[512];         /* "ViewLayer.Combined", "" (top level) */
    const char *letters;      /* "RGBA", "RGB", "XYZ", "Z", "R" */
} layer_pick;

typedef struct composite_inputs {
    char view_layer[256];     /* the view layer used ("" when the file has none) */
    layer_pick beauty, position, depth;
    bool has_position, has_depth;   /* a position layer; else a depth layer (camera-space Z, world units) */
    const char *position_path, *depth_path;
    bool position_half;       /* the position's channels are HALF (overflow beyond 65504 reads as inf) */
} composite_inputs;

/* Chooses the layers of `bi` (the --composite file) and, when given, `pi` (--position FILE) / `di` (--depth FILE).
 * 0, or 2 after one line on stderr. */
int composite_pick_inputs(const composite_options *co, const io_exr_info *bi, const io_exr_info *pi,
                          const io_exr_info *di, composite_inputs *in);


typedef struct composite_fixups {
    size_t repaired;          /* edge pixels (0 < alpha) without a position that took a neighbour's */
    size_t unrepaired;        /* covered pixels left without a position (composited as the beauty, no atmosphere) */
    size_t overflowed;        /* half positions that overflowed to inf (beyond 65504 world units) */
    size_t opaque;            /* alpha-1 pixels at (0, 0, 0) / without a position: an opaque film's background */
} composite_fixups;

/* A band of the frame held in memory: `rows` rows from `first_row`, of which rows [core_row, core_row + core_rows)
 * are the band's own (the rest: neighbours for the edge repair, COMPOSITE_BAND_MARGIN rows each side). */
enum { COMPOSITE_BAND_MARGIN = 3 };
typedef struct composite_band {
    int width, frame_height;
    int first_row, rows, core_row, core_rows;
} composite_band;

/* Makes a band's `position` (RGBA rows) fit to composite, in place: a depth pass (`depth`, non-NULL, may be
 * `position` itself) becomes world positions along each pixel's ray of `v` (needs v->oriented); overflowed half
 * values are counted and left missing; a covered core pixel whose position is missing, non-finite or exactly
 * (0, 0, 0) takes the position of its nearest covered neighbour with one (within COMPOSITE_BAND_MARGIN pixels; ties:
 * the coverage closest to its own). Missing positions end as NaN. Counts (added to *out) cover the core rows. */
void composite_fix_positions(const float *beauty, float *position, const float *depth, const composite_band *band,
                             const composite_view *v, bool position_half, composite_fixups *out);

/* Reads rows [first_row, first_row + rows) of the picked beauty into `beauty` and of the position (or depth, into
 * `position`'s first value per pixel) into `position`, RGBA per pixel. 0, 1 (memory) or 2 (one line on stderr). */
int composite_read_band(const char *beauty_path, const composite_inputs *in, int width, int first_row, int rows,
                        float *beauty, float *position);

#endif
