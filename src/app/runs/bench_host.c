/* --bench through the public API (bench_host.h). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "app/runs/bench_host.h"
#include "app/runs/bench_report.h"
#include "app/runs/cpu_time.h"
#include "app/runs/host_ring.h"
#include "app/runs/sequence_frames.h"
#include "app/runs/sequence_host.h"
#include "app/runs/stop.h"
#include "app/scene/light.h"
#include "io/encode_settings.h"
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* The host's own image (--bench without --render): what a host engine's offscreen colour target is to vksky. */
typedef struct bench_target {
    VkDevice device;
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;
    vksky_image use;             /* frame.color */
} bench_target;

static int target_create(bench_target *t, vksky_context *ctx, uint32_t width, uint32_t height)
{
    vksky_context_handles k;
    vksky_context_get_handles(ctx, &k);
    *t = (bench_target){.device = k.device};
    const VkFormat format = BENCH_TARGET_FORMAT;   /* a swapchain's image's size and bytes, storage-capable */
    VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                            .format = format, .extent = {width, height, 1}, .mipLevels = 1, .arrayLayers = 1,
                            .samples = VK_SAMPLE_COUNT_1_BIT, .tiling = VK_IMAGE_TILING_OPTIMAL,
                            .usage = BENCH_TARGET_USAGE};
    if (vkCreateImage(t->device, &ii, NULL, &t->image) != VK_SUCCESS) return 1;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(t->device, t->image, &req);
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(k.physical_device, &mp);
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < mp.memoryTypeCount && type == UINT32_MAX; ++i)
        if ((req.memoryTypeBits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT))
            type = i;
    for (uint32_t i = 0; i < mp.memoryTypeCount && type == UINT32_MAX; ++i)
        if (req.memoryTypeBits & (1u << i)) type = i;
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                               .memoryTypeIndex = type};
    if (type == UINT32_MAX || vkAllocateMemory(t->device, &ai, NULL, &t->memory) != VK_SUCCESS ||
        vkBindImageMemory(t->device, t->image, t->memory, 0) != VK_SUCCESS)
        return 1;
    VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = t->image,
                                .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
                                .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    if (vkCreateImageView(t->device, &vi, NULL, &t->view) != VK_SUCCESS) return 1;
    /* Each frame overwrites every pixel (before: UNDEFINED) after the last frame's tone map wrote it, and leaves it
     * as a host that draws its UI over the sky would take it (a colour attachment, written). */
    t->use = (vksky_image){
        .image = t->image, .view = t->view, .format = format, .extent = {width, height},
        .before = {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                   VK_IMAGE_LAYOUT_UNDEFINED},
        .after = {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                  VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}};
    return 0;
}

static void target_destroy(bench_target *t)
{
    if (!t->device) return;
    if (t->view) vkDestroyImageView(t->device, t->view, NULL);
    if (t->image) vkDestroyImage(t->device, t->image, NULL);
    if (t->memory) vkFreeMemory(t->device, t->memory, NULL);
    *t = (bench_target){0};
}

/* One frame, waited for (its LUTs into the cache on a miss, as every headless frame); its timed passes in t (count in
 * *n: 0 without timestamps); with `luts_on_compute`, the LUT passes' from the compute queue's timer instead. */
static int frame(host_commands *h, vksky_renderer *r, const host_view *v, double *wall, vksky_pass_timing *t,
                 uint32_t *n, bool luts_on_compute)
{
    if (host_commands_render(h, r, v, NULL, wall) || vksky_renderer_store_luts(r) != VKSKY_SUCCESS) return 1;
    vksky_result got = luts_on_compute ? vksky_renderer_get_lut_timings(r, t, BENCH_MAX_PASSES, n)
                                       : vksky_renderer_get_timings(r, t, BENCH_MAX_PASSES, n);
    if (got != VKSKY_SUCCESS || *n > BENCH_MAX_PASSES) *n = 0;
    return 0;
}

