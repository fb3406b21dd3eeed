/* The composite driver: read the render (io/exr_read.h), find its layers, place the camera, run the composite
 * pass (sky/composite.h), write the composite and its AOV layers (io/exr_layers.h). Every bad input is one line on
 * stderr and exit status 2, before any output file exists. */
#include "app/composite_app.h"
#include "app/startup.h"
#include "app/stop.h"
#include "io/exr_layers.h"
#include "io/exr_read.h"
#include "io/atomic_file.h"
#include "io/exr_write.h"
#include "io/half_float.h"
#include "io/png_io.h"
#include "sky/frame.h"
#include "sky/submit.h"
#include "sky/view_params.h"
#include "sky/composite.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const char *const AOV_NAMES[VKSKY_AOV_COUNT] = {"", "sky", "sun_disk", "transmittance", "rayleigh", "mie"};

/* --- Finding the layers ---------------------------------------------------------------------------------- */

static bool has_channel(const io_exr_info *info, const char *name)
{
    for (int i = 0; i < info->channel_count; ++i)
        if (!strcmp(info->channels[i].name, name)) return true;
    return false;
}

/* "<prefix>.<c>" for each of the channel letters in `letters` present? (prefix "" = top level: "<c>"). */
static bool has_layer(const io_exr_info *info, const char *prefix, const char *letters)
{
    char name[512];
    for (const char *c = letters; *c; ++c) {
        snprintf(name, sizeof name, "%s%s%c", prefix, *prefix ? "." : "", *c);
        if (!has_channel(info, name)) return false;
    }
    return true;
}

/* The layer of the first channel named "<anything><suffix>" (e.g. suffix ".Combined.R" -> "ViewLayer.Combined"):
 * Blender names it after the view layer, whatever that is called. */
static bool find_layer(const io_exr_info *info, const char *suffix, char *out, size_t size)
{
    size_t ls = strlen(suffix);
    for (int i = 0; i < info->channel_count; ++i) {
        const char *n = info->channels[i].name;
        size_t ln = strlen(n);
        /* The layer is the name less its ".R" / ".X". */
        if (ln > ls && !strcmp(n + ln - ls, suffix) && ln - 2 < size) {
            snprintf(out, size, "%.*s", (int)(ln - 2), n);
            return true;
        }
    }
    return false;
}

/* The channel list for a message: "R, G, B, ViewLayer.Combined.R, ..." (the first dozen). */
static void list_channels(const io_exr_info *info, char *out, size_t size)
{
    out[0] = '\0';
    size_t used = 0;
    for (int i = 0; i < info->channel_count && i < 12; ++i) {
        int n = snprintf(out + used, size - used, "%s%s", i ? ", " : "", info->channels[i].name);
        if (n < 0 || (size_t)n >= size - used) break;
        used += (size_t)n;
    }
    if (info->channel_count > 12 && used + 8 < size) strcat(out, ", ...");
    if (info->channel_count == 0) snprintf(out, size, "no channels");
}

typedef struct layer_pick {
    char prefix[256];
    const char *letters;      /* "RGBA", "RGB", "XYZ" */
} layer_pick;

static int pick_beauty(const io_exr_info *info, const char *path, const char *asked, layer_pick *p)
{
    char have[600];
    if (asked) {
        snprintf(p->prefix, sizeof p->prefix, "%s", asked);
    } else if (!find_layer(info, ".Combined.R", p->prefix, sizeof p->prefix)) {
        if (!has_layer(info, "", "RGB")) {
            list_channels(info, have, sizeof have);
            fprintf(stderr, "vksky: --composite: %s: no beauty layer: expected <ViewLayer>.Combined.R,G,B,A or "
                            "R,G,B,A (or --beauty-layer NAME); the file has %s\n", path, have);
            return 2;
        }
        p->prefix[0] = '\0';
    }
    p->letters = has_layer(info, p->prefix, "RGBA") ? "RGBA" : "RGB";
    if (!has_layer(info, p->prefix, "RGB")) {
        list_channels(info, have, sizeof have);
        fprintf(stderr, "vksky: --composite: %s: no beauty layer '%s' (channels %s%sR,G,B[,A]); the file has %s\n",
                path, p->prefix, p->prefix, *p->prefix ? "." : "", have);
        return 2;
    }
    return 0;
}

