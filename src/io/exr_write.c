/* vksky image I/O: the RGBA half-float EXR writer of renders. See exr_write.h; the file itself is written by
   exr_layers.c's encode loop, shared with the multilayer writer. */
#include "io/exr_write.h"

#include "io/exr_common.h"
#include "io/io_error.h"

#include <stdlib.h>

int io_write_exr(const char *path, int width, int height, const io_exr_layer *layers, int layer_count, char *err,
                 size_t err_size)
{
    return io_write_exr_meta(path, width, height, layers, layer_count, NULL, err, err_size);
}

int io_write_exr_meta(const char *path, int width, int height, const io_exr_layer *layers, int layer_count,
                      const struct io_exr_meta *meta, char *err, size_t err_size)
{
    /* The encode loop and every check are exr_layers.c's (io_exr_write_layers_half): here only the RGBA half
       layers are described to it. */
    if (!layers || layer_count <= 0 || layer_count > 1000)
        return io_exr_write_layers_half(path, width, height, NULL, layer_count, meta, err, err_size);
    io_exr_write_layer *w = (io_exr_write_layer *)calloc((size_t)layer_count, sizeof *w);
    if (!w) {
        io_set_err(err, err_size, "cannot write '%s': out of memory", io_safe_path(path));
        return -1;
    }
    for (int i = 0; i < layer_count; ++i) w[i] = (io_exr_write_layer){layers[i].name, 4, layers[i].rgba_half, NULL, 0};
    int r = io_exr_write_layers_half(path, width, height, w, layer_count, meta, err, err_size);
    free(w);
    return r;
}

int io_write_exr_rgba_f32(const char *path, int width, int height, const float *rgba, int store_float,
                          const struct io_exr_meta *meta, char *err, size_t err_size)
{
    io_exr_write_layer w = {"", 4, NULL, rgba, store_float};
    return io_exr_write_layers_half(path, width, height, rgba ? &w : NULL, rgba ? 1 : 0, meta, err, err_size);
}
