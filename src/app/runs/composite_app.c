/* The composite driver: read the render (io/exr_read.h), find its layers, place the camera, run the composite
 * pass through include/vksky.h (vksky_composite_*: this file is a host of the API, no src/sky or src/lib header),
 * write the composite and its AOV layers (io/exr_layers.h). Every bad input is one line on stderr and exit status 2,
 * before any output file exists. */
#include "app/runs/composite_app.h"
#include "app/runs/composite_bands.h"
#include "app/runs/composite_camera.h"
#include "app/runs/composite_layers.h"
#include "app/runs/composite_spectral.h"
#include "app/runs/exr_header.h"
#include "app/runs/host_async.h"
#include "app/runs/host_device.h"
#include "app/runs/host_print.h"
#include "app/runs/host_ring.h"
#include "app/runs/spectral_host.h"
#include "app/runs/stage_times.h"
#include "app/runs/startup.h"
#include "app/runs/stop.h"
#include "app/scene/light.h"
#include "io/exr_layers.h"
#include "io/exr_read.h"
#include "io/atomic_file.h"
#include "io/exr_write.h"
#include "io/half_float.h"
#include "io/png_io.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const char *const AOV_NAMES[VKSKY_COMPOSITE_LAYERS] = {"", "sky", "sun_disk", "transmittance", "rayleigh", "mie"};

/* --- Running the pass -------------------------------------------------------------------------------------- */

static int frames_from_env(void)
{
    const char *env = getenv("VKSKY_FRAMES");
    return env ? atoi(env) : 1;
}

/* The device (app/runs/host_device.h), the command line's scene (its flags, parsed again by the API's loader: the same
 * parser, the same values; `extra` appended), and a renderer in the lesson's units (docs/units.md: the medium as given,
 * the disc unpowered): DISPLAY of width x height read back (--aovs: the sky frame), or LUTS_ONLY (the composite: its
 * images are not used). The host's command buffer, and --async-luts' compute queue (app/runs/host_async.h). */
typedef struct composite_gpu {
    host_device *dev;
    vksky_context *ctx;
    vksky_scene *scene;
    vksky_renderer *r;
    host_commands h[2];           /* [1]: the second slot's, for a ring of bands (made by composite_run) */
    host_async async;
    bool timings;                 /* --timings: the report after the teardown (startup.h) */
} composite_gpu;

static void gpu_release(composite_gpu *g)
{
    host_commands_destroy(&g->h[0]);
    host_commands_destroy(&g->h[1]);
    host_async_destroy(&g->async);
    vksky_renderer_destroy(g->r);
    vksky_scene_destroy(g->scene);
    g->r = NULL, g->scene = NULL;
}

static int gpu_end(composite_gpu *g, int status)
{
    gpu_release(g);
    return host_device_close(g->dev, g->ctx, status, (host_device_end){.timings = g->timings});
}

/* The command line's scene (`render_scale_1`: with --render-scale=1 appended). 0, or 1 (the line printed). The
 * loader parses the flags again with the command line's own parser, which holds stdout and stderr while it runs: made
 * before any other thread of the run prints. */
static int scene_of(const options *o, bool render_scale_1, vksky_scene **out)
{
    char **argv = malloc(((size_t)o->argc + 2) * sizeof *argv);
    if (!argv) return 1;
    int argc = o->argc;
    memcpy(argv, o->argv, (size_t)argc * sizeof *argv);
    if (render_scale_1) argv[argc++] = "--render-scale=1";   /* the LUTs only: the sky at full scale, as before */
    argv[argc] = NULL;
    vksky_result made = vksky_scene_from_args(argc, argv, host_print_message, NULL, out);
    free(argv);
    return made == VKSKY_SUCCESS ? 0 : 1;
}

