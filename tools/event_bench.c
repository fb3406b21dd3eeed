/* event_bench: a split barrier (vkCmdSetEvent2 ... vkCmdWaitEvents2) against the plain barrier, where independent
 * work sits between a producer and its consumer (issue 29; docs/synchronization.md §11). A benchmark, not a test.
 *
 * Two renderers, each with its own LUTs, in one command buffer:
 *   A  renderer 1's multi-scattering LUT pass (compute: writes ms1)
 *   B  renderer 2's multi-scattering LUT pass (compute: writes ms2; touches nothing of A's or C's)
 *   C  renderer 1's sky-view LUT pass (compute: samples ms1)
 * plain:  A, barrier ms1 (COMPUTE write -> COMPUTE sampled), B, C. The barrier's second scope is every later compute
 *         shader, so B waits for A although it does not need to.
 * split:  A, vkCmdSetEvent2(ms1's dependency), B, vkCmdWaitEvents2(the same), C. Only C waits; B may overlap A.
 * Both orders are recorded as frames of their own, alternated, with GPU timestamps around A..C (warm-up, then
 * medians of N). With --validate (validation + synchronization validation) any message fails the run (exit 1).
 *
 *   event_bench [--validate] [--frames N] [--small]     --small: smaller LUT work (lavapipe)
 * Output: "event_bench device=... plain_gpu_ms=M split_gpu_ms=M plain_wall_ms=M split_wall_ms=M frames=N" */
#include "sky/submit.h"
#include "sky/passes.h"
#include "app/runs/bench_report.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static void renderer(sky_renderer *r, gpu_context *ctx, bool small)
{
    sky_renderer_desc desc = {.width = 16, .height = 16, .readback = true, .display_format = VK_FORMAT_R8G8B8A8_SRGB};
    desc.lut = sky_lut_quality_default();
    if (small) desc.lut.multiscatter_sqrt_dirs = 4, desc.lut.multiscatter_steps = 10;
    sky_renderer_create(r, ctx, &desc);
    model_atmosphere a;
    model_atmosphere_earth(&a);
    sky_renderer_set_atmosphere(r, &a, 0.5 * 0.53 * 3.14159265358979323846 / 180.0);
    sky_view view = sky_view_default();
    frame_desc f = {.view = &view};
    sky_renderer_render(r, &f);   /* the LUTs computed once: every LUT now sampled-readable */
}

/* One frame: the LUT images from their sampled layout to storage (WAR on the last frame's reads), A, the dependency
 * of C on A (a barrier or an event pair), B, C, then back to the sampled layout for the next frame. */
