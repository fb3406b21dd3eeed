/* vksky image I/O: a multilayer EXR for compositing: one part, HALF channels, the compression of --exr-compression
 * (encode_settings.h: ZIP by default), the layers named in
 * the layer.channel convention that Nuke, Blender and OpenImageIO read ("sky.R", "sky.G", ...). Atomic: written to
 * "<dir>/.<basename>.tmp.<pid>" and renamed over `path` only when complete; on failure no file is left at `path`.
 */
#ifndef VKSKY_IO_EXR_LAYERS_H
#define VKSKY_IO_EXR_LAYERS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Named io_exr_out_layer, not io_exr_layer: that name is already the RGBA-half layer of io_write_exr (image_io.h /
   exr_write.h), and a translation unit may include both writers. */
typedef struct io_exr_out_layer {
    const char *name;     /* "" for the top-level R, G, B(, A); else e.g. "sky" -> sky.R, sky.G, sky.B(, sky.A) */
    int channels;         /* 3 (RGB) or 4 (RGBA) */
    const float *pixels;  /* width*height*channels floats, interleaved, top row first; stored as half (finite
                             values beyond +-65504 clamp, inf and NaN stay) */
} io_exr_out_layer;

/* 0 on success; else -1 and one line in err[err_size] (bad size, NULL pixels, a channel count other than 3 or 4,
   an empty or duplicate or over-long layer name, a name with a '.' at either end, an unwritable path). */
int io_write_exr_layers(const char *path, int width, int height, const io_exr_out_layer *layers, int layer_count,
                        char *err, size_t err_size);

/* The same with the header attributes of `meta` (exr_meta.h; NULL: none): every EXR vksky writes says how it was
   made (issue 28). */
struct io_exr_meta;
int io_write_exr_layers_meta(const char *path, int width, int height, const io_exr_out_layer *layers,
                             int layer_count, const struct io_exr_meta *meta, char *err, size_t err_size);

/* The same file written in bands (issue 28: a composite of any height through a band-sized buffer). open writes the
   header (the layers' names and channel counts; their pixels are not read) and returns NULL + err on failure, nothing
   left behind. rows appends the next `rows` rows (`layers` as at open, in the same order, `pixels` pointing at this
   band's first row); every call but the last must bring a multiple of rows_per_chunk rows (the compression's
   io_exr_compression_lines, known before the file is opened). finish renames the file
   into place. On any failure (-1 + err) the stream is gone: nothing at `path`, no temporary. */
typedef struct io_exr_band_layer {
    const char *name;     /* as io_exr_out_layer */
    int channels;         /* 3 or 4 written */
    int stride;           /* floats from one pixel to the next (>= channels: an RGB layer read out of RGBA rows) */
    const float *pixels;  /* rows: the band's first row first */
} io_exr_band_layer;
typedef struct io_exr_layers_stream io_exr_layers_stream;
io_exr_layers_stream *io_exr_layers_stream_open(const char *path, int width, int height,
                                                const io_exr_band_layer *layers, int layer_count,
                                                const struct io_exr_meta *meta, char *err, size_t err_size);
int io_exr_layers_stream_rows_per_chunk(const io_exr_layers_stream *s);
int io_exr_layers_stream_rows(io_exr_layers_stream *s, const io_exr_band_layer *layers, int rows, char *err,
                              size_t err_size);
int io_exr_layers_stream_finish(io_exr_layers_stream *s, char *err, size_t err_size);
void io_exr_layers_stream_abort(io_exr_layers_stream *s);   /* NULL accepted */

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_IO_EXR_LAYERS_H */