/* Per-pass GPU medians, then the frame: the benchmark's output format (app/runs/bench_report.h). */
static int bench(const options *o, host_commands *h, vksky_renderer *r, const vksky_image *target)
{
    int n = o->bench_frames, status = 0;
    bench_figures b;
    if (bench_figures_begin(&b, n)) status = 1;
    vksky_pass_timing t[BENCH_MAX_PASSES];
    uint32_t c = 0;
    /* Warm-up: lavapipe compiles shaders at first use; GPUs ramp their clocks. Auto exposure (--auto-exposure, or a
     * photometric PNG among the outputs): the frames meter on the GPU, and the meter's passes are timed too. */
    host_view v = {.yaw_deg = o->view.yaw_deg, .pitch_deg = o->view.pitch_deg, .fov_deg = o->view.fov_deg,
                   .exposure = o->view.exposure_ev, .auto_exposure = o->auto_exposure || light_auto_exposure_wanted(o),
                   .target = target, .projection = (vksky_projection)o->view.projection,
                   .whole_width = (uint32_t)o->width, .whole_height = (uint32_t)o->height};
    double w;
    for (int i = 0; i < 3 && !stop_requested() && status == 0; ++i) status = frame(h, r, &v, &w, t, &c, false);
    /* LUT passes, measured on their own (a frame recomputes them only when the atmosphere changes). With
     * --async-luts they run on the compute queue, timed on its own timer. The wall time of these frames (each
     * rebuilds the LUTs, as an animated sun does) is tools/async_bench.sh's figure. */
    v.force_luts = true;
    b.async = h->async != NULL;
    for (int i = 0; i < n && !stop_requested() && status == 0; ++i) {
        status = frame(h, r, &v, &b.luts_wall[i], t, &c, b.async);
        for (uint32_t k = 0; k < c; ++k) bench_figures_lut_pass(&b, i, t[k].name, t[k].gpu_ms);
    }
    /* Steady-state frames. The process's CPU time over them too: on a CPU device (lavapipe) that is the frame's
     * work whatever else the machine runs, where wall and timestamp times grow with the machine's load. */
    v.force_luts = false;
    b.cpu_start = process_cpu_ms();
    for (int i = 0; i < n && !stop_requested() && status == 0; ++i) {
        status = frame(h, r, &v, &b.wall[i], t, &c, false);
        b.timed = b.timed && c > 0;
        for (uint32_t k = 0; k < c; ++k) bench_figures_pass(&b, i, t[k].name, t[k].gpu_ms);   /* names: the renderer's */
    }
    bench_report_print(&b, stop_requested() || status ? 0 : n);   /* the graceful stop: no figures from a cut-short run */
    bench_figures_end(&b);
    return status;
}

/* --bench with --render and a sequence (issue 27): the frames to disk, timed from the first frame's submit to the
 * last file (the renderer is warm: bench() ran first). */
static int bench_sequence(const options *o, vksky_context *ctx, vksky_scene *scene, vksky_renderer *r,
                          host_async *async)
{
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    double cpu_start = process_cpu_ms();
    /* --async-luts: one frame at a time, its LUTs on the compute queue (app/runs/sequence_host.c). */
    int status = sequence_host_render(o, ctx, scene, r, async, NULL);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double s = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    int frames = o->frame_last - o->frame_first + 1;
    if (status == 0)
        bench_report_sequence(frames, o->output_count, s, process_cpu_ms() - cpu_start,
                              async ? 0 : host_ring_slots_wanted(), io_encode_threads());
    return status;
}

int bench_host_run(const options *o, vksky_context *ctx, vksky_scene *scene, vksky_renderer *r, host_async *async)
{
    host_commands h;
    bench_target target = {0};
    /* No outputs: the frame writes the host's own image (a renderer without readback). */
    bool own_image = o->output_count == 0;
    int status = host_commands_create(&h, ctx);
    if (status == 0 && own_image && target_create(&target, ctx, (uint32_t)o->width, (uint32_t)o->height)) {
        fprintf(stderr, "vksky: cannot make the benchmark's %dx%d image\n", o->width, o->height);
        status = 1;
    }
    h.async = async;
    if (status == 0) status = bench(o, &h, r, own_image ? &target.use : NULL);
    host_commands_destroy(&h);
    target_destroy(&target);
    if (status == 0 && o->output_count > 0 && sequence_active(o) && !stop_requested())
        status = bench_sequence(o, ctx, scene, r, async);
    return status;
}