static double frame(gpu_context *ctx, sky_renderer *r1, sky_renderer *r2, VkEvent event, bool split, gpu_timer *t,
                    double *gpu_ms)
{
    VkImageSubresourceRange one = gpu_color_range(0, 1);
    VkCommandBuffer cmd = gpu_begin_commands(ctx);
    gpu_timer_reset(t, cmd);
    gpu_barrier_batch b = gpu_barrier_batch_begin("event bench start");
    gpu_barrier_add_image(&b, "bench.ms1.to_storage", "ms1", r1->luts.multiscatter.image, one,
                          GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
    gpu_barrier_add_image(&b, "bench.ms2.to_storage", "ms2", r2->luts.multiscatter.image, one,
                          GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
    gpu_barrier_add_image(&b, "bench.skyview1.to_storage", "skyview1", r1->luts.skyview.image, one,
                          GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, GPU_USAGE_COMPUTE_STORAGE_WRITE, true);
    gpu_barrier_flush(cmd, &b);
    uint32_t slot = gpu_timer_begin(t, cmd, "A..C");
    luts_record_multiscatter(&r1->luts, cmd, false);                                    /* A */
    /* C samples what A wrote: RAW + GENERAL -> SHADER_READ_ONLY. */
    VkImageMemoryBarrier2 ms1 = gpu_image_barrier(r1->luts.multiscatter.image, one, GPU_USAGE_COMPUTE_STORAGE_WRITE,
                                                  GPU_USAGE_COMPUTE_SAMPLED, false);
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .imageMemoryBarrierCount = 1,
                            .pImageMemoryBarriers = &ms1};
    if (split) vkCmdSetEvent2(cmd, event, &dep);
    else vkCmdPipelineBarrier2(cmd, &dep);
    luts_record_multiscatter(&r2->luts, cmd, false);                                    /* B */
    if (split) vkCmdWaitEvents2(cmd, 1, &event, &dep);
    sky_view view = sky_view_default();
    SkyPush sv = sky_view_skyview_push(&view);
    luts_record_skyview(&r1->luts, cmd, &sv);                                       /* C */
    gpu_timer_end(t, cmd, slot);
    b = gpu_barrier_batch_begin("event bench end");
    gpu_barrier_add_image(&b, "bench.ms2.write_to_sample", "ms2", r2->luts.multiscatter.image, one,
                          GPU_USAGE_COMPUTE_STORAGE_WRITE, GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, false);
    gpu_barrier_add_image(&b, "bench.skyview1.write_to_sample", "skyview1", r1->luts.skyview.image, one,
                          GPU_USAGE_COMPUTE_STORAGE_WRITE, GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, false);
    /* ms1 is SHADER_READ_ONLY for C already; the next frame's to_storage discards it from any layout. */
    gpu_barrier_flush(cmd, &b);
    /* Unsignalled again for the next frame's set, after the barrier above, which orders it after the wait (a reset
     * racing a set or a wait is what synchronization validation reports as SYNC-vkCmdSetEvent2-missingbarrier-reset). */
    if (split) vkCmdResetEvent2(cmd, event, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    double t0 = now_ms();
    gpu_submit_and_wait(ctx, cmd);
    double wall = now_ms() - t0;
    double ms[GPU_TIMER_MAX];
    *gpu_ms = gpu_timer_read(ctx, t, ms) ? ms[0] : -1.0;
    return wall;
}

int main(int argc, char **argv)
{
    bool validate = false, small = false;
    int n = 200;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--validate")) validate = true;
        else if (!strcmp(argv[i], "--small")) small = true;
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc && atoi(argv[i + 1]) > 0) n = atoi(argv[++i]);
        else {
            fprintf(stderr, "event_bench: bad option '%s' (accepted: --validate, --small, --frames N with N > 0)\n",
                    argv[i]);
            return 2;
        }
    }
    gpu_context ctx;
    gpu_context_desc desc = {.validation = validate, .device_index = -1};
    if (gpu_context_create(&ctx, &desc) != 0) return 1;
    sky_renderer r1, r2;
    renderer(&r1, &ctx, small);
    renderer(&r2, &ctx, small);
    VkEventCreateInfo einfo = {.sType = VK_STRUCTURE_TYPE_EVENT_CREATE_INFO,
                               .flags = VK_EVENT_CREATE_DEVICE_ONLY_BIT};
    VkEvent event;
    VK_CHECK(vkCreateEvent(ctx.device, &einfo, NULL, &event));
    gpu_timer t;
    gpu_timer_create(&ctx, &t);
    double *gpu[2] = {calloc((size_t)n, sizeof(double)), calloc((size_t)n, sizeof(double))};
    double *wall[2] = {calloc((size_t)n, sizeof(double)), calloc((size_t)n, sizeof(double))};
    double ignored;
    for (int i = 0; i < 3; ++i) frame(&ctx, &r1, &r2, event, i & 1, &t, &ignored);   /* warm-up */
    for (int i = 0; i < n; ++i)
        for (int split = 0; split < 2; ++split) wall[split][i] = frame(&ctx, &r1, &r2, event, split, &t, &gpu[split][i]);
    printf("event_bench device=\"%s\" plain_gpu_ms=%.4f split_gpu_ms=%.4f plain_wall_ms=%.4f split_wall_ms=%.4f "
           "frames=%d\n", ctx.props.deviceName, bench_median(gpu[0], n), bench_median(gpu[1], n), bench_median(wall[0], n),
           bench_median(wall[1], n), n);
    for (int k = 0; k < 2; ++k) free(gpu[k]), free(wall[k]);
    gpu_timer_destroy(&ctx, &t);
    vkDestroyEvent(ctx.device, event, NULL);
    sky_renderer_destroy(&r1);
    sky_renderer_destroy(&r2);
    gpu_context_destroy(&ctx);
    unsigned messages = gpu_validation_message_count();
    if (messages) fprintf(stderr, "event_bench: validation reported %u message(s)\n", messages);
    return messages ? 1 : 0;
}
