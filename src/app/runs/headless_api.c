/* One headless frame through include/vksky.h (headless_api.h): a perspective frame, or an environment map in one
 * band. The order a host follows (docs/library.md): context, scene, renderer, then per frame: begin its command
 * buffer, vksky_record, end, submit, wait, read. */
#include "app/runs/headless_api.h"
#include "app/runs/tiles_out.h"
#include "app/runs/bench_host.h"
#include "app/runs/sequence_frames.h"
#include "app/runs/sequence_host.h"
#include "app/runs/host_ring.h"
#include "app/runs/spectral_host.h"
#include "app/runs/host_print.h"
#include "app/runs/startup.h"
#include "app/runs/stop.h"
#include "app/runs/tiles.h"
#include "app/scene/light.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Auto exposure's figures, as the command line prints them (the GPU metered the frame that was just rendered). */
static int print_metered(const options *o, const sky_view *view, const vksky_renderer *r)
{
    vksky_exposure e;
    if (vksky_renderer_get_exposure(r, 0, &e) != VKSKY_SUCCESS) return 1;
    if (!o->quiet)
        fprintf(stderr, "vksky: auto exposure: EV100 %.4f (log-average luminance %.6g %s over %.0f pixels, metered on "
                        "the GPU%s)\n", e.ev100, e.log_average, view->ev100 ? "cd/m2" : "(relative units)", e.pixel_count,
                view->projection != VKSKY_PROJECTION_TYPE_PERSPECTIVE ? " in 1 band" : "");
    return 0;
}

/* An environment map's files (app/runs/tiles_out.h: the envmap attributes, streamed as the banded maps are). */
static int write_map(const options *o, const vksky_readback *px)
{
    output outs[OPTIONS_MAX_OUTPUTS] = {0};
    float *rows_f32 = NULL;
    size_t rows_cap = 0;
    char err[512];
    int status = open_outputs(o, outs);
    for (int i = 0; i < o->output_count && status == 0; ++i) {
        int rc = outs[i].exr ? write_exr_rows(o, outs[i].exr_stream, px->linear_rgba16f, o->height, &rows_f32,
                                              &rows_cap, err, sizeof err)
                             : io_png_stream_rows(outs[i].png_stream, px->display_rgba8, o->height, err, sizeof err);
        if (rc == 0) rc = outs[i].exr ? io_exr_stream_finish(outs[i].exr_stream, err, sizeof err)
                                      : io_png_stream_finish(outs[i].png_stream, err, sizeof err);
        outs[i] = (output){0};   /* finished, or aborted by the stream itself */
        if (rc != 0) fprintf(stderr, "vksky: %s\n", err), status = 1;
    }
    free(rows_f32);
    abort_outputs(o, outs);
    return status;
}

static int write_image(const options *o, const vksky_readback *px);

static int render_and_write(const options *o, host_commands *h, vksky_renderer *r)
{
    const sky_view *view = &o->view;
    bool auto_exposure = light_auto_exposure_wanted(o);
    startup_frame_begin();   /* --timings: the first image */
    /* The view as the command line gave it (the sky pass's own rays from yaw, pitch and fov); auto exposure: the GPU
     * meters the frame and its tone map reads the result (slot 0: one frame at a time). An environment map: one band,
     * the whole image, the projection giving each pixel its direction. */
    host_view v = {.yaw_deg = view->yaw_deg, .pitch_deg = view->pitch_deg, .fov_deg = view->fov_deg,
                   .exposure = view->exposure_ev, .auto_exposure = auto_exposure,
                   .projection = (vksky_projection)view->projection, .whole_width = (uint32_t)o->width,
                   .whole_height = (uint32_t)o->height};
    h->frames = host_frames_wanted();   /* the tests' VKSKY_FRAMES loop (host_ring.h) */
    int status = host_commands_render(h, r, &v, o->trace_barriers ? stdout : NULL, NULL);
    if (status == 0 && auto_exposure) status = print_metered(o, view, r);
    /* A LUT cache miss: the LUTs this frame computed, into the cache for the next start (a hit or none: nothing). */
    if (status == 0 && vksky_renderer_store_luts(r) != VKSKY_SUCCESS) status = 1;
    if (status == 0 && o->timings) host_timings_frame_end(r);
    vksky_readback px;
    if (status != 0 || vksky_renderer_get_readback(r, &px) != VKSKY_SUCCESS) return 1;
    return write_image(o, &px);
}

static int write_image(const options *o, const vksky_readback *px)
{
    /* A map stopped (Ctrl-C, TERM) while it rendered: no file, as a banded render stops (stop_status says so). */
    int rc;
    if (o->view.projection != VKSKY_PROJECTION_TYPE_PERSPECTIVE) {
        rc = stop_requested() ? 1 : write_map(o, px);
    } else {
        frame_ring_pixels pixels = {px->linear_rgba16f, px->display_rgba8};
        rc = sequence_write_frame(o, &pixels, o->frame_first, false);
    }
    startup_outputs_done();   /* --timings: the files are done; what follows is teardown */
    return rc;
}

/* --spectral N of one image: the wavelength groups rendered and summed on the host (app/runs/spectral_host.c). */
static int render_spectral(const options *o, vksky_context *ctx, const vksky_scene *scene, host_commands *h)
{
    spectral_image img;
    int status = spectral_host_render(o, ctx, scene, h, &img);
    if (status == 0) {
        vksky_readback px = {.linear_rgba16f = img.linear, .display_rgba8 = img.display, .width = (uint32_t)o->width,
                             .height = (uint32_t)o->height};
        status = write_image(o, &px);
    }
    spectral_image_release(&img);
    return status;
}

