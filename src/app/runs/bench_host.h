/* --bench N, with --render or alone, as a host of include/vksky.h (issue 25 item 1): per-pass GPU medians from
 * vksky_renderer_get_timings, the LUT passes from frames with frame.force_luts, wall and CPU time per frame; then a
 * sequence's frames to disk, timed (app/runs/sequence_host.c). The same lines as app/runs/headless.c's bench: one
 * report (app/runs/bench_report.h). No src/sky or src/lib header (tests/layering_test.sh). */
#ifndef VKSKY_APP_BENCH_HOST_H
#define VKSKY_APP_BENCH_HOST_H
#include <volk.h>
#include <vksky.h>
#include "app/cli/options_struct.h"
#include "app/runs/host_async.h"

/* The benchmark of o's frame with r (made from `scene`), then its sequence, if any, to disk. r is a readback renderer
 * (--render), or (no outputs) a renderer writing the host's own image: the CLI makes an offscreen 8-bit image of r's
 * size and passes it as the frame's target, as a host engine passes its own. async (NULL: none): --async-luts, the
 * LUT passes on the compute queue (app/runs/host_async.h), timed there (vksky_renderer_get_lut_timings).
 * 0 ok, 1 failed. */
int bench_host_run(const options *o, vksky_context *ctx, vksky_scene *scene, vksky_renderer *r, host_async *async);
/* The offscreen image of --bench alone: 8-bit UNORM, a colour attachment and a storage image, so that the renderer
 * (made with BENCH_DISPLAY_CONFIG chained) tone-maps it in a compute dispatch where its post chain is compute (a GPU):
 * the old path's own display image's figures. */
#define BENCH_TARGET_FORMAT VK_FORMAT_R8G8B8A8_UNORM
#define BENCH_TARGET_USAGE (VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT)
#define BENCH_DISPLAY_CONFIG \
    {.type = VKSKY_STRUCTURE_TYPE_DISPLAY_CONFIG, .target_usage = BENCH_TARGET_USAGE, .tonemap_path = VKSKY_TONEMAP_PATH_AUTO}
#endif
