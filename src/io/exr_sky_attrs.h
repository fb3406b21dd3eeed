/* vksky image I/O: what an EXR's header says about the sky beyond its pixels (types only; written by
 * io/exr_envmap_attrs.c, passed in by the streamed writer's caller). */
#ifndef VKSKY_IO_EXR_SKY_ATTRS_H
#define VKSKY_IO_EXR_SKY_ATTRS_H
#include <stdbool.h>

typedef enum io_envmap { IO_ENVMAP_NONE, IO_ENVMAP_LATLONG, IO_ENVMAP_CUBE } io_envmap;

/* What the header says about the sky beyond the pixels (io/exr_envmap_attrs.c writes it). */
typedef struct io_exr_sky_attrs {
    io_envmap envmap;                 /* the standard "envmap" attribute (none: left out) */
    const char *projection;           /* "vksky:projection" (NULL: left out) */
    bool has_sun;
    float sun_direction[3];           /* "vksky:sunDirection": unit vector toward the sun, the map's axes */
    float sun_illuminance[3];         /* "vksky:sunIlluminance": RGB illuminance at the top of the atmosphere */
    float sun_at_camera[3];           /* "vksky:sunIlluminanceAtCamera": through the atmosphere to the camera (0 when
                                         the planet hides the sun): the separate sun light of a --no-sun-disc map */
    /* Units (issue 32): "vksky:units" says what a pixel holds, "vksky:sunIlluminanceUnits" the unit of both sun
     * attributes (NULL: left out); whiteLuminance > 0: OpenEXR's standard "whiteLuminance", the cd/m2 of RGB 1,1,1. */
    const char *units;
    const char *sun_units;
    float white_luminance;
    const struct io_exr_meta *meta;   /* issue 28: the standard and vksky attributes (exr_meta.h; NULL: none) */
} io_exr_sky_attrs;
#endif
