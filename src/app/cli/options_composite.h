/* The flags of `vksky --composite` and `--aovs` (issue 12), parsed apart from the shared flag table: they are taken
 * out of argv before options_parse sees it, so the shared table needs no entry for them. */
#ifndef VKSKY_APP_OPTIONS_COMPOSITE_H
#define VKSKY_APP_OPTIONS_COMPOSITE_H
#include <stdbool.h>
#include <stdio.h>

typedef enum aerial_method { AERIAL_MARCH, AERIAL_VOLUME, AERIAL_AUTO } aerial_method;

typedef struct composite_options {
    const char *input;              /* --composite FILE.exr: multilayer render, or the beauty with --position */
    const char *position;           /* --position FILE.exr (NULL: the position is a layer of the input) */
    const char *beauty_layer;       /* --beauty-layer NAME (NULL: <ViewLayer>.Combined, or top-level R,G,B,A) */
    const char *position_layer;     /* --position-layer NAME (NULL: <ViewLayer>.Position, or top-level X,Y,Z/R,G,B) */
    const char *view_layer;         /* --view-layer NAME: the view layer of the beauty and the position (NULL: the
                                       file's only one; Composite, the compositor's output, only when named) */
    const char *depth;              /* --depth FILE.exr: camera-space depth (Z) instead of a position pass */
    int argc_all;                   /* the whole command line, this module's flags too (for the output's header) */
    char **argv_all;
    double world_unit_m;            /* --world-unit M: metres per world unit (default 1) */
    int up_axis;                    /* --world-up y|z: 1 or 2 (default z) */
    double ground_altitude_km;      /* --ground-altitude KM (default 0) */
    bool has_camera_position;
    double camera_position[3];      /* --camera-position X,Y,Z (world units) */
    bool has_orientation;           /* --yaw or --pitch given (they are the shared flags; seen, not taken) */
    bool has_fov;                   /* --fov given */
    bool has_size;                  /* --width or --height given */
    bool aovs;                      /* --aovs: a plain sky render also writes the AOV layers */
    aerial_method aerial;           /* --aerial-perspective march|volume|auto (default auto) */
    unsigned ap_size[3];            /* --ap-volume-size WxHxD: froxels (default 32x32x32) */
    double ap_range_km;             /* --ap-volume-range KM (default 32) */
    double ap_distribution;         /* --ap-volume-slices linear|quadratic: 1 or 2 (default quadratic) */
    bool ap_shape_given;            /* any of the three given */
} composite_options;

/* Takes this module's flags (and their values) out of argv, compacting it and updating *argc; notes the shared
 * flags it cares about. 0, or 2 after one line on stderr (bad value, missing value, a flag that needs
 * --composite). */
int composite_options_extract(composite_options *co, int *argc, char **argv);
/* --aerial-perspective auto: the cheapest method of the measured trade (ap_trade_table.h, tools/tradeoff_aerial)
 * whose error is <= --max-error (0: not given -> the march); true with the volume's shape in size/range/slices
 * (only the shape the flags gave, when they gave one). why[why_size] gets the reason, for a note on stderr. */
bool composite_auto_volume(const composite_options *co, double max_error, unsigned size[3], double *range_km,
                           double *distribution, char *why, size_t why_size);
void composite_options_print_help(FILE *out);
#endif
