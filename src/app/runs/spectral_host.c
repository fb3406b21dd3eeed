/* --spectral N of one image through include/vksky.h (spectral_host.h). */
#include "app/runs/spectral_host.h"
#include "app/runs/sequence_frames.h"
#include "app/runs/sequence_resume.h"
#include "app/runs/stop.h"
#include "app/runs/spectral_render.h"
#include "app/runs/startup.h"
#include "app/runs/tiles.h"
#include "app/scene/light.h"
#include "io/half_float.h"
#include "io/parts.h"
#include <pthread.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define GROUPS_MAX (VKSKY_SPECTRAL_MAX / 3 + 1)

void spectral_image_release(spectral_image *img)
{
    free(img->linear);
    free(img->display);
    *img = (spectral_image){0};
}

static bool wants_png(const options *o)
{
    for (int i = 0; i < o->output_count; ++i) {
        size_t n = strlen(o->outputs[i]);
        if (n < 4 || strcasecmp(o->outputs[i] + n - 4, ".exr")) return true;
    }
    return false;
}

/* Every group's renderer, made and recorded: the groups' frames in one command buffer, one submission, one wait. */
typedef struct groups {
    uint32_t count, per_pass;
    /* One renderer for every group, given each group's scene in turn (a still: one set of pipelines to make, which
     * a CPU device compiles per renderer), else a renderer per group (a sequence: each keeps its LUTs, and a frame's
     * groups go in one submission). */
    bool shared;
    bool quiet;   /* the host tone map's auto exposure line left out (--quiet, or a sequence: as the GPU meter's) */
    vksky_scene *scene[GROUPS_MAX];
    vksky_renderer *r[GROUPS_MAX];
    double weights[GROUPS_MAX][4][3];
    /* The groups summed on the GPU (ABI 4: each group's frame adds into it, the last resolves; one readback a frame),
     * or NULL: each group read back and summed on the host (VKSKY_SPECTRAL_SUM=host, for the comparison tests). */
    vksky_spectral_sum *sum;
    /* An auto-exposed PNG whose groups bloom: each group also renders a bloom-free frame, summed apart (on the GPU into
     * meter_sum, or on the host), for the host's meter. The GPU's meter reads the HDR image before bloom; the groups'
     * composites carry it (a 1080p afternoon frame's log-average luminance 34 % over the bloom-free one's: a PNG 0.4 EV
     * darker than the RGB one of the same view). NULL without the GPU's sum. */
    bool meter_frames;
    vksky_spectral_sum *meter_sum;
} groups;

static void groups_destroy(groups *g)
{
    for (uint32_t k = 0; k < g->count; ++k) vksky_renderer_destroy(g->r[k]), vksky_scene_destroy(g->scene[k]);
    vksky_spectral_sum_destroy(g->sum);
    vksky_spectral_sum_destroy(g->meter_sum);
}

/* Frame scenes: the groups derived again from the scene as the frame's values left it (a medium may be animated), each
 * renderer given its own (vksky_renderer_set_scene keeps what did not change: a moved sun recomputes no medium LUT).
 * *luts: whether any group's next frame computes the LUTs. */
static int groups_set_scene(groups *g, const options *o, const vksky_scene *scene, bool *luts)
{
    *luts = false;
    for (uint32_t k = 0; k < g->count; ++k) {
        vksky_scene_destroy(g->scene[k]);
        g->scene[k] = NULL;
        if (vksky_scene_spectral_group(scene, (uint32_t)o->spectral, g->per_pass, k, &g->scene[k], g->weights[k],
                                       NULL) != VKSKY_SUCCESS ||
            (!g->shared && vksky_renderer_set_scene(g->r[k], g->scene[k]) != VKSKY_SUCCESS))
            return 1;
        if (!g->shared) *luts = *luts || vksky_renderer_luts_stale(g->r[k]);
    }
    if (g->shared) {   /* one renderer: each group's medium computes its LUTs again, unless there is one group */
        if (g->count == 1 && vksky_renderer_set_scene(g->r[0], g->scene[0]) != VKSKY_SUCCESS) return 1;
        *luts = g->count > 1 || vksky_renderer_luts_stale(g->r[0]);
    }
    return 0;
}