/* `scene`: the command line's, made by the caller (taken over), or NULL: made here. */
static int gpu_begin(const options *o, composite_gpu *g, vksky_scene *scene, uint32_t width, uint32_t height,
                     bool readback)
{
    *g = (composite_gpu){.scene = scene, .timings = o->timings};
    uint32_t compute_index = 0;
    int rc = host_device_open(o, &g->dev, &g->ctx, &compute_index);
    if (rc != 0) {
        vksky_scene_destroy(g->scene);
        return rc;
    }
    if (!g->scene && scene_of(o, !readback, &g->scene) != 0) return gpu_end(g, 1);
    vksky_readback_config rb = {.type = VKSKY_STRUCTURE_TYPE_READBACK_CONFIG};
    vksky_renderer_desc rd = {.abi_version = VKSKY_ABI_VERSION, .next = readback ? &rb : NULL,
                              .output = readback ? VKSKY_OUTPUT_DISPLAY : VKSKY_OUTPUT_LUTS_ONLY, .width = width,
                              .height = height, .target_format = VK_FORMAT_R8G8B8A8_SRGB, .quality = "scene",
                              .bloom = readback && o->view.bloom, .units = VKSKY_UNITS_RELATIVE, .scene = g->scene};
    if (vksky_renderer_create(g->ctx, &rd, &g->r) != VKSKY_SUCCESS) return gpu_end(g, 1);
    if (o->trace_passes)
        vksky_context_set_trace(g->ctx, (o->trace_barriers ? VKSKY_TRACE_BARRIERS : 0u) | VKSKY_TRACE_PASSES,
                                host_print_trace, NULL);
    if (host_commands_create(&g->h[0], g->ctx) != 0) return gpu_end(g, 1);
    if (o->async_luts) {
        if (host_async_create(&g->async, g->ctx, compute_index, o->trace_barriers ? stdout : NULL) != 0)
            return gpu_end(g, 1);
        g->h[0].async = &g->async;
    }
    return 0;
}

/* The composite RGBA at the top level (or `top` when given), the AOVs as RGB layers (io/exr_layers.h: half, the
 * layer.channel names). */
static int write_layers(const char *path, const float *const *aov, int w, int h, const float *top,
                        const io_exr_meta *meta, char *err, size_t err_size)
{
    size_t n = (size_t)w * h;
    float *rgb = malloc(n * 3 * sizeof(float) * (VKSKY_COMPOSITE_LAYERS - 1));
    if (!rgb) {
        snprintf(err, err_size, "out of memory");
        return -1;
    }
    io_exr_out_layer layers[VKSKY_COMPOSITE_LAYERS];
    layers[0] = (io_exr_out_layer){"", 4, top ? top : aov[0]};
    for (uint32_t k = 1; k < VKSKY_COMPOSITE_LAYERS; ++k) {
        float *dst = rgb + (size_t)(k - 1) * 3 * n;
        const float *src = aov[k];
        for (size_t i = 0; i < n; ++i)
            for (int ch = 0; ch < 3; ++ch) dst[3 * i + ch] = src[4 * i + ch];
        layers[k] = (io_exr_out_layer){AOV_NAMES[k], 3, dst};
    }
    int rc = io_write_exr_layers_meta(path, w, h, layers, VKSKY_COMPOSITE_LAYERS, meta, err, err_size);
    free(rgb);
    return rc;
}

static composite_view view_from_options(const options *o)
{
    return (composite_view){.km_per_unit = 0.001, .up_axis = 2, .fov_y_deg = o->view.fov_deg,
                            .sun_azimuth_deg = o->view.sun_azimuth_deg, .sun_elevation_deg = o->view.sun_elevation_deg,
                            .steps = o->view.steps, .max_steps = o->view.max_steps,
                            .steps_ramp_km = o->view.steps_ramp_km, .sample_offset = o->view.sample_offset,
                            .step_distribution = o->view.step_distribution};
}

/* The options that describe the composite's sky as a plain render (its header's vksky:scene, so that `vksky --scene
 * OUT.exr` renders the sky of its uncovered pixels): the camera's altitude, and its direction as yaw/pitch in vksky's
 * local frame (a camera's roll is not a scene value: it is lost), its field of view and the image's size. */
static options composite_scene(const options *o, const composite_options *co, const composite_view *v,
                               double altitude_km, int width, int height)
{
    options s = *o;
    if (co->argv_all) s.argc = co->argc_all, s.argv = co->argv_all;
    s.width = width, s.height = height;
    s.view.altitude_km = altitude_km;
    if (v->oriented) {
        double f[3];
        vksky_composite_world_to_local(v->up_axis, v->forward, f);
        s.view.pitch_deg = asin(fmax(-1.0, fmin(1.0, f[1]))) * 180.0 / 3.14159265358979323846;
        s.view.yaw_deg = atan2(f[2], f[0]) * 180.0 / 3.14159265358979323846;
        s.view.fov_deg = v->fov_y_deg;
    }
    return s;
}