static int pick_position(const io_exr_info *info, const char *path, const char *asked, bool own_file, layer_pick *p)
{
    char have[600];
    if (asked) {
        snprintf(p->prefix, sizeof p->prefix, "%s", asked);
    } else if (!find_layer(info, ".Position.X", p->prefix, sizeof p->prefix)) {
        p->prefix[0] = '\0';
        if (!own_file || !(has_layer(info, "", "XYZ") || has_layer(info, "", "RGB"))) {
            list_channels(info, have, sizeof have);
            fprintf(stderr, "vksky: --composite: %s: no position layer: expected <ViewLayer>.Position.X,Y,Z%s (or "
                            "--position-layer NAME, or --position FILE.exr); the file has %s\n", path,
                    own_file ? " or X,Y,Z or R,G,B" : "", have);
            return 2;
        }
    }
    /* X, Y, Z; a position with just R, G, B (a plain image) is read as X, Y, Z. */
    p->letters = has_layer(info, p->prefix, "XYZ") ? "XYZ" : has_layer(info, p->prefix, "RGB") ? "RGB" : NULL;
    if (!p->letters) {
        list_channels(info, have, sizeof have);
        fprintf(stderr, "vksky: --composite: %s: no position layer '%s' (channels %s%sX,Y,Z or R,G,B); the file has %s\n",
                path, p->prefix, p->prefix, *p->prefix ? "." : "", have);
        return 2;
    }
    return 0;
}

/* Read a picked layer into `out` (stride 4 floats per pixel; a missing alpha reads as 1). */
static int read_layer(const char *path, const layer_pick *p, int width, int height, float *out)
{
    size_t n = (size_t)width * height, count = strlen(p->letters);
    char names_buf[4][300];
    const char *names[4];
    for (size_t i = 0; i < count; ++i) {
        snprintf(names_buf[i], sizeof names_buf[i], "%s%s%c", p->prefix, *p->prefix ? "." : "", p->letters[i]);
        names[i] = names_buf[i];
    }
    float *tmp = malloc(n * count * sizeof(float));
    char err[512];
    if (!tmp) {
        fprintf(stderr, "vksky: --composite: %s: out of memory for %dx%d pixels\n", path, width, height);
        return 1;
    }
    if (io_exr_read_channels(path, names, (int)count, tmp, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: --composite: %s\n", err);
        free(tmp);
        return 2;
    }
    for (size_t i = 0; i < n; ++i)
        for (size_t c = 0; c < 4; ++c) out[4 * i + c] = c < count ? tmp[count * i + c] : 1.0f;
    free(tmp);
    return 0;
}

/* --- The camera ------------------------------------------------------------------------------------------- */

/* Inverse of a 3x3 (row-major); false when singular. */
static bool invert3(const double m[3][3], double out[3][3])
{
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if (!(fabs(det) > 1e-300) || !isfinite(det)) return false;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            int a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, d = (i + 2) % 3;
            out[i][j] = (m[a][c] * m[b][d] - m[a][d] * m[b][c]) / det;
        }
    return true;
}

/* OpenEXR's worldToCamera (row vectors, p_cam = p_world M; the camera looks along -Z, +X right, +Y up): the
 * camera's position and axes in world coordinates. With worldToNDC (NDC x, y in [-1, 1] across the screen
 * window) also the vertical field of view. */