static int groups_create(groups *g, const options *o, vksky_context *ctx, const vksky_scene *scene, bool shared,
                         int height)
{
    g->shared = shared;
    g->quiet = o->quiet || sequence_active(o);   /* o: the run's, not a frame's */
    /* Four to a pass unless the horizon is in a perspective frame (its resolve needs the composite's alpha). */
    g->per_pass = spectral_render_four_wide(o) ? 4u : 3u;
    uint32_t count = vksky_spectral_group_count((uint32_t)o->spectral, g->per_pass);
    if (count == 0 || count > GROUPS_MAX) {
        fprintf(stderr, "vksky: --spectral %d: not a count the GPU takes\n", o->spectral);
        return 1;
    }
    vksky_readback_config readback = {.type = VKSKY_STRUCTURE_TYPE_READBACK_CONFIG};
    bool bloom = o->view.bloom && height == o->height;   /* bands: no bloom (tiles.c) */
    /* A map's frame has no bloom (its composite is the HDR texel), nor has the four-wide build. */
    g->meter_frames = bloom && g->per_pass == 3 && o->view.projection == VKSKY_PROJECTION_PERSPECTIVE && wants_png(o) &&
                      light_auto_exposure_wanted(o);
    for (uint32_t k = 0; k < count; ++k) {
        if (vksky_scene_spectral_group(scene, (uint32_t)o->spectral, g->per_pass, k, &g->scene[k], g->weights[k],
                                       NULL) != VKSKY_SUCCESS)
            return 1;
        g->count = k + 1;
        if (shared && k > 0) continue;
        vksky_renderer_desc rd = {
            .abi_version = VKSKY_ABI_VERSION, .next = &readback, .output = VKSKY_OUTPUT_DISPLAY,
            .width = (uint32_t)o->width, .height = (uint32_t)height, .target_format = VK_FORMAT_R8G8B8A8_SRGB,
            .quality = "scene", .bloom = bloom,
            .units = o->units == OPTIONS_UNITS_RELATIVE ? VKSKY_UNITS_RELATIVE : VKSKY_UNITS_PHOTOMETRIC,
            .scene = g->scene[k]};
        if (vksky_renderer_create(ctx, &rd, &g->r[k]) != VKSKY_SUCCESS) return 1;
    }
    const char *where = getenv("VKSKY_SPECTRAL_SUM");
    if (where && !strcmp(where, "host")) return 0;
    if (vksky_spectral_sum_create(ctx, (uint32_t)o->width, (uint32_t)height, &g->sum) != VKSKY_SUCCESS ||
        (g->meter_frames &&
         vksky_spectral_sum_create(ctx, (uint32_t)o->width, (uint32_t)height, &g->meter_sum) != VKSKY_SUCCESS))
        return 1;
    return 0;
}

/* The whole image's view of o (a band's: its own first row, tiles.c). */
static host_view whole_view(const options *o)
{
    const sky_view *view = &o->view;
    /* The groups' own tone maps are not used (the sum is tone-mapped on the host): no meter on the GPU. */
    return (host_view){.yaw_deg = view->yaw_deg, .pitch_deg = view->pitch_deg, .fov_deg = view->fov_deg,
                       .exposure = view->exposure_ev, .projection = (vksky_projection)view->projection,
                       .whole_width = (uint32_t)o->width, .whole_height = (uint32_t)o->height};
}

/* The groups' frames for host_commands_submit: renderers rs[0 .. n-1] (groups first .. first + n - 1) of view v, one
 * after the other into the command buffer; with the GPU's sum each frame adds its group into it, the frame's last
 * group resolves. */
typedef struct group_frames {
    const groups *g;
    vksky_renderer *const *rs;
    uint32_t first, n;
    const host_view *view;
    vksky_spectral_sum *sum;   /* the sum these frames add into (g->sum or g->meter_sum; NULL: the host sums) */
} group_frames;