int headless_api_render(const options *o, vksky_context *ctx, uint32_t compute_queue_index)
{
    vksky_scene *scene = NULL;
    vksky_renderer *r = NULL;
    int status = 1;
    host_commands h = {0};
    host_async async = {0};
    /* The command line's scene, view and quality (flags over a --scene file), parsed again by the API's loader:
     * the same parser, so the same values. */
    /* A map, or an image in several bands (app/runs/tiles.c), is drawn at full size (a band's rows are its own): the
     * command line, at scale 1. */
    bool is_map = o->view.projection != VKSKY_PROJECTION_TYPE_PERSPECTIVE;
    bool banded = o->bench_frames == 0 && tiles_in_bands(o);
    char **argv = malloc(((size_t)o->argc + 2) * sizeof *argv);
    if (!argv) goto done;
    int argc = o->argc;
    memcpy(argv, o->argv, (size_t)argc * sizeof *argv);
    if (is_map || banded) {
        tiles_begin_notes(o);
        argv[argc++] = "--render-scale=1";
    }
    argv[argc] = NULL;
    vksky_result made = vksky_scene_from_args(argc, argv, host_print_message, NULL, &scene);
    free(argv);
    if (made != VKSKY_SUCCESS) goto done;
    if (o->spectral) {   /* a renderer per wavelength group (app/runs/spectral_host.c), none of the RGB medium */
        /* --async-luts: the groups' LUT passes on the compute queue (app/runs/host_async.h), as for an RGB frame. */
        status = host_commands_create(&h, ctx);
        if (status == 0 && o->async_luts) {
            status = host_async_create(&async, ctx, compute_queue_index, o->trace_barriers ? stdout : NULL);
            h.async = status == 0 ? &async : NULL;
        }
        if (status == 0)
            status = stop_requested()                               ? 0
                     : sequence_active(o) || o->skip_existing       ? spectral_host_sequence(o, ctx, scene, &h)
                     : banded                                       ? spectral_host_bands(o, ctx, scene, &h)
                                                                    : render_spectral(o, ctx, scene, &h);
        goto done;
    }
    vksky_readback_config readback = {.type = VKSKY_STRUCTURE_TYPE_READBACK_CONFIG};
    /* --bench without outputs: no readback, the frame writes the host's own image (app/runs/bench_host.c), a UNORM
     * storage image the compute tone map writes where the post chain is compute. */
    vksky_display_config bench_display = BENCH_DISPLAY_CONFIG;
    vksky_renderer_desc rd = {
        .abi_version = VKSKY_ABI_VERSION, .next = o->output_count > 0 ? (const void *)&readback : &bench_display,
        .output = VKSKY_OUTPUT_DISPLAY,
        .width = (uint32_t)o->width, .height = (uint32_t)(banded ? tiles_frame_rows(o) : o->height),
        .target_format = o->output_count > 0 ? VK_FORMAT_R8G8B8A8_SRGB : BENCH_TARGET_FORMAT, .quality = "scene",
        .bloom = o->view.bloom && !banded,
        .units = o->units == OPTIONS_UNITS_RELATIVE ? VKSKY_UNITS_RELATIVE : VKSKY_UNITS_PHOTOMETRIC, .scene = scene};
    if (vksky_renderer_create(ctx, &rd, &r) != VKSKY_SUCCESS) goto done;
    if (o->trace_passes)
        vksky_context_set_trace(ctx, (o->trace_barriers ? VKSKY_TRACE_BARRIERS : 0u) | VKSKY_TRACE_PASSES,
                                host_print_trace, NULL);
    if (host_commands_create(&h, ctx)) goto done;
    /* --async-luts: the LUT passes on the compute queue the device was made with (app/runs/host_async.h). */
    if (o->async_luts) {
        if (host_async_create(&async, ctx, compute_queue_index, o->trace_barriers ? stdout : NULL)) goto done;
        h.async = &async;
    }
    /* Stopped while the device and the renderer were made: nothing to render (stop_status says why). */
    /* A sequence (or --skip-existing): the frames through the host's readback ring or one at a time
     * (app/runs/sequence_host.c); an image in several bands, band by band (app/runs/tiles.c); else the one frame. */
    if (stop_requested()) {
        status = 0;
    } else if (o->bench_frames > 0) {
        /* --bench: no barrier trace over its frames (the pass trace stays, as the CLI's own bench keeps it). */
        vksky_context_set_trace(ctx, o->trace_passes ? VKSKY_TRACE_PASSES : 0u, host_print_trace, NULL);
        status = bench_host_run(o, ctx, scene, r, h.async);
    } else if (banded) {
        status = tiles_render(o, ctx, r, &h, o->trace_barriers ? stdout : NULL);
    } else if (sequence_active(o) || o->skip_existing)
        status = sequence_host_render(o, ctx, scene, r, h.async, o->trace_barriers ? stdout : NULL);
    else status = render_and_write(o, &h, r);
done:
    if (startup_keep_for_exit(o, status)) return status;   /* one image, validation off: the exit frees it (startup.h) */
    host_commands_destroy(&h);
    host_async_destroy(&async);
    vksky_renderer_destroy(r);
    vksky_scene_destroy(scene);
    return status;
}