static bool is_exr(const char *path)
{
    size_t n = strlen(path);
    return n > 4 && strcasecmp(path + n - 4, ".exr") == 0;
}

/* The froxel volume's shape for --aerial-perspective (volume, or auto when --max-error allows it) into d, or d->volume
 * false: a march per pixel. -1 (after one line on stderr): volume asked for without a known camera orientation. */
static int pick_volume(const options *o, const composite_options *co, bool oriented, vksky_composite_desc *d)
{
    d->volume = false;
    char why[300] = "";
    unsigned size[3] = {co->ap_size[0], co->ap_size[1], co->ap_size[2]};
    double range = co->ap_range_km, distribution = co->ap_distribution;
    bool want = co->aerial == AERIAL_VOLUME ||
                (co->aerial == AERIAL_AUTO && composite_auto_volume(co, o->max_error, size, &range, &distribution,
                                                                    why, sizeof why));
    if (want && !oriented) {
        if (co->aerial == AERIAL_VOLUME) {
            fprintf(stderr, "vksky: --aerial-perspective volume: the froxel volume covers the camera's frustum, whose "
                            "orientation is unknown (no worldToCamera, no --yaw/--pitch); give it, or use march\n");
            return -1;
        }
        want = false;
        snprintf(why, sizeof why, "the camera's orientation is unknown: the march");
    }
    if (co->aerial == AERIAL_AUTO && o->max_error > 0.0) fprintf(stderr, "vksky: --aerial-perspective auto: %s\n", why);
    if (!want) return 0;
    d->volume = true;
    for (int k = 0; k < 3; ++k) d->volume_size[k] = size[k];
    /* The float values the pass takes (the froxel volume's shape is single precision on the GPU). */
    d->volume_range_km = (float)range, d->volume_distribution = (float)distribution;
    return 0;
}

/* The notes of a composite that succeeded (its inputs' counts, band_reader: read once, as they were composited). */
static void print_notes(const band_reader *r, bool oriented)
{
    if (r->fix.overflowed)
        fprintf(stderr, "vksky: --composite: note: %zu positions overflowed the half-float range (beyond 65504 world "
                        "units) and have no atmosphere: write the Position pass as float (Blender: Output > Float "
                        "(Full))\n", r->fix.overflowed);
    if (r->fix.repaired || r->fix.unrepaired)
        fprintf(stderr, "vksky: --composite: note: %zu edge pixels without a position took their nearest covered "
                        "neighbour's%s\n", r->fix.repaired, r->fix.unrepaired ? "; some found none (composited without "
                        "atmosphere)" : "");
    if (!oriented && r->sky > 0)
        fprintf(stderr, "vksky: --composite: the camera's orientation is unknown (no worldToCamera, no --yaw/--pitch): "
                        "%zu pixels without geometry keep the beauty\n", r->sky);
}

/* The spectral composite's bands (composite_spectral.h) into out_path: the same stream, layers and header as the RGB
 * composite's. 0, or 1 after one line on stderr. */
