#include "app/runs/headless.h"
#include "app/scene/render_values.h"
#include "app/runs/headless_api.h"
#include "app/runs/sequence.h"
#include "app/runs/sequence_host.h"
#include "app/runs/startup.h"
#include "app/runs/spectral_render.h"
#include "app/runs/spectral_host.h"
#include "app/runs/stop.h"
#include "app/runs/tiles.h"
#include "io/encode_settings.h"
#include "sky/limits.h"
#include "sky/submit.h"
#include "gpu/pipeline_cache.h"
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* VKSKY_FRAMES=N (tests): N frames recorded back to back into one command buffer, the LUTs recomputed in every
 * frame after the first; the last frame is written. Barriers order work across submissions to one queue just as
 * within one command buffer, so this is what the queue sees of frames in flight; synchronization validation,
 * which checks within a command buffer, then also sees each frame's first use of an image after the previous
 * frame's last (the write-after-read barriers that only matter from the second frame on). */
static void render_frames(sky_renderer *r, const frame_desc *f)
{
    /* --timings: the first frame's files are done when the second frame begins (or the run ends). */
    startup_outputs_done();
    startup_frame_begin();
    const char *env = getenv("VKSKY_FRAMES");
    int n = env ? atoi(env) : 1;
    /* --async-luts: each frame is its own pair of submissions (LUTs on the compute queue, the frame on the graphics
     * queue), which synchronization validation checks across submissions and queues. */
    if (n > 1 && r->ctx->compute_queue) {
        for (int i = 0; i < n && i < 16; ++i) {
            frame_desc fi = *f;
            fi.force_luts = f->force_luts || i > 0;
            sky_renderer_render(r, &fi);
        }
        startup_frame_end(r);
        return;
    }
    if (n <= 1) {
        sky_renderer_render(r, f);
        startup_frame_end(r);
        return;
    }
    VkCommandBuffer cmd = gpu_begin_commands(r->ctx);
    for (int i = 0; i < n && i < 16; ++i) {
        frame_desc fi = *f;
        fi.force_luts = f->force_luts || i > 0;
        fi.follows_frame = i > 0;   /* the readback copies' write-after-write: a barrier of frame_record's */
        frame_record(r, cmd, &fi);
    }
    gpu_submit_and_wait(r->ctx, cmd);
    gpu_buffer_invalidate(r->ctx, &r->readback_linear);
    gpu_buffer_invalidate(r->ctx, &r->readback_display);
    startup_frame_end(r);
}

/* The end of every run: the context goes, any validation message fails the run, and a stop asked for by a signal
 * gives its exit status (stop.h). */
static int finish(gpu_context *ctx, int status, bool timings, bool keep)
{
    startup_outputs_done();
    startup_close_cache(ctx);
    if (!keep) gpu_context_destroy(ctx);   /* keep: one image, validation off, left to the exit (startup.h) */
    if (timings) startup_report(stderr);
    unsigned messages = gpu_validation_message_count();
    if (messages) {
        fprintf(stderr, "vksky: validation reported %u message%s\n", messages, messages == 1 ? "" : "s");
        if (status == 0) status = 1;
    }
    return stop_status(status);
}

static int run_checked(const options *o);

/* The runs that go through the public API as its host (app/runs/headless_api.c; docs/library.md's status): one
 * perspective frame to files, sequences and --skip-existing (app/runs/sequence_host.c), --async-luts (the LUTs on the
 * compute queue: app/runs/host_async.c), the tests' VKSKY_FRAMES loop, --timings, --bench with --render or alone (the
 * frame into the host's own image) and with --async-luts (app/runs/bench_host.c), environment maps and
 * images in bands (app/runs/tiles.c; a --bench frame is whole, as before). A frame with no output (its traces) and
 * --spectral still call src/sky here. */
static bool api_host_wanted(const options *o)
{
    return (o->output_count > 0 || o->bench_frames > 0) && (!o->spectral || spectral_host_wanted(o));   /* --bench alone: into the host's image */
}

int headless_run(const options *given)
{
    stop_install();
    /* Refuse bad frames and unwritable outputs before any expensive work (exit 2, nothing written): every frame's
     * options and files, one frame's or a sequence's (whose quality choice may then serve all its frames). A copy of
     * its own: the check may parse the sequence again under that choice. */
    options checked;
    if (options_copy(&checked, given)) return 1;
    int status = sequence_check(&checked) ? 2 : run_checked(&checked);
    options_release(&checked);
    return status;
}