static bool camera_from_matrices(const io_exr_info *info, composite_view *v, double *fov_deg)
{
    const float *M = info->world_to_camera;
    double R[3][3], Ri[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) R[i][j] = M[4 * i + j];
    if (!invert3(R, Ri)) return false;
    /* c R + t = 0 -> c = -t R^-1; camera axis k in world: row k of R^-1. */
    for (int j = 0; j < 3; ++j) {
        v->camera[j] = -(M[12] * Ri[0][j] + M[13] * Ri[1][j] + M[14] * Ri[2][j]);
        v->right[j] = Ri[0][j], v->up[j] = Ri[1][j], v->forward[j] = -Ri[2][j];
    }
    double *axes[3] = {v->right, v->up, v->forward};
    for (int k = 0; k < 3; ++k) {
        double n = sqrt(axes[k][0] * axes[k][0] + axes[k][1] * axes[k][1] + axes[k][2] * axes[k][2]);
        for (int j = 0; j < 3; ++j) axes[k][j] /= n;
    }
    *fov_deg = 0.0;
    if (info->has_world_to_ndc) {
        /* The camera-space point (0, 1, -1) lands at NDC y = 1 / tan(fov / 2). */
        double p[3], h[4] = {0, 0, 0, 0};
        for (int j = 0; j < 3; ++j) p[j] = v->camera[j] + Ri[1][j] - Ri[2][j];
        const float *N = info->world_to_ndc;
        for (int j = 0; j < 4; ++j) h[j] = p[0] * N[j] + p[1] * N[4 + j] + p[2] * N[8 + j] + N[12 + j];
        double y = h[3] != 0.0 ? fabs(h[1] / h[3]) : 0.0;
        double fov = y > 0.0 ? 2.0 * atan(1.0 / y) * 180.0 / 3.14159265358979323846 : 0.0;
        if (fov >= 1.0 && fov <= 170.0) *fov_deg = fov;
    }
    return true;
}

/* --- Running the pass -------------------------------------------------------------------------------------- */

static int frames_from_env(void)
{
    const char *env = getenv("VKSKY_FRAMES");
    return env ? atoi(env) : 1;
}

/* GPU context, a renderer for the LUTs (1x1: its own images are not used), the atmosphere of the options. */
static int gpu_begin(const options *o, gpu_context *ctx, sky_renderer *r, uint32_t width, uint32_t height,
                     bool readback)
{
    stop_install();   /* SIGINT/SIGTERM from here on: the output is not renamed into place; exit 130/143 */
    gpu_context_desc desc = {.validation = o->validate, .device_index = o->device_index};
    int rc = gpu_context_create(ctx, &desc);
    if (rc != 0) return rc == -2 ? 2 : 1;
    startup_open_cache(ctx, o);
    if (o->trace_barriers) gpu_barrier_trace(stdout);
    gpu_barrier_set_drop(getenv("VKSKY_DROP_BARRIER"));
    sky_features features = options_features(o);
    sky_renderer_desc rdesc = {.width = width, .height = height, .bloom = readback && o->view.bloom,
                               .readback = readback, .display_format = VK_FORMAT_R8G8B8A8_SRGB,
                               .render_scale = readback ? o->render_scale : 1.0, .lut = o->lut,
                               .bloom_mips = (uint32_t)o->bloom_mips, .atmosphere = &o->atmosphere,
                               .sun_angular_radius_rad = options_sun_radius_rad(o), .features = &features};
    sky_renderer_create(r, ctx, &rdesc);
    if (o->trace_passes) r->pass_trace = stdout;
    return 0;
}

static int gpu_end(gpu_context *ctx, sky_renderer *r, int status)
{
    sky_renderer_destroy(r);
    startup_close_cache(ctx);
    gpu_context_destroy(ctx);
    unsigned messages = gpu_validation_message_count();
    if (messages) {
        fprintf(stderr, "vksky: validation reported %u message%s\n", messages, messages == 1 ? "" : "s");
        if (status == 0) status = 1;
    }
    return stop_status(status);
}

