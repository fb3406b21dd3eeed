/* Where the fragment tone map needs its horizon path (issue 26). hdr_upsample.glsl takes seven fetches for an output
 * pixel within two texels of the horizon and one elsewhere, a per-pixel branch; but lavapipe (Mesa 22.3) runs a
 * branch's body under a lane mask even where no lane takes it, so every pixel paid the seven (the tone map 3-4x its
 * one-fetch cost). The decision is therefore made here, per tile of the output, from the analytic horizon and the
 * sky pass's own projection values in double: a tile none of whose texels can be within the horizon path's reach is
 * drawn by the far-only pipeline (the branch compiled out), the rest by the full one. The test is conservative (a
 * bound on the horizon's level function's derivatives over the tile), so each pixel takes the path the full shader
 * would give it and the image is the same, byte for byte (ctest tonemap_regions). */
#ifndef VKSKY_SKY_TONEMAP_REGIONS_H
#define VKSKY_SKY_TONEMAP_REGIONS_H
#include "shared.h"
#include <stdbool.h>
#include <stdint.h>
#include <volk.h>

#define TONEMAP_REGION_TILE 32    /* a tile's output pixels: columns */
#define TONEMAP_REGION_ROWS 8     /* and rows (the horizon runs mostly across: a thin band of tiles) */
#define TONEMAP_REGIONS_MAX 512   /* more: one region, the full path (the image is the same, only slower) */

typedef struct tonemap_region {
    VkRect2D rect;   /* output pixels */
    bool horizon;    /* the full path (some texel it reads may lie within the horizon path's reach) */
} tonemap_region;

typedef struct tonemap_regions {
    uint32_t count;
    tonemap_region region[TONEMAP_REGIONS_MAX];
} tonemap_regions;

/* The regions of a `display`-sized tone map reading an `hdr`-sized sky image that the sky pass drew with `sky` (its
 * push: projection, tile offset, horizon). Horizontal runs of tiles of one kind, runs that repeat from one tile row
 * to the next merged. VKSKY_TONEMAP_SPLIT=0 in the environment: one region, the full path (the image before). */
void tonemap_regions_plan(tonemap_regions *out, const SkyPush *sky, VkExtent2D hdr, VkExtent2D display);
#endif
