/* The files of a banded render or an environment map (tiles_out.h). */
#include "app/runs/tiles_out.h"
#include "app/runs/exr_header.h"
#include "app/runs/stage_times.h"
#include "app/scene/light.h"
#include "app/cli/options.h"
#include "app/cli/options_projection.h"
#include "sky/projection.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static bool is_exr(const char *path)
{
    size_t n = strlen(path);
    return n > 4 && strcasecmp(path + n - 4, ".exr") == 0;
}

/* Photometric (or --exr-type float): the EXR gets output units as floats (app/scene/light.h), else the half rows as read. */
static bool scaled_rows(const options *o)
{
    return o->units != OPTIONS_UNITS_RELATIVE || o->exr_type == OPTIONS_EXR_FLOAT;
}

/* A band's EXR rows: as read back, or in output units (the HDR scale divided out) through `band_f32` (one band's
 * floats, made once: a 16384-wide band is 128 MB, whose pages a fresh malloc per band would fault in again). */
int write_exr_rows(const options *o, io_exr_stream *s, const uint16_t *half, int rows, float **band_f32,
                   size_t *band_cap, char *err, size_t err_size)
{
    if (!scaled_rows(o)) {
        stage_mark t0 = stage_mark_now();
        int rc = io_exr_stream_rows(s, half, rows, err, err_size);
        stage_add_since(STAGE_WRITE, t0);
        return rc;
    }
    bool unused;
    size_t pixels = (size_t)rows * (size_t)o->width;
    if (pixels > *band_cap) {
        free(*band_f32);
        *band_f32 = malloc(pixels * 4 * sizeof(float));
        *band_cap = *band_f32 ? pixels : 0;
    }
    if (!*band_f32) {
        snprintf(err, err_size, "out of memory for an EXR band");
        io_exr_stream_abort(s);
        return -1;
    }
    stage_mark t0 = stage_mark_now();
    light_exr_pixels_into(o, half, pixels, *band_f32, &unused);
    stage_mark t1 = stage_mark_now();
    stage_add_since(STAGE_CONVERT, t0);
    int rc = io_exr_stream_rows_f32(s, *band_f32, rows, err, err_size);
    stage_add_since(STAGE_WRITE, t1);
    return rc;
}

int open_outputs(const options *o, output *outs)
{
    char err[512];
    int p = o->view.projection;
    io_exr_sky_attrs attrs = {
        .envmap = p == SKY_PROJECTION_EQUIRECT ? IO_ENVMAP_LATLONG : p == SKY_PROJECTION_CUBEMAP ? IO_ENVMAP_CUBE : IO_ENVMAP_NONE,
        .projection = options_projection_name(p)};
    light_sky_attrs(o, &attrs);   /* the sun (direction, illuminance, at the camera) and the units */
    bool scaled = scaled_rows(o), store_float = light_stream_float(o);
    /* Issue 28: the header every EXR of vksky carries; a map's camera matrices would describe no camera. */
    exr_header hdr;
    bool has_hdr = exr_header_build(&hdr, o, -1) == 0;
    if (has_hdr && p != SKY_PROJECTION_PERSPECTIVE) hdr.meta.world_to_camera = hdr.meta.world_to_ndc = NULL;
    attrs.meta = has_hdr ? &hdr.meta : NULL;
    for (int i = 0; i < o->output_count; ++i) {
        outs[i].exr = is_exr(o->outputs[i]);
        if (outs[i].exr)
            outs[i].exr_stream = scaled ? io_exr_stream_open_f32(o->outputs[i], o->width, o->height, &attrs,
                                                                 store_float, err, sizeof err)
                                        : io_exr_stream_open(o->outputs[i], o->width, o->height, &attrs, err, sizeof err);
        else outs[i].png_stream = io_png_stream_open(o->outputs[i], o->width, o->height, err, sizeof err);
        if (!outs[i].exr_stream && !outs[i].png_stream) {
            fprintf(stderr, "vksky: %s\n", err);
            if (has_hdr) exr_header_free(&hdr);
            return 1;
        }
    }
    if (has_hdr) exr_header_free(&hdr);   /* written with each header at open */
    return 0;
}

void abort_outputs(const options *o, output *outs)
{
    for (int i = 0; i < o->output_count; ++i) {
        io_exr_stream_abort(outs[i].exr_stream);
        io_png_stream_abort(outs[i].png_stream);
        outs[i] = (output){0};
    }
}

void tiles_note_render_scale(const options *o)
{
    bool scale_given = false;   /* a note for the user's --render-scale, not for a preset's (--quality auto's) */
    for (int i = 1; i < o->argc; ++i)
        if (!strncmp(o->argv[i], "--render-scale", 14) && (o->argv[i][14] == '\0' || o->argv[i][14] == '='))
            scale_given = true;
    if (o->render_scale != 1.0 && scale_given && !o->quiet)
        fprintf(stderr, "vksky: note: --render-scale %g ignored: banded renders are rendered at full size\n", o->render_scale);
}