/* The composite RGBA at the top level (or `top` when given), the AOVs as RGB layers (io/exr_layers.h: half, the
 * layer.channel names). */
static int write_layers(const char *path, const sky_composite *c, const float *top, char *err, size_t err_size)
{
    size_t n = (size_t)c->width * c->height;
    float *rgb = malloc(n * 3 * sizeof(float) * (VKSKY_AOV_COUNT - 1));
    if (!rgb) {
        snprintf(err, err_size, "out of memory");
        return -1;
    }
    io_exr_out_layer layers[VKSKY_AOV_COUNT];
    layers[0] = (io_exr_out_layer){"", 4, top ? top : sky_composite_layer(c, VKSKY_AOV_COMPOSITE)};
    for (int k = 1; k < VKSKY_AOV_COUNT; ++k) {
        float *dst = rgb + (size_t)(k - 1) * 3 * n;
        const float *src = sky_composite_layer(c, k);
        for (size_t i = 0; i < n; ++i)
            for (int ch = 0; ch < 3; ++ch) dst[3 * i + ch] = src[4 * i + ch];
        layers[k] = (io_exr_out_layer){AOV_NAMES[k], 3, dst};
    }
    int rc = io_write_exr_layers(path, (int)c->width, (int)c->height, layers, VKSKY_AOV_COUNT, err, err_size);
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

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* --bench N with --composite: per-pass GPU medians of N composite frames after warm-up (the LUTs are not in them:
 * built once by the first frame), one line per pass like the sky's benchmark. */
static void bench(sky_renderer *r, sky_composite *c, const CompositePush *push, int frames)
{
    enum { PASSES = 4 };
    static const char *const names[PASSES] = {"ap_volume", "composite_upload", "composite", "composite_readback"};
    double *ms = calloc((size_t)frames * (PASSES + 1), sizeof *ms), read[GPU_TIMER_MAX];
    if (!ms) return;
    double *wall = ms + (size_t)frames * PASSES;   /* submit -> fence (lavapipe's timestamps miss compute work) */
    for (int i = 0; i < 3; ++i) sky_composite_render(r, c, push, 1);   /* warm-up: LUTs, shader compiles, clocks */
    for (int i = 0; i < frames; ++i) {
        wall[i] = sky_composite_render(r, c, push, 1);
        uint32_t count = gpu_timer_read(r->ctx, &r->timer, read);
        for (uint32_t k = 0; k < count; ++k)
            for (int p = 0; p < PASSES; ++p)
                if (!strcmp(r->timer.names[k], names[p])) ms[p * frames + i] = read[k];
    }
    for (int p = c->has_volume ? 0 : 1; p < PASSES && r->timer.enabled; ++p) {
        qsort(ms + p * frames, (size_t)frames, sizeof *ms, compare_double);
        printf("pass %s gpu_ms %.4f (%ux%u)\n", names[p], ms[p * frames + frames / 2], c->width, c->height);
    }
    qsort(wall, (size_t)frames, sizeof *wall, compare_double);
    printf("composite frame wall_ms %.3f (submit to fence, median of %d; %s)\n", wall[frames / 2], frames,
           c->has_volume ? "volume" : "march");
    free(ms);
}

static bool is_exr(const char *path)
{
    size_t n = strlen(path);
    return n > 4 && strcasecmp(path + n - 4, ".exr") == 0;
}

/* The froxel volume's shape for --aerial-perspective (volume, or auto when --max-error allows it), or NULL: a
 * march per pixel. -1 (after one line on stderr): volume asked for without a known camera orientation. */
static int pick_volume(const options *o, const composite_options *co, bool oriented, ap_volume_desc *desc,
                       const ap_volume_desc **out)
{
    *out = NULL;
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
    *desc = (ap_volume_desc){size[0], size[1], size[2], (float)range, (float)distribution};
    *out = desc;
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
    /* The files and their layers. */
    const char *beauty_path = co->input, *position_path = co->position ? co->position : co->input;
    io_exr_info bi = {0}, pi = {0};
    if (io_exr_read_info(beauty_path, &bi, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: --composite: %s\n", err);
        return 2;
    }
    int status = 0;
    if (co->position && io_exr_read_info(position_path, &pi, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: --position: %s\n", err);
        io_exr_info_free(&bi);
        return 2;
    }
    const io_exr_info *pinfo = co->position ? &pi : &bi;
    layer_pick bp, pp;
    if (pick_beauty(&bi, beauty_path, co->beauty_layer, &bp) ||
        pick_position(pinfo, position_path, co->position_layer, co->position != NULL, &pp)) {
        status = 2;
        goto done_info;
    }
    if (pinfo->width != bi.width || pinfo->height != bi.height) {
        fprintf(stderr, "vksky: --position: %s is %dx%d but the beauty %s is %dx%d; they must be the same size\n",
                position_path, pinfo->width, pinfo->height, beauty_path, bi.width, bi.height);
        status = 2;
        goto done_info;
    }
    int w = bi.width, h = bi.height;
    size_t n = (size_t)w * h;

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
        composite_view_orient_yaw_pitch(&v, o->view.yaw_deg, o->view.pitch_deg);
        if (!co->has_fov && !(from_matrix && matrix_fov > 0.0))
            fprintf(stderr, "vksky: --composite: no --fov given: the sky pixels assume %g degrees (vertical); give the "
                            "render's field of view\n", o->view.fov_deg);
        else if (!co->has_fov)
            v.fov_y_deg = matrix_fov;
    } else if (from_matrix && (matrix_fov > 0.0 || co->has_fov)) {
        v.oriented = true;
        if (!co->has_fov) v.fov_y_deg = matrix_fov;
    }

    ap_volume_desc vol_desc;
    const ap_volume_desc *vol = NULL;
    if (pick_volume(o, co, v.oriented, &vol_desc, &vol) != 0) {
        status = 2;
        goto done_info;
    }
    gpu_context ctx;
    sky_renderer r;
    /* Inputs, before the GPU: a bad pixel pass fails fast. */
    float *beauty = malloc(n * 4 * sizeof(float)), *position = malloc(n * 4 * sizeof(float));
    if (!beauty || !position) {
        fprintf(stderr, "vksky: --composite: out of memory for %dx%d pixels\n", w, h);
        status = 1;
        goto done_pixels;
    }
    if ((status = read_layer(beauty_path, &bp, w, h, beauty)) || (status = read_layer(position_path, &pp, w, h, position)))
        goto done_pixels;
    size_t geometry = 0, sky = 0;
    for (size_t i = 0; i < n; ++i) {
        const float *p = position + 4 * i;
        bool finite = isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
        if (finite && beauty[4 * i + 3] > 0.0f) ++geometry;
        else ++sky;
    }
    if (geometry == 0) {
        fprintf(stderr, "vksky: --composite: %s: the position pass has no finite pixel with alpha > 0: nothing to "
                        "apply the atmosphere to (is it the world-position pass?)\n", position_path);
        status = 2;
        goto done_pixels;
    }
    CompositePush push;
    model_atmosphere earth = o->atmosphere;
    double altitude = composite_push(&v, earth.bottom_radius, (uint32_t)w, (uint32_t)h, &push);
    if (altitude < 0.0) {
        fprintf(stderr, "vksky: --composite: the camera (%g, %g, %g world units) is inside the planet (%.4g km below "
                        "the ground); check --world-up, --world-unit, --ground-altitude\n",
                v.camera[0], v.camera[1], v.camera[2], -altitude);
        status = 2;
        goto done_pixels;
    }
    if (!v.oriented && sky > 0)
        fprintf(stderr, "vksky: --composite: the camera's orientation is unknown (no worldToCamera, no --yaw/--pitch): "
                        "%zu pixels without geometry keep the beauty\n", sky);

    if ((status = gpu_begin(o, &ctx, &r, 1, 1, false)) != 0) goto done_pixels;
    sky_composite c;
    if (sky_composite_create(&c, &r, (uint32_t)w, (uint32_t)h, vol, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: --composite: %s\n", err);
        status = gpu_end(&ctx, &r, 2);
        goto done_pixels;
    }
    float *in = sky_composite_inputs(&c);
    memcpy(in, beauty, n * 4 * sizeof(float));
    memcpy(in + 4 * n, position, n * 4 * sizeof(float));
    if (o->bench_frames > 0) bench(&r, &c, &push, o->bench_frames);
    sky_composite_render(&r, &c, &push, frames_from_env());
    if (write_layers(out_path, &c, NULL, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: --render: %s\n", err);
        status = 1;
    }
    sky_composite_destroy(&c, &r);
    status = gpu_end(&ctx, &r, status);
done_pixels:
    free(beauty);
    free(position);
done_info:
    io_exr_info_free(&bi);
    io_exr_info_free(&pi);
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
    gpu_context ctx;
    sky_renderer r;
    int status = gpu_begin(o, &ctx, &r, (uint32_t)o->width, (uint32_t)o->height, true);
    if (status) return status;
    /* The sky frame itself, as a plain render. */
    frame_desc f = {.view = &o->view};
    sky_renderer_render(&r, &f);
    /* The layers: the composite pass over a frame with no geometry, the camera the view's (at the world origin,
     * +Y up, km). */
    composite_view v = view_from_options(o);
    v.km_per_unit = 1.0, v.up_axis = 1;
    v.camera[1] = o->view.altitude_km;
    composite_view_orient_yaw_pitch(&v, o->view.yaw_deg, o->view.pitch_deg);
    CompositePush push;
    composite_push(&v, o->atmosphere.bottom_radius, (uint32_t)o->width, (uint32_t)o->height, &push);
    push.forward.w = (float)o->view.altitude_km;   /* exactly the sky pass's altitude */
    /* The volume only with --aerial-perspective volume: there is no geometry to sample it, but the frame is the
     * composite's with the volume pass in it (barrier tests, docs/synchronization.md). */
    ap_volume_desc vol = {co->ap_size[0], co->ap_size[1], co->ap_size[2], (float)co->ap_range_km,
                          (float)co->ap_distribution};
    sky_composite c;
    if (sky_composite_create(&c, &r, (uint32_t)o->width, (uint32_t)o->height,
                             co->aerial == AERIAL_VOLUME ? &vol : NULL, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: --aovs: %s\n", err);
        return gpu_end(&ctx, &r, 2);
    }
    size_t n = (size_t)o->width * o->height;
    float *in = sky_composite_inputs(&c);
    for (size_t i = 0; i < n; ++i) {
        float *b = in + 4 * i, *p = in + 4 * (n + i);
        b[0] = b[1] = b[2] = b[3] = 0.0f;
        p[0] = p[1] = p[2] = p[3] = NAN;   /* no geometry anywhere */
    }
    sky_composite_render(&r, &c, &push, frames_from_env());
    float *top = malloc(n * 4 * sizeof(float));
    const uint16_t *half = r.readback_linear.mapped;
    for (size_t i = 0; top && i < 4 * n; ++i) top[i] = io_half_to_float(half[i]);
    for (int i = 0; i < o->output_count && status == 0; ++i) {
        int rc = !top ? -1
                 : is_exr(o->outputs[i]) ? write_layers(o->outputs[i], &c, top, err, sizeof err)
                                         : io_write_png(o->outputs[i], o->width, o->height, r.readback_display.mapped, 1,
                                                        err, sizeof err);
        if (rc != 0) {
            fprintf(stderr, "vksky: --render: %s\n", top ? err : "out of memory");
            status = 1;
        }
    }
    free(top);
    sky_composite_destroy(&c, &r);
    return gpu_end(&ctx, &r, status);
}
