/* vksky image I/O: io_read_exr, the RGBA layer reader of tests and tools, on top of the general reader
   (exr_read_info.c, exr_read_pixels.c: every size checked, any part, HALF/FLOAT/UINT, scanline or tiled). */
#include "io/exr_read.h"

#include "io/exr_common.h"
#include "io/io_error.h"

#include <stdlib.h>
#include <string.h>

int io_read_exr(const char *path, const char *layer_name, int *width, int *height, float **rgba, char *err,
                size_t err_size)
{
    const char *p = io_safe_path(path);
    if (rgba) *rgba = NULL;
    if (width) *width = 0;
    if (height) *height = 0;
    if (!width || !height || !rgba) {
        io_set_err(err, err_size, "cannot read '%s': NULL output argument", p);
        return -1;
    }
    if (!layer_name) layer_name = "";
    if (strlen(layer_name) > IO_EXR_MAX_LAYER_NAME) {
        io_set_err(err, err_size, "cannot read '%s': layer name too long", p);
        return -1;
    }
    char names[4][IO_EXR_MAX_LAYER_NAME + 8];
    const char *np[4] = {names[0], names[1], names[2], names[3]};
    for (int c = 0; c < 4; ++c) io_exr_channel_name(names[c], sizeof names[c], layer_name, c);

    io_exr_info info;
    if (io_exr_read_info(path, &info, err, err_size) != 0) return -1;
    int have = 0;
    for (int i = 0; i < info.channel_count; ++i) {
        for (int c = 0; c < 4; ++c) have |= (strcmp(info.channels[i].name, names[c]) == 0) << c;
    }
    int w = info.width, h = info.height;
    io_exr_info_free(&info);
    if ((have & 7) != 7) {
        io_set_err(err, err_size, "cannot read '%s': no layer '%s' (channels %s, %s, %s)", p, layer_name, names[0],
                   names[1], names[2]);
        return -1;
    }
    int count = (have & 8) ? 4 : 3;
    float *buf = (float *)malloc((size_t)w * (size_t)h * 4u * sizeof(float));
    if (!buf) {
        io_set_err(err, err_size, "cannot read '%s': out of memory for %dx%d image", p, w, h);
        return -1;
    }
    if (io_exr_read_channels(path, np, count, buf, err, err_size) != 0) {
        free(buf);
        return -1;
    }
    if (count == 3) { /* spread RGB to RGBA from the back, A = 1 */
        for (size_t i = (size_t)w * (size_t)h; i-- > 0;) {
            buf[4 * i + 3] = 1.0f;
            for (int c = 2; c >= 0; --c) buf[4 * i + (size_t)c] = buf[3 * i + (size_t)c];
        }
    }
    *width = w;
    *height = h;
    *rgba = buf;
    return 0;
}