static int record_groups(void *user, VkCommandBuffer cmd, bool force_luts, bool follows_frame)
{
    (void)force_luts, (void)follows_frame;   /* one frame a submission: neither applies */
    const group_frames *f = user;
    const groups *g = f->g;
    host_view v = *f->view;
    vksky_frame_spectral_sum step = {.type = VKSKY_STRUCTURE_TYPE_FRAME_SPECTRAL_SUM, .sum = f->sum};
    for (uint32_t k = 0; k < f->n; ++k) {
        uint32_t group = f->first + k;
        step.group = group, step.first = group == 0, step.last = group + 1 == g->count;
        memcpy(step.xyz_weights, g->weights[group], sizeof step.xyz_weights);
        v.spectral_sum = f->sum ? &step : NULL;
        if (host_record(f->rs[k], cmd, &v, 0) != 0) return 1;
    }
    return 0;
}

/* The frames of renderers rs[0 .. n-1] in one command buffer, one submission, one wait (with --async-luts: their
 * LUT passes first, in one submission on the compute queue: host_async.h). */
static int render_list(const groups *g, vksky_renderer *const *rs, uint32_t first, uint32_t n, const options *o,
                       const host_view *view, vksky_spectral_sum *sum, host_commands *h)
{
    group_frames frames = {g, rs, first, n, view, sum};
    host_submission s = {.luts = rs, .luts_count = n, .record = record_groups, .user = &frames,
                         .trace = o->trace_barriers ? stdout : NULL, .what = "the spectral frame"};
    if (host_commands_submit(h, &s, 0, 1)) return 1;
    /* A LUT cache miss: the LUTs computed, into the cache for the next start (a hit or none: nothing). */
    for (uint32_t k = 0; k < n; ++k)
        if (vksky_renderer_store_luts(rs[k]) != VKSKY_SUCCESS) return 1;
    return 0;
}

/* The host's sum, split over the encode threads (io_encode_threads, --threads): each part is a range of whole pixels
 * and every pixel's arithmetic is the same whatever the split (groups in order, the same float adds), so the bytes
 * depend on nothing else. A 720p frame of 24 wavelengths is 22 M multiply-adds, on the render thread a serial part of every
 * frame (issue 27: the spectral sequence at 3.5-4 frames/s on the H100). */
typedef struct sum_job {
    const groups *g;
    const uint16_t *group_px[GROUPS_MAX];   /* the readbacks summed by this job, groups first .. first + count - 1 */
    uint32_t first, count;
    bool resolve;                           /* then XYZ -> Rec.709 into linear (and rgb) */
    const uint16_t *alpha;                  /* the last group's readback (three to a pass: the alpha) */
    const float *resolved;                  /* or the GPU's sum, resolved: only converted (linear halves, rgb) */
    float *xyz, *rgb;
    uint16_t *linear;                       /* or NULL (the meter's sum: its floats only) */
} sum_job;

static void sum_pixels(void *user, size_t part, size_t begin, size_t end)
{
    (void)part;
    const sum_job *j = user;
    const groups *g = j->g;
    if (j->resolved) {   /* the GPU summed and resolved: the EXR's halves (clamped to their range) and the PNG's floats */
        for (size_t i = begin; i < end; ++i) {
            const float *px = j->resolved + 4 * i;
            for (int q = 0; q < 3; ++q) {
                float v = px[q] < -65504.0f ? -65504.0f : px[q] > 65504.0f ? 65504.0f : px[q];
                if (j->linear) j->linear[4 * i + q] = io_float_to_half(v);
                if (j->rgb) j->rgb[4 * i + q] = px[q];
            }
            if (j->linear) j->linear[4 * i + 3] = io_float_to_half(px[3]);
            if (j->rgb) j->rgb[4 * i + 3] = 1.0f;
        }
        return;
    }
    const float *half_value = io_half_table();
    for (uint32_t n = 0; n < j->count; ++n) {
        const double(*m)[3] = g->weights[j->first + n];
        const uint16_t *px = j->group_px[n];
        for (size_t i = begin; i < end; ++i) {
            const uint16_t *p = px + 4 * i;
            float *x = j->xyz + 3 * i;
            for (uint32_t c = 0; c < g->per_pass; ++c) {
                float v = half_value[p[c]];
                for (int q = 0; q < 3; ++q) x[q] += (float)(m[c][q] * v);
            }
        }
    }
    if (!j->resolve) return;
    /* Alpha: the composite's with three to a pass (the last group's), 1 with four (the
     * four-wide readback's alpha is a wavelength). Out of Rec.709's gamut stays negative; half's range bounds it. */
    for (size_t i = begin; i < end; ++i) {
        double in[3] = {j->xyz[3 * i], j->xyz[3 * i + 1], j->xyz[3 * i + 2]}, rec[3];
        vksky_spectral_xyz_to_rec709(in, rec);
        for (int q = 0; q < 3; ++q) {
            double v = rec[q] < -65504.0 ? -65504.0 : rec[q] > 65504.0 ? 65504.0 : rec[q];
            if (j->linear) j->linear[4 * i + q] = io_float_to_half((float)v);
            if (j->rgb) j->rgb[4 * i + q] = (float)rec[q];
        }
        if (j->linear) j->linear[4 * i + 3] = g->per_pass == 4 ? io_float_to_half(1.0f) : j->alpha[4 * i + 3];
        if (j->rgb) j->rgb[4 * i + 3] = 1.0f;
    }
}