static int run_checked(const options *o)
{
    if (o->output_count > 0 && o->bench_frames == 0 && tiles_wanted(o) && sequence_active(o)) {
        fprintf(stderr, "vksky: --animate/--frame-count/--frame-range: not with an environment map (--projection) or "
                        "an image over the band budget; render such frames one run each\n");
        return 2;
    }
    char why[200];
    if (!gpu_barrier_set_weaken(getenv("VKSKY_WEAKEN_BARRIER"), why, sizeof why)) {
        fprintf(stderr, "vksky: VKSKY_WEAKEN_BARRIER: %s\n", why);
        return 2;
    }
    gpu_context ctx;
    /* VKSKY_ASYNC_ONE_QUEUE=1 (tests): --async-luts on a device with one queue (lavapipe), both submissions on it. */
    const char *one_queue = getenv("VKSKY_ASYNC_ONE_QUEUE");
    gpu_context_desc desc = {.validation = o->validate, .device_index = o->device_index,
                             .async_compute = !o->async_luts ? GPU_ASYNC_OFF
                                              : one_queue && !strcmp(one_queue, "1") ? GPU_ASYNC_ONE_QUEUE
                                                                                    : GPU_ASYNC_ON};
    int rc = gpu_context_create(&ctx, &desc);
    if (rc != 0) return rc == -2 ? 2 : 1;
    if (sky_limits_report(&ctx) != 0) {   /* a limit under the pipelines' need: the line, exit 1 */
        gpu_context_destroy(&ctx);
        return 1;
    }
    startup_open_cache(&ctx, o);
    gpu_barrier_set_drop(getenv("VKSKY_DROP_BARRIER"));
    if (api_host_wanted(o)) {
        /* The device (and its pipeline cache) adopted by a vksky context: the frame through include/vksky.h. */
        vksky_context_desc device = {
            .abi_version = VKSKY_ABI_VERSION, .get_instance_proc_addr = vkGetInstanceProcAddr,
            .instance = ctx.instance, .physical_device = ctx.physical, .device = ctx.device,
            .queue_family = ctx.queue_family, .queue_index = 0, .pipeline_cache = ctx.pipeline_cache,
            /* --async-luts: the compute queue the device was made with (the main queue itself under
             * VKSKY_ASYNC_ONE_QUEUE=1), for vksky_record_luts. */
            .compute_queue = ctx.compute_queue != VK_NULL_HANDLE, .compute_queue_family = ctx.compute_family,
            .compute_queue_index = ctx.compute_index};
        /* What the CLI's device creation enabled: the memory model too where the device has it (single-pass SPD). */
        vksky_device_requirements enabled = {.synchronization2 = true, .dynamic_rendering = true, .maintenance4 = true,
                                             .vulkan_memory_model = ctx.memory_model_device_scope,
                                             .vulkan_memory_model_device_scope = ctx.memory_model_device_scope};
        int status = headless_api_render(o, &device, &enabled, ctx.debug_utils, gpu_cache_dir(&ctx));
        return finish(&ctx, status, o->timings, startup_keep_for_exit(o, status));
    }
    if (o->trace_barriers) gpu_barrier_trace(stdout);

    sky_renderer r;
    render_scene scene;
    render_scene_of(o, &scene);
    render_quality quality = render_quality_of(o);
    sky_renderer_desc rdesc = render_desc(&quality, &scene);
    rdesc.width = (uint32_t)o->width, rdesc.height = (uint32_t)o->height, rdesc.bloom = o->view.bloom;
    rdesc.readback = o->output_count > 0, rdesc.display_format = VK_FORMAT_R8G8B8A8_SRGB;
    rdesc.spectral4 = spectral_render_four_wide(o), rdesc.bloom = rdesc.bloom && !rdesc.spectral4;   /* no bloom there */
    sky_renderer_create(&r, &ctx, &rdesc);
    if (o->trace_passes) gpu_barrier_trace_passes(stdout);

    int status = 0;
    if (stop_requested()) {
        /* Stopped while the device and the renderer were made: nothing to render. */
    } else {
        /* A frame with no output (its traces), or --spectral: each frame once per wavelength group, combined on the
         * host before it is written (the serial loop). */
        if (o->spectral) spectral_render_begin(o, render_frames);
        status = sequence_render(o, &r, o->spectral ? spectral_render_frame : render_frames);
    }
    sky_renderer_destroy(&r);
    return finish(&ctx, status, o->timings, false);
}
