/* vksky image I/O: reading EXRs written by other programs (Blender, Nuke, renderers): untrusted input. OpenEXRCore
 * (the C API of OpenEXR 3.1) only. Every size in the file is validated before anything is allocated; a bad file
 * gives a nonzero return and one human line in err ("FILE: not an OpenEXR file", "FILE: truncated chunk ...")
 * naming what is wrong and, where it helps, what is accepted. Nothing here crashes or leaks on any input.
 */
#ifndef VKSKY_IO_EXR_READ_H
#define VKSKY_IO_EXR_READ_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The largest data window accepted: each side at most IO_EXR_READ_MAX_SIDE pixels and the area at most
   IO_EXR_READ_MAX_PIXELS (2^28 pixels, 1 GiB per float channel), so a hostile header cannot make the caller
   allocate more than that per channel. */
#define IO_EXR_READ_MAX_SIDE 65536
#define IO_EXR_READ_MAX_PIXELS (1LL << 28)

typedef struct io_exr_channel {
    char *name;     /* the full name as stored: "R", "ViewLayer.Combined.R", "Position.X" */
    int part;       /* index of the part holding it (0 for single-part files) */
    int pixel_type; /* EXR_PIXEL_UINT (0), EXR_PIXEL_HALF (1) or EXR_PIXEL_FLOAT (2), as in openexr.h */
} io_exr_channel;

typedef struct io_exr_info {
    int width, height;         /* data window size of part 0; io_exr_read_channels needs every part it reads from
                                  to have this size (Blender's multi-part files always do) */
    int part_count;            /* parts in the file */
    int channel_count;         /* every channel of every part, in part then file (alphabetical) order */
    io_exr_channel *channels;
    /* The standard camera attributes (worldToCamera, worldToNDC: M44f, row-major as stored, row-vector convention
       p' = p * M) from part 0, else from the first part that has them. */
    int has_world_to_camera, has_world_to_ndc;
    float world_to_camera[16], world_to_ndc[16];
} io_exr_info;

/* Reads the header(s) of `path`. 0 on success (free with io_exr_info_free); else nonzero, *info zeroed, and one
   human line in err[err_size] (err may be NULL). */
int io_exr_read_info(const char *path, io_exr_info *info, char *err, size_t err_size);
void io_exr_info_free(io_exr_info *info); /* frees the channel list and zeroes *info; NULL and zeroed are fine */

/* Reads the named channels (any part; HALF, FLOAT or UINT; scanline or tiled (level 0); any compression OpenEXR 3.1
   decodes) as float, `count` interleaved values per pixel in the order of `names`, row 0 = top of the data window.
   `out` must hold width*height*count floats (width, height as io_exr_read_info reports). A name that is missing
   (the message lists what the file has), a part of another size, a deep or subsampled channel, a compression 3.1
   cannot decode, a truncated or corrupt chunk: nonzero and one line in err; `out` is then unspecified. */
int io_exr_read_channels(const char *path, const char *const *names, int count, float *out, char *err,
                         size_t err_size);

/* io_exr_read_channels for rows [row0, row0 + rows) of the data window only (a band of a large image: only the chunks
   that hold them are decoded); `out` holds width*rows*count floats, its row 0 = row row0. */
int io_exr_read_rows(const char *path, const char *const *names, int count, int row0, int rows, float *out, char *err,
                     size_t err_size);

/* Readers for tests/tools: read layer `layer_name` ("" = default R,G,B,A; a missing A reads as 1) from an EXR (any
   compression OpenEXRCore supports, HALF or FLOAT channels, scanline or tiled (level 0) parts, first part that has
   the layer) into a malloc'd float RGBA array (interleaved, row-major, top row of the data window first; free() it).
   Channels are matched by name. R, G and B must exist. Errors follow io_error.h ("cannot read 'PATH': ..."). */
int io_read_exr(const char *path, const char *layer_name, int *width, int *height, float **rgba, char *err,
                size_t err_size);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_IO_EXR_READ_H */