/* Groups first .. first + count - 1 (renderers rs[0 .. count-1]'s last frames) into the XYZ sum; with resolve, the
 * sum then into linear Rec.709 (and rgb for the PNG's tone map). */
static int accumulate(const groups *g, vksky_spectral_sum *sum, uint32_t first, uint32_t count,
                      vksky_renderer *const *rs, float *xyz, size_t pixels, bool resolve, uint16_t *linear, float *rgb)
{
    sum_job job = {.g = g, .first = first, .count = count, .resolve = resolve, .xyz = xyz, .rgb = rgb,
                   .linear = linear};
    if (sum) {   /* the GPU's sum: read back once, after the last group */
        if (!resolve) return 0;
        if (vksky_spectral_sum_get(sum, &job.resolved) != VKSKY_SUCCESS) return 1;
        io_parts_run(pixels, 65536, sum_pixels, &job);
        return 0;
    }
    for (uint32_t n = 0; n < count; ++n) {
        vksky_readback px;
        if (vksky_renderer_get_readback(rs[n], &px) != VKSKY_SUCCESS) return 1;
        job.group_px[n] = job.alpha = px.linear_rgba16f;
    }
    io_parts_run(pixels, 65536, sum_pixels, &job);   /* parts of at least 64 Ki pixels */
    return 0;
}

/* Whether the meter counts the ground's pixels: where the last group lights a ground. */
static bool lit_ground(const groups *g)
{
    for (uint32_t c = 0; c < 3; ++c) {
        vksky_spectral_coefficients k;
        if (vksky_scene_spectral_coefficients(g->scene[g->count - 1], c, &k) == VKSKY_SUCCESS && k.ground_albedo != 0.0)
            return true;
    }
    return false;
}

/* The view the PNG's host tone map reads: auto exposure where a PNG is written and no exposure was given (light.h). */
static sky_view png_view(const options *o)
{
    sky_view view = o->view;
    view.auto_exposure = light_auto_exposure_wanted(o);
    return view;
}

/* A frame: every group rendered and summed into XYZ, then XYZ -> linear Rec.709 into out (and the PNG's tone map).
 * With g->meter_frames each group's bloom-free frame follows its own (the renderer's LUTs as they are: no LUT pass),
 * summed apart into what the PNG's auto exposure meters. */