static int spectral_bands(const options *o, composite_gpu *g, band_reader *reader, const vksky_composite_desc *cdesc,
                          const composite_view *v, int w, int h, const io_exr_meta *meta, const char *out_path)
{
    char err[600];
    io_exr_band_layer layers[VKSKY_COMPOSITE_LAYERS];
    for (uint32_t k = 0; k < VKSKY_COMPOSITE_LAYERS; ++k)
        layers[k] = (io_exr_band_layer){AOV_NAMES[k], k == 0 ? 4 : 3, 4, NULL};
    io_exr_layers_stream *out = io_exr_layers_stream_open(out_path, w, h, layers, VKSKY_COMPOSITE_LAYERS, meta, err,
                                                          sizeof err);
    if (!out) {
        fprintf(stderr, "vksky: --render: %s\n", err);
        return 1;
    }
    if (composite_spectral_bands(reader, &g->h[0], g->ctx, g->scene, o->spectral, cdesc, v,
                                 o->trace_barriers ? stdout : NULL, out) != 0)
        return 1;
    if (io_exr_layers_stream_finish(out, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: --render: %s\n", err);
        return 1;
    }
    return 0;
}

int composite_run(const options *o, const composite_options *co)
{
    char err[600];
    if (o->output_count != 1 || !is_exr(o->outputs[0])) {
        fprintf(stderr, "vksky: --composite: needs exactly one --render FILE.exr (the composite and its layers)\n");
        return 2;
    }
    const char *out_path = o->outputs[0];
    if (io_check_writable(out_path, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: --render: %s\n", err);
        return 2;
    }
    /* The files and their layers (app/runs/composite_layers.c: one view layer for all of them). */
    const char *beauty_path = co->input;
    io_exr_info bi = {0}, pi = {0}, di = {0};
    if (io_exr_read_info(beauty_path, &bi, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: --composite: %s\n", err);
        return 2;
    }
    int status = 0;
    const char *extra_flag = co->depth ? "--depth" : "--position", *extra_path = co->depth ? co->depth : co->position;
    io_exr_info *extra = co->depth ? &di : &pi;
    if (extra_path && io_exr_read_info(extra_path, extra, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: %s: %s\n", extra_flag, err);
        io_exr_info_free(&bi);
        return 2;
    }
    composite_inputs inputs;
    if (composite_pick_inputs(co, &bi, &pi, &di, &inputs) != 0) {
        status = 2;
        goto done_info;
    }
    if (extra_path && (extra->width != bi.width || extra->height != bi.height)) {
        fprintf(stderr, "vksky: %s: %s is %dx%d but the beauty %s is %dx%d; they must be the same size\n", extra_flag,
                extra_path, extra->width, extra->height, beauty_path, bi.width, bi.height);
        status = 2;
        goto done_info;
    }
    const io_exr_info *pinfo = co->position ? &pi : &bi;
    int w = bi.width, h = bi.height;

    /* The camera: --camera-position and --yaw/--pitch, else the EXR's worldToCamera (and worldToNDC). */
    composite_view v = view_from_options(o);
    v.km_per_unit = co->world_unit_m * 1e-3;
    v.up_axis = co->up_axis;
    v.ground_altitude_km = co->ground_altitude_km;
    const io_exr_info *cam_info = bi.has_world_to_camera ? &bi : pinfo->has_world_to_camera ? pinfo : NULL;
    double matrix_fov = 0.0;
    bool from_matrix = cam_info && camera_from_matrices(cam_info, &v, &matrix_fov);
    if (co->has_camera_position) memcpy(v.camera, co->camera_position, sizeof v.camera);
    if (!from_matrix && !co->has_camera_position) {
        fprintf(stderr, "vksky: --composite: %s has no worldToCamera attribute: give --camera-position X,Y,Z (world "
                        "units) and --yaw/--pitch/--fov for its orientation\n", beauty_path);
        status = 2;
        goto done_info;
    }
    if (co->has_orientation) {
        vksky_composite_view_orient(&v, o->view.yaw_deg, o->view.pitch_deg);
        if (!co->has_fov && !(from_matrix && matrix_fov > 0.0))
            fprintf(stderr, "vksky: --composite: no --fov given: the sky pixels assume %g degrees (vertical); give the "
                            "render's field of view\n", o->view.fov_deg);
        else if (!co->has_fov)
            v.fov_y_deg = matrix_fov;
    } else if (from_matrix && (matrix_fov > 0.0 || co->has_fov)) {
        v.oriented = true;
        if (!co->has_fov) v.fov_y_deg = matrix_fov;
    }

    vksky_composite_desc cdesc = {.abi_version = VKSKY_ABI_VERSION, .width = (uint32_t)w};
    if (pick_volume(o, co, v.oriented, &cdesc) != 0) {
        status = 2;
        goto done_info;
    }
    if (inputs.has_depth && !v.oriented) {
        fprintf(stderr, "vksky: --composite: a depth pass needs the camera's orientation and field of view (no "
                        "worldToCamera/worldToNDC in %s): give --yaw/--pitch/--fov\n", beauty_path);
        status = 2;
        goto done_info;
    }
    /* The camera's altitude over the command line's planet (the scene: a value, no device yet). */
    vksky_scene *planet = NULL;
    if (scene_of(o, true, &planet) != 0) {
        status = 1;
        goto done_info;
    }
    double altitude = vksky_composite_view_altitude(&v, planet);
    /* The inputs in bands (app/runs/composite_bands.h), read once: each band is checked as it is composited (an
     * opaque film stops the run at the band that shows it, no geometry at all at the end: exit 2 with one line, the
     * output's temporary removed, nothing at its path) and its counts kept for the notes (issue 28 item 6: a check
     * pass of its own decoded the inputs twice). A camera inside the planet starts no device. */
    if (altitude < 0.0) {
        fprintf(stderr, "vksky: --composite: the camera (%g, %g, %g world units) is inside the planet (%.4g km below "
                        "the ground); check --world-up, --world-unit, --ground-altitude\n",
                v.camera[0], v.camera[1], v.camera[2], -altitude);
        vksky_scene_destroy(planet);
        status = 2;
        goto done_info;
    }
    int band_rows = composite_band_rows(w, h);
    band_reader reader;
    if ((status = band_reader_init(&reader, beauty_path, &inputs, &v, w, h, band_rows)) != 0) {
        vksky_scene_destroy(planet);
        goto done_info;
    }
    composite_gpu g = {0};
    bool started = false;
    stage_mark setup = stage_mark_now();
    if ((status = gpu_begin(o, &g, planet, 1, 1, false)) != 0) goto done_checked;   /* the device's line printed */
    started = true;
    composite_start_times start = {.setup_wall_ms = stage_mark_now().wall_ms - setup.wall_ms};

    /* The header: how it was made, and the scene of its sky (`vksky --scene OUT.exr`). */
    exr_header hdr;
    options scene = composite_scene(o, co, &v, altitude, w, h);
    if (exr_header_build(&hdr, &scene, -1) != 0) {
        fprintf(stderr, "vksky: --composite: out of memory\n");
        status = 1;
        goto done_checked;
    }
    /* The render's own camera matrices (its world, its units: the position pass's) where it had them. */
    if (cam_info) {
        memcpy(hdr.world_to_camera, cam_info->world_to_camera, sizeof hdr.world_to_camera);
        if (cam_info->has_world_to_ndc) memcpy(hdr.world_to_ndc, cam_info->world_to_ndc, sizeof hdr.world_to_ndc);
    }
    if (!v.oriented) hdr.meta.world_to_camera = hdr.meta.world_to_ndc = NULL;

    vksky_composite *c = NULL;
    cdesc.rows = (uint32_t)band_rows;
    if (o->spectral) {   /* --spectral N: a composite pass per group of three wavelengths (composite_spectral.h) */
        status = gpu_end(&g, spectral_bands(o, &g, &reader, &cdesc, &v, w, h, &hdr.meta, out_path));
        if (status == 0) print_notes(&reader, v.oriented);
        started = false;
        goto done_header;
    }
    /* Two slots, a ring of bands (composite_bands.h), where there are several bands of one frame each and no
     * --async-luts; VKSKY_COMPOSITE_SLOTS=1: one band at a time. */
    const char *slots_env = getenv("VKSKY_COMPOSITE_SLOTS");
    int slots = band_rows < h && frames_from_env() <= 1 && !o->async_luts && !(slots_env && atoi(slots_env) == 1) ? 2 : 1;
    if (slots == 2 && host_commands_create(&g.h[1], g.ctx) != 0) slots = 1;
    cdesc.slots = (uint32_t)slots;
    if (vksky_composite_create(g.r, &cdesc, &c) != VKSKY_SUCCESS) {
        status = gpu_end(&g, 2);   /* the band is too large for the device's images (the line printed) */
        started = false;
        goto done_header;
    }
    /* The segments' steps by length, the sky by tiles (docs/aerial_perspective.md). */
    if (vksky_composite_set_view(c, &v, (uint32_t)h, VKSKY_COMPOSITE_FAST, NULL) != VKSKY_SUCCESS) status = 1;
    if (status == 0 && o->bench_frames > 0) {   /* the first band (the whole image up to 2^18 pixels) */
        if ((status = band_reader_read(&reader, 0)) == 0) {
            band_reader_upload(&reader, vksky_composite_inputs(c, 0), band_rows);
            composite_bench(&g.h[0], g.r, c, cdesc.volume, (uint32_t)w, (uint32_t)band_rows, o->bench_frames,
                            o->trace_barriers ? stdout : NULL);
        }
        reader.fix = (composite_fixups){0}, reader.geometry = reader.sky = 0;   /* counted again below */
    }
    static const char *const names[VKSKY_COMPOSITE_LAYERS] = {"", "sky", "sun_disk", "transmittance", "rayleigh",
                                                              "mie"};
    io_exr_band_layer layers[VKSKY_COMPOSITE_LAYERS];
    for (uint32_t k = 0; k < VKSKY_COMPOSITE_LAYERS; ++k)
        layers[k] = (io_exr_band_layer){names[k], k == 0 ? 4 : 3, 4, NULL};
    io_exr_layers_stream *out = status ? NULL : io_exr_layers_stream_open(out_path, w, h, layers,
                                                                         VKSKY_COMPOSITE_LAYERS, &hdr.meta, err,
                                                                         sizeof err);
    if (!status && !out) {
        fprintf(stderr, "vksky: --render: %s\n", err);
        status = 1;
    }
    stage_begin();
    if (out && (status = composite_bands_render(&reader, g.h, slots, g.r, c, frames_from_env(),
                                                o->trace_barriers ? stdout : NULL, out)) == 0 &&
        io_exr_layers_stream_finish(out, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: --render: %s\n", err);
        status = 1;
    }
    /* The LUTs the first band computed into the LUT cache (the bands are done: nothing in flight), as a still's are:
     * the next composite of the medium, a sequence's next frame, uploads them. Nothing on a hit or with no cache. */
    if (status == 0 && vksky_renderer_store_luts(g.r) != VKSKY_SUCCESS) status = 1;
    if (status == 0) print_notes(&reader, v.oriented);
    if (status == 0 && o->timings) composite_timings_report(stderr, &reader, &start);
    vksky_composite_destroy(c);
    status = gpu_end(&g, status);
    started = false;
done_header:
    exr_header_free(&hdr);
done_checked:
    if (started) status = gpu_end(&g, status);
    band_reader_free(&reader);
done_info:
    io_exr_info_free(&bi);
    io_exr_info_free(&pi);
    io_exr_info_free(&di);
    return status;
}

int composite_aovs_run(const options *o, const composite_options *co)
{
    char err[600];
    bool any_exr = false;
    for (int i = 0; i < o->output_count; ++i) {
        if (io_check_writable(o->outputs[i], err, sizeof err) != 0) {
            fprintf(stderr, "vksky: --render: %s\n", err);
            return 2;
        }
        any_exr = any_exr || is_exr(o->outputs[i]);
    }
    if (!any_exr || o->bench_frames) {
        fprintf(stderr, "vksky: --aovs: needs --render FILE.exr (the layers are EXR layers; not with --bench)\n");
        return 2;
    }
    composite_gpu g;
    int status = gpu_begin(o, &g, NULL, (uint32_t)o->width, (uint32_t)o->height, true);
    if (status) return status;
    FILE *trace = o->trace_barriers ? stdout : NULL;
    /* The layers: the composite pass over a frame with no geometry, the camera the view's (at the world origin,
     * +Y up, km), its altitude exactly the sky pass's. The volume only with --aerial-perspective volume: there is no
     * geometry to sample it, but the frame is the composite's with the volume pass in it (barrier tests,
     * docs/synchronization.md). */
    composite_view v = view_from_options(o);
    v.km_per_unit = 1.0, v.up_axis = 1;
    v.camera[1] = o->view.altitude_km;
    v.altitude_km = o->view.altitude_km;
    vksky_composite_view_orient(&v, o->view.yaw_deg, o->view.pitch_deg);
    vksky_composite_desc cd = {.abi_version = VKSKY_ABI_VERSION, .width = (uint32_t)o->width,
                               .rows = (uint32_t)o->height, .volume = co->aerial == AERIAL_VOLUME,
                               .volume_size = {co->ap_size[0], co->ap_size[1], co->ap_size[2]},
                               .volume_range_km = (float)co->ap_range_km,
                               .volume_distribution = (float)co->ap_distribution};
    size_t n = (size_t)o->width * o->height;
    const float *aov[VKSKY_COMPOSITE_LAYERS] = {NULL};
    const uint16_t *linear = NULL;
    const uint8_t *display = NULL;
    vksky_composite *c = NULL;
    spectral_image img = {0};
    float *sums = NULL;
    if (o->spectral) {   /* the sky frame (the spectral still's) and the layers in spectral colour */
        if (spectral_host_render(o, g.ctx, g.scene, &g.h[0], &img) != 0 ||
            composite_spectral_aovs(&g.h[0], g.ctx, g.scene, o->spectral, &cd, &v, trace, &sums) != 0)
            status = 1;
        for (uint32_t k = 0; k < VKSKY_COMPOSITE_LAYERS && sums; ++k) aov[k] = sums + (size_t)k * n * 4;
        linear = img.linear, display = img.display;
    } else {
        /* The sky frame itself, as a plain render (the view as the command line gives it). */
        host_view hv = {.yaw_deg = o->view.yaw_deg, .pitch_deg = o->view.pitch_deg, .fov_deg = o->view.fov_deg,
                        .exposure = o->view.exposure_ev, .auto_exposure = light_auto_exposure_wanted(o)};
        if (host_commands_render(&g.h[0], g.r, &hv, trace, NULL) != 0) return gpu_end(&g, 1);
        if (vksky_composite_create(g.r, &cd, &c) != VKSKY_SUCCESS) return gpu_end(&g, 2);
        if (vksky_composite_set_view(c, &v, (uint32_t)o->height, VKSKY_COMPOSITE_VIEW_ALTITUDE, NULL) != VKSKY_SUCCESS) {
            vksky_composite_destroy(c);
            return gpu_end(&g, 1);
        }
        float *in = vksky_composite_inputs(c, 0);
        for (size_t i = 0; i < n; ++i) {
            float *b = in + 4 * i, *p = in + 4 * (n + i);
            b[0] = b[1] = b[2] = b[3] = 0.0f;
            p[0] = p[1] = p[2] = p[3] = NAN;   /* no geometry anywhere */
        }
        vksky_composite_frame f = {.slot = 0};
        if (composite_submit(&g.h[0], g.r, c, &f, frames_from_env(), trace, NULL) != 0) status = 1;
        vksky_readback px;
        if (status == 0 && vksky_renderer_get_readback(g.r, &px) != VKSKY_SUCCESS) status = 1;
        if (status == 0) linear = px.linear_rgba16f, display = px.display_rgba8;
        if (status == 0 && vksky_renderer_store_luts(g.r) != VKSKY_SUCCESS) status = 1;   /* as the bands' (above) */
        for (uint32_t k = 0; k < VKSKY_COMPOSITE_LAYERS; ++k) aov[k] = vksky_composite_layer(c, 0, k);
    }
    float *top = status ? NULL : malloc(n * 4 * sizeof(float));
    exr_header hdr;
    options with_aovs = *o;   /* the command line with --aovs */
    if (co->argv_all) with_aovs.argc = co->argc_all, with_aovs.argv = co->argv_all;
    if (top && exr_header_build(&hdr, &with_aovs, -1) != 0) {
        free(top);
        top = NULL;
    }
    for (size_t i = 0; top && i < 4 * n; ++i) top[i] = io_half_to_float(linear[i]);
    for (int i = 0; i < o->output_count && status == 0; ++i) {
        int rc = !top ? -1
                 : is_exr(o->outputs[i]) ? write_layers(o->outputs[i], aov, o->width, o->height, top, &hdr.meta, err,
                                                        sizeof err)
                                         : io_write_png(o->outputs[i], o->width, o->height, display, 1, err,
                                                        sizeof err);
        if (rc != 0) {
            fprintf(stderr, "vksky: --render: %s\n", top ? err : "out of memory");
            status = 1;
        }
    }
    if (top) exr_header_free(&hdr);
    free(top);
    free(sums);
    spectral_image_release(&img);
    vksky_composite_destroy(c);
    return gpu_end(&g, status);
}