static int groups_frame(groups *g, const options *o, host_commands *h, spectral_image *out)
{
    *out = (spectral_image){0};
    host_view v = whole_view(o), bare = v;
    vksky_frame_display no_bloom = {.type = VKSKY_STRUCTURE_TYPE_FRAME_DISPLAY,
                                    .tonemap = (vksky_tonemap)o->view.tonemap, .bloom = false};
    bare.display = &no_bloom;
    size_t pixels = (size_t)o->width * o->height;
    bool png = wants_png(o), meter = png && g->meter_frames;
    float *xyz = calloc(pixels * 3, sizeof *xyz);
    /* The meter's sum on the host (VKSKY_SPECTRAL_SUM=host) needs its own XYZ and Rec.709 floats; the GPU's resolved
     * sum is already Rec.709 floats, metered where it is. */
    bool host_meter = meter && !g->meter_sum;
    float *meter_xyz = host_meter ? calloc(pixels * 3, sizeof *meter_xyz) : NULL;
    out->linear = malloc(pixels * 4 * sizeof *out->linear);
    float *rgb = png ? malloc(pixels * 4 * sizeof *rgb) : NULL;
    float *meter_rgb = host_meter ? malloc(pixels * 4 * sizeof *meter_rgb) : NULL;
    if (png) out->display = malloc(pixels * 4);
    if (!xyz || !out->linear || (png && (!rgb || !out->display)) ||
        (host_meter && (!meter_rgb || !meter_xyz))) {
        fprintf(stderr, "vksky: --spectral: out of memory\n");
        free(xyz), free(rgb), free(meter_xyz), free(meter_rgb);
        return 1;
    }
    int status = 0;
    if (g->shared) {   /* one renderer: each group summed before the next one's frame overwrites its readback */
        for (uint32_t k = 0; k < g->count && status == 0 && !stop_requested(); ++k) {
            bool last = k + 1 == g->count;
            status = vksky_renderer_set_scene(g->r[0], g->scene[k]) != VKSKY_SUCCESS ||
                     render_list(g, g->r, k, 1, o, &v, g->sum, h) ||
                     accumulate(g, g->sum, k, 1, g->r, xyz, pixels, last, out->linear, rgb) ||
                     (meter && (render_list(g, g->r, k, 1, o, &bare, g->meter_sum, h) ||
                                (host_meter &&
                                 accumulate(g, NULL, k, 1, g->r, meter_xyz, pixels, last, NULL, meter_rgb))));
        }
    } else {
        status = render_list(g, g->r, 0, g->count, o, &v, g->sum, h) ||
                 accumulate(g, g->sum, 0, g->count, g->r, xyz, pixels, true, out->linear, rgb) ||
                 (meter && (render_list(g, g->r, 0, g->count, o, &bare, g->meter_sum, h) ||
                            (host_meter &&
                             accumulate(g, NULL, 0, g->count, g->r, meter_xyz, pixels, true, NULL, meter_rgb))));
    }
    free(xyz), free(meter_xyz);
    if (status != 0 || stop_requested()) {
        free(rgb), free(meter_rgb);
        return 1;
    }
    if (png) {
        sky_view view = png_view(o);
        spectral_meter m = {0};
        const float *metered = meter_rgb ? meter_rgb : rgb;   /* the bloom-free sum, or the image's (no bloom) */
        if (meter && g->meter_sum && vksky_spectral_sum_get(g->meter_sum, &metered) != VKSKY_SUCCESS) {
            free(rgb);
            return 1;
        }
        if (view.auto_exposure)
            spectral_render_meter_rows(&view, o->width, o->height, 0, o->height, lit_ground(g),
                                       o->atmosphere.bottom_radius, metered, &m);
        spectral_render_tonemap_rows(&view, spectral_render_exposure(&view, &m, 1, g->quiet), o->width, o->height, 0,
                                     rgb, out->display);
    }
    free(rgb), free(meter_rgb);
    return 0;
}

static void print_message(void *user, vksky_severity severity, const char *message)
{
    (void)user, (void)severity;
    fprintf(stderr, "vksky: %s\n", message);
}

/* A frame's files, written on a thread of their own while the next frame renders and sums (issue 27: on the render
 * thread the write was a serial half of every spectral frame). One frame at a time: the next hand-over first joins
 * the frame before, so files are written and lines printed in the frames' order. */
typedef struct frame_write {
    const options *base;
    options f;
    spectral_image img;
    int index, done;
    bool sequence, luts, pending;
    int status;
    pthread_t tid;
} frame_write;

static void *write_frame(void *arg)
{
    frame_write *w = arg;
    frame_ring_pixels px = {w->img.linear, w->img.display};
    char path[PATH_MAX];
    w->status = sequence_write_outputs(&w->f, &px, w->index, w->sequence, path);
    if (w->status == 0 && w->sequence) sequence_frame_line(w->base, w->index, w->done, path, w->luts);
    spectral_image_release(&w->img);
    return NULL;
}

/* Waits for the frame being written, if any: its status (0 when none). */
static int write_join(frame_write *w)
{
    if (!w->pending) return 0;
    pthread_join(w->tid, NULL);
    w->pending = false;
    return w->status;
}

/* A sequence (or --skip-existing) one frame at a time, with an RGB sequence's lines and files (app/runs/sequence.c's
 * sequence_write_outputs, sequence_frame_line, sequence_summary_line), each frame's files written while the next
 * renders. */
static int render_sequence(const options *base, vksky_context *ctx, vksky_scene *scene, host_commands *h, groups *g)
{
    bool sequence = sequence_active(base);
    int count = base->frame_count > 0 ? base->frame_count : 1, done = 0, skipped = 0, lut_computations = 0;
    int range = base->frame_last - base->frame_first + 1, status = 0;
    frame_write w = {.base = base, .sequence = sequence};
    (void)ctx;
    for (int i = base->frame_first; i <= base->frame_last && !stop_requested() && !status; ++i) {   /* stop: between frames */
        options f;
        if (sequence_frame_options(base, i, &f)) {   /* parsed before (sequence_check): not expected */
            status = 1;
            break;
        }
        if (base->skip_existing && sequence_resume_skip(&f, i, count, done + skipped + 1, range)) {
            ++skipped;
            continue;
        }
        const char *names[OPTIONS_MAX_ANIMATE];
        double values[OPTIONS_MAX_ANIMATE];
        int n = sequence_frame_values(base, i, names, values);
        bool luts = false;
        if (vksky_scene_set_values(scene, (uint32_t)n, names, values, print_message, NULL) != VKSKY_SUCCESS ||
            groups_set_scene(g, base, scene, &luts)) {
            status = 1;
            break;
        }
        lut_computations += luts;
        spectral_image img;
        if (groups_frame(g, &f, h, &img)) {
            spectral_image_release(&img);
            status = 1;
            break;
        }
        if ((status = write_join(&w)) != 0) {   /* the frame before is written (its line printed) */
            spectral_image_release(&img);
            break;
        }
        ++done;
        w.f = f, w.img = img, w.index = i, w.done = done + skipped, w.luts = luts;
        if (pthread_create(&w.tid, NULL, write_frame, &w) == 0) w.pending = true;
        else write_frame(&w);   /* no thread: written here */
        status = w.pending ? 0 : w.status;
    }
    int last = write_join(&w);
    if (status || last) return 1;
    if (stop_requested()) return 1;   /* frames already written are whole and stay; stop_status says the rest */
    if (sequence) sequence_summary_line(base, done, skipped, lut_computations);
    return 0;
}

/* A sequence's renderers: one per group on a GPU (each keeps its LUTs; a frame's groups in one submission), one for
 * all on a CPU device (lavapipe compiles every renderer's pipelines, 1.3 s of CPU a 960x540 run for 24 wavelengths,
 * and runs the groups' passes one after another either way: the frame costs the same). VKSKY_SPECTRAL_SHARED=0 or 1
 * chooses (tests: both paths on one device). */
static bool sequence_shared(const vksky_context *ctx)
{
    const char *env = getenv("VKSKY_SPECTRAL_SHARED");
    if (env && (!strcmp(env, "0") || !strcmp(env, "1"))) return env[0] == '1';
    vksky_context_handles k;
    vksky_context_get_handles(ctx, &k);
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(k.physical_device, &p);
    return p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
}

int spectral_host_sequence(const options *o, vksky_context *ctx, vksky_scene *scene, host_commands *h)
{
    groups g = {0};
    int status = groups_create(&g, o, ctx, scene, sequence_shared(ctx), o->height);
    if (status == 0) status = render_sequence(o, ctx, scene, h, &g);
    groups_destroy(&g);
    return status;
}

int spectral_host_render(const options *o, vksky_context *ctx, const vksky_scene *scene, host_commands *h,
                         spectral_image *out)
{
    *out = (spectral_image){0};
    groups g = {0};
    int status = groups_create(&g, o, ctx, scene, true, o->height);
    startup_frame_begin();   /* --timings: the first image (its renderer's figures, its last group's passes) */
    if (status == 0) status = groups_frame(&g, o, h, out);
    if (status == 0 && o->timings) host_timings_frame_end(g.r[0]);
    groups_destroy(&g);
    if (status) spectral_image_release(out);
    return status;
}

/* An image in several bands (app/runs/tiles.c draws them through tiles_render_drawn): a renderer per group of the
 * band's size, each keeping its LUTs from band to band, every group of a band in one submission, the sum on the encode
 * threads into the band's linear image and, with a PNG, its floats tone-mapped on the host into the band's display
 * rows. An auto-exposed PNG is metered first: every band drawn once and its own rows metered in order (the whole
 * image's sum, as groups_frame counts it), nothing written; then drawn again and written at that
 * exposure (the RGB banded meter's two passes, tiles.c). Memory stays a band's: no whole image is kept. */
typedef struct band_draw {
    const options *o;
    groups *g;
    host_commands *h;
    size_t pixels;      /* a band's, pad rows included */
    float *xyz;
    float *rgb;         /* a PNG's: the band's sum as floats, the tone map's input (NULL: no PNG) */
    spectral_image img;
    sky_view view;      /* the PNG's (png_view) */
    double exposure;    /* the PNG's, given or metered (meter_bands) */
} band_draw;

/* The band of view v rendered and summed into d->img.linear (and d->rgb). */
static int sum_band(band_draw *d, const host_view *v)
{
    memset(d->xyz, 0, d->pixels * 3 * sizeof *d->xyz);
    return render_list(d->g, d->g->r, 0, d->g->count, d->o, v, d->g->sum, d->h) ||
           accumulate(d->g, d->g->sum, 0, d->g->count, d->g->r, d->xyz, d->pixels, true, d->img.linear, d->rgb);
}

static int draw_band(void *user, const host_view *v, frame_ring_pixels *out)
{
    band_draw *d = user;
    if (sum_band(d, v)) return 1;
    /* Every row drawn, pad rows too (the writer skips them): the tone map is per pixel. */
    if (d->rgb)
        spectral_render_tonemap_rows(&d->view, d->exposure, d->o->width, (int)(d->pixels / (size_t)d->o->width),
                                     v->first_row, d->rgb, d->img.display);
    *out = (frame_ring_pixels){d->img.linear, d->img.display};
    return 0;
}

/* Auto exposure of a banded PNG: each band's own rows (not its pad rows) metered in the image's row order. */
static int meter_bands(band_draw *d)
{
    const options *o = d->o;
    int band = tiles_band_rows(o->width, o->height, tiles_budget()), pad = tiles_band_pad(o), bands = 0;
    spectral_meter m = {0};
    bool every_pixel = lit_ground(d->g);
    for (int y = 0; y < o->height; y += band, ++bands) {
        if (stop_requested()) return 1;   /* nothing written yet: stop_status says why */
        host_view v = whole_view(o);
        v.band = true, v.first_row = y - pad;
        if (sum_band(d, &v)) return 1;
        spectral_render_meter_rows(&d->view, o->width, o->height, y, o->height - y < band ? o->height - y : band,
                                   every_pixel, o->atmosphere.bottom_radius, d->rgb + (size_t)pad * o->width * 4, &m);
    }
    d->exposure = spectral_render_exposure(&d->view, &m, bands, d->g->quiet);
    return 0;
}

int spectral_host_bands(const options *o, vksky_context *ctx, const vksky_scene *scene, host_commands *h)
{
    groups g = {0};
    int rows = tiles_frame_rows(o), status = groups_create(&g, o, ctx, scene, false, rows);
    bool png = wants_png(o);
    band_draw d = {.o = o, .g = &g, .h = h, .pixels = (size_t)o->width * (size_t)rows, .view = png_view(o)};
    d.exposure = d.view.exposure_ev;
    d.xyz = malloc(d.pixels * 3 * sizeof *d.xyz);
    d.img.linear = malloc(d.pixels * 4 * sizeof *d.img.linear);
    if (png) d.rgb = malloc(d.pixels * 4 * sizeof *d.rgb), d.img.display = malloc(d.pixels * 4);
    if (status == 0 && (!d.xyz || !d.img.linear || (png && (!d.rgb || !d.img.display)))) {
        fprintf(stderr, "vksky: --spectral: out of memory\n");
        status = 1;
    }
    if (status == 0 && png && d.view.auto_exposure) status = meter_bands(&d);
    if (status == 0) status = tiles_render_drawn(o, draw_band, &d);
    free(d.xyz), free(d.rgb);
    spectral_image_release(&d.img);
    groups_destroy(&g);
    return status;
}
